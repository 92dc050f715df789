// skinspec.swatch (docs/PYTHON.md "Swatch charts"): the colours of a material over one or two swept fields, each
// patch to a colour tolerance, as `skinspec swatch` computes them (appearance/swatch_chart.hpp), as numpy arrays.
#include <limits>

#include <pybind11/stl.h>

#include "appearance/swatch_chart.hpp"
#include "python/bindings.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/skin_tone.hpp"

namespace skinspec::python {
namespace {

py::dict swatch(const std::string& material, const py::object& vary, const py::object& set, double delta_e, const std::string& illuminant,
                const std::string& observer, const std::string& solver, const py::object& seed, const py::object& max_rays, const std::string& geometry,
                const std::string& space, const py::object& threads, const py::object& progress) {
    SwatchRequest request;
    request.material = material;
    if (!set.is_none()) {
        if (!py::isinstance<py::dict>(set)) throw InputError("set: expected a dict {field: value}");
        for (const auto& [key, value] : set.cast<py::dict>()) {
            request.overrides.push_back(parse_override(py::str(key).cast<std::string>() + "=" + py::str(value).cast<std::string>()));
        }
    }
    if (vary.is_none()) request.sweeps = default_swatch_sweeps(load_material(request.material, request.overrides));
    else {
        for (const auto& text : name_list(vary, "vary")) request.sweeps.push_back(parse_sweep(text));
    }
    request.illuminant = parse_illuminant(illuminant, "illuminant");
    request.observer = parse_observer(observer, "observer");
    request.delta_e = delta_e;
    request.solver = std::string(find_solver(solver).name());
    request.geometry = parse_measurement_geometry(geometry, "geometry");
    if (!seed.is_none()) {
        request.seed = whole_number(seed, 0, 9.223372036854775808e18, "seed");
        request.sampling_options.push_back("seed");
    }
    if (!max_rays.is_none()) {
        request.max_rays_per_wavelength = whole_number(max_rays, 1, 1.125899906842624e15, "max_rays");
        request.sampling_options.push_back("max_rays");
    }
    const auto& cm = ColorManagement::builtin();
    const std::string chosen_space = cm.canonical_space(space, "space");
    const ThreadLimit limit(threads);
    SwatchChart chart;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            auto r = request;
            r.cancel = &cancel;
            r.on_progress = [&report](std::size_t done, std::size_t total) { report(Progress{0, 0, done, total}); };
            chart = compute_swatch(r);
        },
        progress);
    const auto rows = static_cast<py::ssize_t>(chart.rows), columns = static_cast<py::ssize_t>(chart.columns);
    const auto n = static_cast<py::ssize_t>(chart.wavelengths.size());
    std::vector<double> xyz, lab, rgb, reflectance, reflectance_se, uncertainty, ita, rays, parameters;
    std::vector<std::string> category;
    for (const auto& p : chart.patches) {
        xyz.insert(xyz.end(), {p.xyz.X, p.xyz.Y, p.xyz.Z});
        lab.insert(lab.end(), {p.lab.L, p.lab.a, p.lab.b});
        const auto c = cm.from_xyz(p.xyz, chart.white, chosen_space);
        rgb.insert(rgb.end(), c.begin(), c.end());
        reflectance.insert(reflectance.end(), p.reflectance.begin(), p.reflectance.end());
        reflectance_se.insert(reflectance_se.end(), p.reflectance_stderr.begin(), p.reflectance_stderr.end());
        uncertainty.push_back(p.uncertainty.delta_e2000);
        const auto tone = skin_tone(p.lab);  // none where b* does not define the angle
        ita.push_back(tone ? tone->ita_deg : std::numeric_limits<double>::quiet_NaN());
        category.emplace_back(tone ? std::string(to_string(tone->category)) : std::string());
        rays.push_back(static_cast<double>(p.rays));
        parameters.insert(parameters.end(), p.parameters.begin(), p.parameters.end());
    }
    py::dict d;
    std::vector<std::string> fields;
    for (const auto& s : request.sweeps) fields.push_back(s.field);
    d["material"] = material;
    d["solver"] = request.solver;
    d["fields"] = fields;
    d["shape"] = py::make_tuple(rows, columns);
    d["partial"] = chart.partial;
    d["wavelength_nm"] = to_array(std::vector<double>(chart.wavelengths.nm().begin(), chart.wavelengths.nm().end()), {n});
    if (!chart.partial) {
        const auto sweeps = static_cast<py::ssize_t>(request.sweeps.size());
        d["parameters"] = to_array(parameters, {rows, columns, sweeps});
        d["XYZ"] = to_array(xyz, {rows, columns, 3});
        d["Lab"] = to_array(lab, {rows, columns, 3});
        d["rgb"] = to_array(rgb, {rows, columns, 3});
        d["reflectance"] = to_array(reflectance, {rows, columns, n});
        d["reflectance_stderr"] = to_array(reflectance_se, {rows, columns, n});
        d["delta_e2000_uncertainty"] = to_array(uncertainty, {rows, columns});
        d["ita_deg"] = to_array(ita, {rows, columns});
        d["category"] = category;
        d["rays"] = to_array(rays, {rows, columns});
    }
    d["space"] = chosen_space;
    d["white_XYZ"] = to_array({chart.white.X, chart.white.Y, chart.white.Z}, {3});
    return d;
}

}  // namespace

void bind_swatch(py::module_& m) {
    m.def("swatch", &swatch, R"doc(The colours of a material over one or two swept fields, as `skinspec swatch` computes them (no image is written).

    material: a preset name or .toml path; vary: "FIELD=FIRST:LAST:STEPS[:log]" strings (first: columns, second:
    rows; default for a skin: melanosome fraction 0.01-0.42 in 8 log steps by dermal blood 0.002-0.05 in 5); set:
    {field: value} overrides; delta_e: each patch's CIEDE2000 uncertainty target; space: the colour space of the
    "rgb" array (linear working-space values, white = 1). Returns a dict of (rows, columns, ...) numpy arrays:
    parameters, XYZ, Lab, rgb, reflectance and its stderr per wavelength, delta_e2000_uncertainty, ita_deg, category.)doc",
          py::arg("material") = "biospec-moderately", py::arg("vary") = py::none(), py::kw_only(), py::arg("set") = py::none(),
          py::arg("delta_e") = SwatchRequest{}.delta_e, py::arg("illuminant") = "D65", py::arg("observer") = "2", py::arg("solver") = "biospec",
          py::arg("seed") = py::none(), py::arg("max_rays") = py::none(), py::arg("geometry") = "sci", py::arg("space") = "ACEScg",
          py::arg("threads") = py::none(), py::arg("progress") = py::none());
}

}  // namespace skinspec::python
