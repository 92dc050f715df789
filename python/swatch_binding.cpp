// skinspec.swatch (docs/PYTHON.md "Swatch charts"): the colours of a material over one or two swept fields, each
// patch to a colour tolerance, as `skinspec swatch` computes them (appearance/swatch_chart.hpp), as numpy arrays.
#include <limits>

#include <pybind11/stl.h>

#include "appearance/lit_swatch.hpp"
#include "appearance/profile_shape_report.hpp"
#include "appearance/swatch_files.hpp"
#include "python/bindings.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/skin_tone.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::python {
namespace {

py::dict swatch(const std::string& material, const py::object& vary, const py::object& set, double delta_e, const std::string& illuminant,
                const std::string& observer, const std::string& solver, const py::object& seed, const py::object& max_rays, const std::string& geometry,
                const std::string& space, const py::object& output, bool half, const std::string& display, const std::string& view, int patch_size,
                bool overwrite, const py::object& threads, const py::object& progress, const py::kwargs& switches) {
    auto request = swatch_request_argument(material, set, delta_e, illuminant, observer, solver, seed, max_rays, geometry, switches);
    if (vary.is_none()) request.sweeps = default_swatch_sweeps(load_material(request.material, request.overrides));
    else {
        for (const auto& text : name_list(vary, "vary")) request.sweeps.push_back(parse_sweep(text));
    }
    const auto files = check_swatch_files(SwatchFiles{{output_paths(output, "output"), space, half, display, view, overwrite}, patch_size}, request);
    const auto chart = compute_swatch_interruptible(request, threads, progress);
    write_swatch_files(chart, request, files);
    auto d = swatch_dict(chart, request, files.images.space);
    std::vector<std::string> written;
    for (const auto& f : files.images.files) written.push_back(f.string());
    d["files"] = written;
    return d;
}

// The lighting of a lit swatch: "spot", "edge", or "pattern" with `pattern` an array (height, width) of relative
// irradiance, (height, width, 3) linear Rec.709, or an image file.
Illumination lighting_argument(const std::string& lighting, const py::object& pattern, double spot_radius_mm, PatchGeometry& view) {
    if (lighting != "spot" && lighting != "edge" && lighting != "pattern") {
        throw InputError("lighting: '" + lighting + "' is not a lighting (allowed: spot, edge, pattern)");
    }
    if ((lighting == "pattern") == pattern.is_none()) throw InputError("pattern: give it with lighting=\"pattern\" (and only then)");
    if (lighting == "spot") return Illumination::spot(spot_radius_mm);
    if (lighting == "edge") return Illumination::edge();
    const auto& cm = ColorManagement::builtin();
    if (is_path(pattern)) return pattern_lighting(read_linear_image(path_argument(pattern, "pattern"), "Linear Rec.709", cm), view);
    const auto a = finite_array(pattern, "pattern");
    if (!(a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 3))) throw InputError("pattern: expected an array (height, width) or (height, width, 3)");
    LinearImage image{static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), {}};
    for (py::ssize_t p = 0; p < a.shape(0) * a.shape(1); ++p) {
        for (int c = 0; c < 3; ++c) image.rgb.push_back(static_cast<float>(a.data()[a.ndim() == 2 ? p : 3 * p + c]));
    }
    return pattern_lighting(image, view);
}

