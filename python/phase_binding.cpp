// skinspec.compare_phase (docs/PYTHON.md "Thin-layer phase functions"): measured versus Henyey-Greenstein thin
// layers in the BioSpec skin, as `skinspec compare-phase` compares them (studies/phase_study/phase_comparison.hpp).
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "studies/phase_study/phase_comparison.hpp"

namespace skinspec::python {
namespace {

py::object comparison_object(const PhaseComparison& c, const std::string& hg_source) {
    const auto n = static_cast<py::ssize_t>(c.rows.size());
    std::vector<double> nm, measured, measured_se, hg, hg_se, difference, difference_se;
    std::vector<bool> significant;
    for (const auto& r : c.rows) {
        nm.push_back(r.wavelength_nm);
        measured.push_back(r.measured.value);
        measured_se.push_back(r.measured.stderr);
        hg.push_back(r.hg.value);
        hg_se.push_back(r.hg.stderr);
        difference.push_back(r.difference.value);
        difference_se.push_back(r.difference.stderr);
        significant.push_back(r.significant);
    }
    py::dict d;
    d["material"] = c.material;
    d["quantity"] = c.quantity;
    d["hg_source"] = hg_source;
    d["wavelength_nm"] = to_array(nm, {n});
    d["measured"] = to_array(measured, {n});
    d["measured_stderr"] = to_array(measured_se, {n});
    d["hg"] = to_array(hg, {n});
    d["hg_stderr"] = to_array(hg_se, {n});
    d["difference"] = to_array(difference, {n});
    d["difference_stderr"] = to_array(difference_se, {n});
    d["significant"] = py::array(py::cast(significant));
    d["delta_e2000"] = c.delta_e00 ? py::object(py::float_(*c.delta_e00)) : py::object(py::none());
    d["delta_e2000_uncertainty"] = c.delta_e00_uncertainty ? py::object(py::float_(*c.delta_e00_uncertainty)) : py::object(py::none());
    return result_object("PhaseComparison", d);
}

py::list compare_phase(const py::object& material, const py::object& wavelengths, const std::string& hg_source, const py::object& stderr_target,
                       const py::object& max_rays, const py::object& seed, const py::object& threads, const py::object& progress) {
    const auto skin = material_argument(material, "material");
    const auto* stack = std::get_if<LayerStack>(&skin.material);
    if (!stack) throw InputError("material '" + material_name(skin.material) + "' is homogeneous; compare-phase needs a layered material");
    const auto hg = thin_layer_hg(hg_source, "hg_source");
    SpectralRequest request;
    request.wavelengths = wavelengths.is_none() ? WavelengthGrid::parse(ComparePhaseDefaults::wavelengths, "wavelengths")
                                                : WavelengthGrid::list(finite_vector(wavelengths, "wavelengths"), "wavelengths");
    const double target = one_number(stderr_target, "stderr");
    if (!(target > 0.0)) throw InputError("stderr = " + format_number(target) + " is outside (0, inf)");
    request.stderr_target = target;
    request.max_rays_per_wavelength = whole_number(max_rays, static_cast<double>(minimum_rays_per_wavelength), static_cast<double>(maximum_rays_per_wavelength), "max_rays");
    request.seed = whole_number(seed, 0, 9.223372036854775808e18, "seed");
    const ThreadLimit limit(threads);
    std::vector<PhaseComparison> comparisons;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            auto r = request;
            r.cancel = &cancel;
            r.on_progress = report;
            comparisons = compare_phase_in_skin(*stack, r, hg);
        },
        progress);
    py::list out;
    for (const auto& c : comparisons) out.append(comparison_object(c, hg.source));
    return out;
}

}  // namespace

void bind_phase(py::module_& m) {
    m.def("compare_phase", &compare_phase, R"doc(Measured versus Henyey-Greenstein thin layers, as `skinspec compare-phase` compares them.

    material: a layered skin (Material, preset name or .toml path); wavelengths in nm (default 400-700 every 10);
    hg_source: "rms" (g fitted by
    RMS, Baranoski et al. 2005 Eq. 9), "van-gemert" or a number in [-1, 1]; stderr: the standard-error target of each
    run. Returns two skinspec.PhaseComparison: R of the skin, then T of its stratum corneum and epidermis with no
    reflector below, each with measured, hg and difference (hg - measured) arrays and their standard errors, the
    wavelengths where the difference exceeds 3 standard errors, and for R the CIEDE2000 colour difference.)doc",
          py::arg("material") = "biospec-moderately", py::arg("wavelengths") = py::none(), py::kw_only(),
          py::arg("hg_source") = ComparePhaseDefaults::hg_source, py::arg("stderr") = ComparePhaseDefaults::stderr_target,
          py::arg("max_rays") = ComparePhaseDefaults::max_rays, py::arg("seed") = 1, py::arg("threads") = py::none(),
          py::arg("progress") = py::none());
}

}  // namespace skinspec::python
