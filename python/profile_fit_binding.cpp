// skinspec.fit_profile (docs/PYTHON.md "Fitting"): dipole parameters of a radial profile R(r), as `skinspec
// fit-profile --profile` fits one (inverse/profile_fit/profile_fit.hpp; the report is declared there once).
#include "inverse/profile_fit/profile_fit.hpp"
#include "python/bindings.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::python {
namespace {

ParameterGrid grid_argument(const py::object& value, const ParameterGrid& fallback, const std::string& what) {
    if (value.is_none()) return fallback;
    const auto v = finite_vector(value, what);
    if (v.size() != 3) throw InputError(what + ": expected (first, last, step) in 1/mm");
    return {v[0], v[1], v[2]};
}

py::object fit_profile(const py::object& radii_mm, const py::object& profile_per_mm2, double eta, const py::object& grid_scattering,
                       const py::object& grid_absorption, bool refine, const py::object& total_reflectance, double fit_from_mm) {
    ProfileFitOptions options;
    options.dipole.eta = eta;
    options.dipole.reduced_scattering_per_mm = grid_argument(grid_scattering, options.dipole.reduced_scattering_per_mm, "grid_scattering");
    options.dipole.absorption_per_mm = grid_argument(grid_absorption, options.dipole.absorption_per_mm, "grid_absorption");
    options.dipole.refine = refine;
    if (!total_reflectance.is_none()) options.dipole.total_diffuse_reflectance = one_number(total_reflectance, "total_reflectance");
    options.fit_from_mm = fit_from_mm;
    const auto r = finite_vector(radii_mm, "radii_mm"), profile = finite_vector(profile_per_mm2, "profile_per_mm2");
    if (r.size() != profile.size()) throw InputError("profile_per_mm2: " + std::to_string(profile.size()) + " values for " + std::to_string(r.size()) + " radii");
    ProfileFitReport report;
    run_interruptible([&](const CancelFlag&, const std::function<void(const Progress&)>&) { report = fit_radial(r, profile, options); }, py::none());
    auto out = json_object(profile_fit_json(report, "R"));
    out["fitted_profile_per_mm2"] = to_array(report.fitted_profile, {static_cast<py::ssize_t>(report.fitted_profile.size())});
    return out;
}

}  // namespace

void bind_profile_fit(py::module_& m) {
    m.def("fit_profile", &fit_profile, R"doc(Dipole sigma_s' and sigma_a (1/mm) of a radial profile, as `skinspec fit-profile --profile` fits it.

    radii_mm, profile_per_mm2: R(r) per unit power entering the skin (a skinspec.profiles result is per unit
    incident power: divide it by 1 - R_specular); eta: relative refractive index; grid_scattering,
    grid_absorption: the search grids (first, last, step) in 1/mm (default 0.01-3 by 0.01 and 0-0.01 by 0.001);
    refine: a local optimiser after the grid; total_reflectance: a measured total diffuse reflectance that
    constrains sigma_a (Jensen et al. 2001 Sec. 3); fit_from_mm: radii left out below it. Returns the dict
    fit-profile --json gives per channel (at_bounds lists parameters that ended on an edge of the search) and
    fitted_profile_per_mm2.)doc",
          py::arg("radii_mm"), py::arg("profile_per_mm2"), py::kw_only(), py::arg("eta") = DipoleFitOptions{}.eta, py::arg("grid_scattering") = py::none(),
          py::arg("grid_absorption") = py::none(), py::arg("refine") = true, py::arg("total_reflectance") = py::none(), py::arg("fit_from_mm") = 0.0);
}

}  // namespace skinspec::python