py::dict lit_swatch(const py::object& material, const std::string& lighting, const py::object& pattern, double field_mm, int pixels,
                    double spot_radius_mm, const py::object& wavelengths, const py::object& mode, const std::string& illuminant,
                    const std::string& observer, const std::string& space, const py::object& output, bool half, const std::string& display,
                    const std::string& view_name, bool overwrite, const py::object& progress, const py::object& rays, const py::object& stderr_target,
                    const py::object& max_rays, const py::object& seed, const std::string& geometry, const py::kwargs& switches) {
    const auto skin = material_argument(material, "material");
    auto view = lit_view(field_mm, pixels);
    const auto files = check_image_outputs(ImageOutputs{output_paths(output, "output"), space, half, display, view_name, overwrite});
    const auto& solver = profile_solver_argument(mode);
    check_overrides(solver, skin.material, skin.overrides);
    const auto light = lighting_argument(lighting, pattern, spot_radius_mm, view);
    const auto grid = wavelength_argument(wavelengths);
    const auto solver_settings = solver_switches(switches);
    ProfileRequest settings;
    settings.switches = solver_settings;
    apply_profile_sampling({rays, stderr_target, max_rays, seed}, settings);
    LitSwatch swatch;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            swatch = render_lit_swatch(skin.material, grid, light, view, solver, settings, parse_measurement_geometry(geometry, "geometry"), parse_illuminant(illuminant, "illuminant"),
                                       parse_observer(observer, "observer"), files.space,
                                       [&report](std::size_t done, std::size_t total) { report(Progress{0, 0, done, total}); }, &cancel);
        },
        progress);
    const auto shape = stated_profile_shape_interruptible(solver, skin.material, grid, solver_settings);
    std::string wavelengths_text;
    for (const double nm : grid.nm()) wavelengths_text += (wavelengths_text.empty() ? "" : ",") + format_number(nm);
    write_lit_swatch(swatch, material_name(skin.material), light, field_mm, wavelengths.is_none() ? "400:700:10" : wavelengths_text, files,
                     profile_shape_text(shape));
    const auto& patch = swatch.patch;
    const auto h = static_cast<py::ssize_t>(view.height_px), w = static_cast<py::ssize_t>(view.width_px);
    std::vector<double> exitance;
    std::vector<std::string> labels;
    for (std::size_t c = 0; c < patch.exitance.size(); ++c) {
        exitance.insert(exitance.end(), patch.exitance[c].begin(), patch.exitance[c].end());
        labels.push_back(patch.profiles.channels[c].label);
    }
    std::vector<std::string> written;
    for (const auto& f : files.files) written.push_back(f.string());
    py::dict d;
    d["material"] = material_name(skin.material);
    d["model"] = patch.profiles.model;
    d["lighting"] = light.description();
    d["rgb"] = to_array(std::vector<double>(swatch.image.rgb.begin(), swatch.image.rgb.end()), {h, w, 3});
    d["space"] = files.space;
    d["exitance"] = to_array(exitance, {static_cast<py::ssize_t>(labels.size()), h, w});
    d["labels"] = labels;
    d["wavelength_nm"] = swatch.bands ? py::object(py::none())
                                      : py::object(to_array(std::vector<double>(grid.nm().begin(), grid.nm().end()), {static_cast<py::ssize_t>(grid.size())}));
    d["pixel_mm"] = view.pixel_mm;
    d["shape"] = profile_shape_object(solver, skin.material, shape);
    d["kernel_reach_mm"] = patch.kernel_radius_px * view.pixel_mm;
    d["largest_kernel_correction"] = patch.largest_kernel_correction;
    d["geometry"] = std::string(to_string(patch.geometry_measured));
    d["precision"] = profile_precision_line(patch.profiles);
    d["files"] = written;
    d["warnings"] = summarise_warnings(patch.profiles.warnings);
    return d;
}

}  // namespace

SwatchRequest swatch_request_argument(const std::string& material, const py::object& set, double delta_e, const std::string& illuminant,
                                      const std::string& observer, const std::string& solver, const py::object& seed, const py::object& max_rays,
                                      const std::string& geometry, const py::kwargs& switches) {
    SwatchRequest request;
    request.material = material;
    request.switches = solver_switches(switches);
    if (!set.is_none()) {
        if (!py::isinstance<py::dict>(set)) throw InputError("set: expected a dict {field: value}");
        for (const auto& [key, value] : set.cast<py::dict>()) {
            request.overrides.push_back(parse_override(py::str(key).cast<std::string>() + "=" + py::str(value).cast<std::string>()));
        }
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
        request.max_rays_per_wavelength = whole_number(max_rays, static_cast<double>(minimum_rays_per_wavelength), static_cast<double>(maximum_rays_per_wavelength), "max_rays");
        request.sampling_options.push_back("max_rays");
    }
    return request;
}

SwatchChart compute_swatch_interruptible(const SwatchRequest& request, const py::object& threads, const py::object& progress) {
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
    return chart;
}

