// skinspec.fit_profile, fit_profile_image, fit_profile_patches (docs/PYTHON.md "Fitting"): dipole parameters of a
// radial profile R(r), of an image pair with known light or of a patch list, as `skinspec fit-profile` fits them
// (inverse/profile_fit/profile_fit.hpp; the report is declared there once; formats/profile_inputs.hpp for inputs).
#include <array>

#include <pybind11/stl.h>

#include "formats/profile_inputs.hpp"
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

// The dipole search as fit-profile's options set it (the CLI's defaults when None).
ProfileFitOptions fit_options(double eta, const py::object& grid_scattering, const py::object& grid_absorption, bool refine,
                              const py::object& total_reflectance, double fit_from_mm) {
    ProfileFitOptions options;
    options.dipole.eta = eta;
    options.dipole.reduced_scattering_per_mm = grid_argument(grid_scattering, options.dipole.reduced_scattering_per_mm, "grid_scattering");
    options.dipole.absorption_per_mm = grid_argument(grid_absorption, options.dipole.absorption_per_mm, "grid_absorption");
    options.dipole.refine = refine;
    if (!total_reflectance.is_none()) options.dipole.total_diffuse_reflectance = one_number(total_reflectance, "total_reflectance");
    options.fit_from_mm = fit_from_mm;
    return options;
}

template <class Fit>
ProfileFitReport run_fit(const Fit& fit) {
    ProfileFitReport report;
    run_interruptible([&](const CancelFlag&, const std::function<void(const Progress&)>&) { report = fit(); }, py::none());
    return report;
}

py::dict report_object(const ProfileFitReport& report, const std::string& channel) {
    py::dict out = json_object(profile_fit_json(report, channel));
    out["fitted_profile_per_mm2"] = to_array(report.fitted_profile, {static_cast<py::ssize_t>(report.fitted_profile.size())});
    return out;
}

py::object fit_profile(const py::object& radii_mm, const py::object& profile_per_mm2, double eta, const py::object& grid_scattering,
                       const py::object& grid_absorption, bool refine, const py::object& total_reflectance, double fit_from_mm) {
    const auto options = fit_options(eta, grid_scattering, grid_absorption, refine, total_reflectance, fit_from_mm);
    const auto r = finite_vector(radii_mm, "radii_mm"), profile = finite_vector(profile_per_mm2, "profile_per_mm2");
    if (r.size() != profile.size()) throw InputError("profile_per_mm2: " + std::to_string(profile.size()) + " values for " + std::to_string(r.size()) + " radii");
    return report_object(run_fit([&] { return fit_radial(r, profile, options); }), "R");
}

// (height, width) or (height, width, channels) as one row-major vector per channel (at most 3: alpha ignored).
std::vector<std::vector<double>> image_channels(const py::object& value, std::string_view what, py::ssize_t& height, py::ssize_t& width) {
    const auto a = finite_array(value, what);
    if (a.ndim() != 2 && a.ndim() != 3) throw InputError(std::string(what) + ": expected an array (height, width) or (height, width, channels)");
    height = a.shape(0);
    width = a.shape(1);
    const py::ssize_t channels = a.ndim() == 3 ? a.shape(2) : 1;
    std::vector<std::vector<double>> out(static_cast<std::size_t>(std::min<py::ssize_t>(channels, 3)));
    const double* data = a.data();
    for (py::ssize_t p = 0; p < height * width; ++p) {
        for (std::size_t c = 0; c < out.size(); ++c) out[c].push_back(data[p * channels + static_cast<py::ssize_t>(c)]);
    }
    return out;
}

py::list fit_profile_image(const py::object& irradiance, const py::object& exitance, double pitch_mm, const py::object& mask, double step_mm,
                           double tikhonov, bool non_negative, double eta, const py::object& grid_scattering, const py::object& grid_absorption,
                           bool refine, const py::object& total_reflectance, double fit_from_mm) {
    auto options = fit_options(eta, grid_scattering, grid_absorption, refine, total_reflectance, fit_from_mm);
    options.step_mm = step_mm;
    options.solve = {tikhonov, non_negative};
    std::vector<PlanarScene> scenes;
    std::vector<std::string> names;
    if (is_path(irradiance)) {
        const auto path = [](const py::object& v, std::string_view what) { return v.is_none() ? std::string() : path_argument(v, what).string(); };
        scenes = read_planar_scenes({path(irradiance, "irradiance"), path(exitance, "exitance"), path(mask, "mask"), pitch_mm}, names);
    } else {
        py::ssize_t h = 0, w = 0, he = 0, we = 0;
        const auto e = image_channels(irradiance, "irradiance", h, w);
        const auto l = image_channels(exitance, "exitance", he, we);
        if (he != h || we != w || l.size() != e.size()) throw InputError("exitance: its shape differs from irradiance's");
        std::vector<char> valid(static_cast<std::size_t>(h * w), 1);
        if (!mask.is_none()) {
            py::ssize_t hm = 0, wm = 0;
            const auto m = image_channels(mask, "mask", hm, wm);
            if (hm != h || wm != w) throw InputError("mask: its shape differs from irradiance's");
            for (std::size_t p = 0; p < valid.size(); ++p) valid[p] = m.front()[p] > 0.0 ? 1 : 0;
        }
        for (std::size_t c = 0; c < e.size(); ++c) {
            scenes.push_back(planar_scene(static_cast<int>(w), static_cast<int>(h), pitch_mm, e[c], l[c], valid));
            names.push_back(e.size() == 1 ? "Y" : std::string(1, "RGB"[c]));
        }
    }
    py::list out;
    for (std::size_t c = 0; c < scenes.size(); ++c) {
        const auto report = run_fit([&] { return fit_planar(scenes[c], options); });
        auto d = report_object(report, names[c]);
        d["synthesised"] = to_array(report.synthesised, {scenes[c].height, scenes[c].width});
        out.append(d);
    }
    return out;
}