py::dict swatch_dict(const SwatchChart& chart, const SwatchRequest& request, const std::string& space) {
    const auto& cm = ColorManagement::builtin();
    const auto rows = static_cast<py::ssize_t>(chart.rows), columns = static_cast<py::ssize_t>(chart.columns);
    const auto n = static_cast<py::ssize_t>(chart.wavelengths.size());
    std::vector<double> xyz, lab, rgb, reflectance, reflectance_se, uncertainty, ita, rays, parameters;
    std::vector<std::string> category;
    for (const auto& p : chart.patches) {
        xyz.insert(xyz.end(), {p.xyz.X, p.xyz.Y, p.xyz.Z});
        lab.insert(lab.end(), {p.lab.L, p.lab.a, p.lab.b});
        const auto c = cm.from_xyz(p.xyz, chart.white, space);
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
    d["material"] = request.material;
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
    d["space"] = space;
    d["white_XYZ"] = to_array({chart.white.X, chart.white.Y, chart.white.Z}, {3});
    return d;
}

void bind_swatch(py::module_& m) {
    m.def("lit_swatch", &lit_swatch, R"doc(One flat patch of a material under structured light, as `skinspec swatch --lit` renders it (radial profiles convolved with the light).

    material: a skinspec.Material, preset name or .toml path; lighting: "spot" (a lit disc of spot_radius_mm),
    "edge" (lit for x > 0) or "pattern" with pattern= an array (height, width) of relative irradiance, (height,
    width, 3) linear Rec.709, or an image file (the view takes its aspect); field_mm: the view's width; pixels: its
    width in pixels, [8, 4096]; wavelengths: nm (default 400-700 every 10); mode: a solver that computes profiles
    (default None: rte, the exact transport; rays, stderr, max_rays, seed as skinspec.profiles takes them; or a diffusion
    mode) with its switches as keywords; geometry: "sce" (default, the light from inside) or "sci" (with the first-surface
    reflection where the light falls); space: the working space of "rgb"; output: a file or a list
    (.exr linear; .png, .tif display-referred through display / view), checked before any work. Returns rgb
    (height, width, 3), exitance per channel (channels, height, width; diffuse exitance per unit irradiance, no
    specular), labels, wavelength_nm, pixel_mm, kernel_reach_mm, largest_kernel_correction, files and warnings.)doc",
          py::arg("material"), py::arg("lighting") = "spot", py::kw_only(), py::arg("pattern") = py::none(), py::arg("field_mm") = 20.0,
          py::arg("pixels") = 256, py::arg("spot_radius_mm") = 2.0, py::arg("wavelengths") = py::none(), py::arg("mode") = py::none(),
          py::arg("illuminant") = "D65", py::arg("observer") = "2", py::arg("space") = "ACEScg", py::arg("output") = py::none(),
          py::arg("half") = false, py::arg("display") = "sRGB", py::arg("view") = "Standard", py::arg("overwrite") = false,
          py::arg("progress") = py::none(), py::arg("rays") = py::none(), py::arg("stderr") = py::none(), py::arg("max_rays") = py::none(),
          py::arg("seed") = py::none(), py::arg("geometry") = std::string(to_string(image_geometry)));
    m.def("swatch", &swatch, R"doc(The colours of a material over one or two swept fields, as `skinspec swatch` computes them (the chart image too when `output` is given).

    material: a preset name or .toml path; vary: "FIELD=FIRST:LAST:STEPS[:log]" strings (first: columns, second:
    rows; default for a skin: melanosome fraction 0.01-0.42 in 8 log steps by dermal blood 0.002-0.05 in 5); set:
    {field: value} overrides; delta_e: each patch's CIEDE2000 uncertainty target; mode: the solver (as --mode; default the
    BioSpec walk); space: the colour space of the
    "rgb" array (linear working-space values, white = 1); output: also the chart image, one path or a list (.exr
    linear in `space`; .png, .tif display-referred through display / view, with labelled axes), patch_size in pixels,
    checked before any work; the solver's switches as keywords (e.g. channels=16). Returns a dict of (rows, columns,
    ...) numpy arrays: parameters, XYZ, Lab, rgb, reflectance and its stderr per wavelength, delta_e2000_uncertainty,
    ita_deg, category; and the files written.)doc",
          py::arg("material") = "biospec-moderately", py::arg("vary") = py::none(), py::kw_only(), py::arg("set") = py::none(),
          py::arg("delta_e") = SwatchRequest{}.delta_e, py::arg("illuminant") = "D65", py::arg("observer") = "2", py::arg("mode") = "biospec",
          py::arg("seed") = py::none(), py::arg("max_rays") = py::none(), py::arg("geometry") = std::string(to_string(image_geometry)), py::arg("space") = "ACEScg",
          py::arg("output") = py::none(), py::arg("half") = false, py::arg("display") = "sRGB", py::arg("view") = "Standard",
          py::arg("patch_size") = SwatchFiles{}.patch_px, py::arg("overwrite") = false, py::arg("threads") = py::none(), py::arg("progress") = py::none());
}

}  // namespace skinspec::python