py::dict fit_profile_patches(const py::object& patches, double step_mm, double tikhonov, bool non_negative, double eta,
                             const py::object& grid_scattering, const py::object& grid_absorption, bool refine, const py::object& total_reflectance,
                             double fit_from_mm) {
    auto options = fit_options(eta, grid_scattering, grid_absorption, refine, total_reflectance, fit_from_mm);
    options.step_mm = step_mm;
    options.solve = {tikhonov, non_negative};
    std::vector<SurfacePatch> list;
    if (is_path(patches)) {
        list = read_patch_list(path_argument(patches, "patches").string());
    } else {
        const auto a = finite_array(patches, "patches");
        if (a.ndim() != 2 || a.shape(1) != 9) throw InputError("patches: expected an array (patches, 9): x_mm, y_mm, z_mm, nx, ny, nz, c, l, visible");
        for (py::ssize_t i = 0; i < a.shape(0); ++i) {
            std::array<double, 9> v{};
            for (std::size_t k = 0; k < 9; ++k) v[k] = a.data()[i * 9 + static_cast<py::ssize_t>(k)];
            list.push_back(surface_patch(v, "patches row " + std::to_string(i)));
        }
    }
    const auto report = run_fit([&] { return fit_patches(list, options); });
    auto d = report_object(report, "l");
    d["synthesised"] = to_array(report.synthesised, {static_cast<py::ssize_t>(report.synthesised.size())});
    return d;
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
    m.def("fit_profile_image", &fit_profile_image, R"doc(Dipole parameters per colour channel of a flat sample under known light, as `skinspec fit-profile --irradiance --exitance` fits them (Mukaigawa et al. 2009).

    irradiance, exitance: arrays (height, width) or (height, width, channels) of the irradiance entering the surface
    and the observed exitance pi L_o / F_t, both per mm^2 (at most three channels; a fourth is ignored), or the two
    image files the command reads; pitch_mm: the pixel pitch; mask: non-zero where the exitance is used; step_mm:
    the distance bins; tikhonov, non_negative: the profile estimate's regularisation; the dipole search as
    fit_profile. Returns one dict per channel: fit_profile's, with the estimated profile per bin (distance_mm,
    profile_estimate_per_mm2), psnr_db and the re-synthesised exitance (height, width).)doc",
          py::arg("irradiance"), py::arg("exitance"), py::arg("pitch_mm"), py::kw_only(), py::arg("mask") = py::none(),
          py::arg("step_mm") = ProfileFitOptions{}.step_mm, py::arg("tikhonov") = 0.0, py::arg("non_negative") = false,
          py::arg("eta") = DipoleFitOptions{}.eta, py::arg("grid_scattering") = py::none(), py::arg("grid_absorption") = py::none(),
          py::arg("refine") = true, py::arg("total_reflectance") = py::none(), py::arg("fit_from_mm") = 0.0);
    m.def("fit_profile_patches", &fit_profile_patches, R"doc(Dipole parameters from surface patches with known light, as `skinspec fit-profile --patches` fits them.

    patches: an array (patches, 9) of x_mm, y_mm, z_mm, nx, ny, nz, c (power entering), l (exitance per mm^2),
    visible (0 or 1), or the patch-list CSV the command reads; the rest as fit_profile_image. Returns fit_profile's
    dict with the estimated profile per bin and the re-synthesised exitance per patch.)doc",
          py::arg("patches"), py::kw_only(), py::arg("step_mm") = ProfileFitOptions{}.step_mm, py::arg("tikhonov") = 0.0,
          py::arg("non_negative") = false, py::arg("eta") = DipoleFitOptions{}.eta, py::arg("grid_scattering") = py::none(),
          py::arg("grid_absorption") = py::none(), py::arg("refine") = true, py::arg("total_reflectance") = py::none(), py::arg("fit_from_mm") = 0.0);
}

}  // namespace skinspec::python
