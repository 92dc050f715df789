// skinspec.export_lut / export_profile / export_pbrt / export_mitsuba (docs/PYTHON.md "Exports"): the files
// `skinspec export ...` writes, written by the same library calls, with the command's --json report returned as a
// dict of numpy arrays.
#include <array>
#include <chrono>
#include <filesystem>

#include <pybind11/stl.h>

#include "appearance/lut_export.hpp"
#include "appearance/profile_export.hpp"
#include "appearance/profile_shape_report.hpp"
#include "formats/mcml_export.hpp"
#include "formats/mcml_files.hpp"
#include "formats/scene_export.hpp"
#include "python/bindings.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::python {
namespace {

const LayerStack& layered(const PyMaterial& material, std::string_view command) {
    const auto* stack = std::get_if<LayerStack>(&material.material);
    if (!stack) {
        throw InputError("material '" + material_name(material.material) + "' is given per band (a homogeneous half-space without layers); " +
                         std::string(command) + " writes the layers of a layered material");
    }
    return *stack;
}

py::object export_scene_files(SceneRenderer renderer, const py::object& material, const py::object& output, const py::object& wavelengths,
                              const py::object& rgb, const py::object& phase, double phase_wavelength_nm, bool overwrite) {
    const auto skin = material_argument(material, "material");
    const auto& stack = layered(skin, "export_" + std::string(to_string(renderer)));
    const auto scene = path_argument(output, "output");
    MediaRequest request;
    request.rgb = !rgb.is_none();
    if (request.rgb) {
        if (!wavelengths.is_none()) throw InputError("rgb: give either wavelengths (spectral media) or rgb (three wavelengths as R, G, B), not both");
        request.wavelengths_nm = finite_vector(rgb, "--rgb");
    } else {
        const auto grid = wavelengths.is_none() ? WavelengthGrid::parse(renderer_sampled_wavelengths, "wavelengths")
                                                : wavelength_argument(wavelengths);
        request.wavelengths_nm.assign(grid.nm().begin(), grid.nm().end());
    }
    request.phase_wavelength_nm = phase_wavelength_nm;
    request.phase = phase.is_none() ? default_phase_export(renderer)
                                    : parse_named_choice(phase.cast<std::string>(), "phase", std::array{PhaseExport::own, PhaseExport::hg}, "a phase export");
    return json_object(scene_export_json(export_scene(stack, request, renderer, scene, overwrite), renderer));
}

py::object export_profile(const py::object& material, const py::object& output, const py::object& table, const std::string& per,
                          const py::object& wavelengths, const std::string& space, const std::string& illuminant, const std::string& observer,
                          std::size_t gaussians, const py::object& radii_mm, const py::object& mode, const py::object& rays,
                          const py::object& stderr_target, const py::object& max_rays, const py::object& seed, const py::object& vary, bool overwrite,
                          const py::kwargs& switches) {
    const auto skin = material_argument(material, "material");
    ProfileExportRequest fit_request;
    fit_request.per = parse_profile_channels(per, "per");
    const auto& solver = profile_solver_argument(mode);
    const auto& cm = ColorManagement::builtin();
    fit_request.space = cm.canonical_space(space, "space");
    space_chromaticities(fit_request.space);
    fit_request.illuminant = parse_illuminant(illuminant, "illuminant");
    fit_request.observer = parse_observer(observer, "observer");
    fit_request.gaussians = gaussians;
    const auto json_file = output.is_none() ? std::filesystem::path() : path_argument(output, "output");
    const auto table_file = table.is_none() ? std::filesystem::path() : path_argument(table, "table");
    if (!json_file.empty()) check_output_path(json_file, overwrite, {".json"});
    if (!table_file.empty()) check_output_path(table_file, overwrite, {".csv"});
    const bool bands = std::holds_alternative<HomogeneousMaterial>(skin.material);
    check_profile_export(material_name(skin.material), bands, fit_request);
    const auto grid = profile_export_wavelengths(fit_request, wavelengths.is_none() ? std::nullopt : std::optional(wavelength_argument(wavelengths)), "wavelengths");
    const auto radii = radii_mm.is_none() ? py::object(to_array(parse_radii_mm("0:10:0.01", "radii_mm"), {1001})) : radii_mm;
    const auto request = profile_request_argument(grid, radii, false, {rays, stderr_target, max_rays, seed}, switches, skin.overrides);
    if (!vary.is_none()) {
        // A grid: every member's fit, one set of variances (as `export profile --vary`).
        const auto axes = vary_axes(vary);
        const auto built = profile_grid_members(skin.material, axes);
        std::vector<const Material*> members;
        for (const auto& m : built) members.push_back(&m);
        const auto all = solve_profiles_interruptible(solver, members, request);
        const auto fitted = fit_profile_export_grid(all, axes, bands, fit_request);
        const auto document = profile_export_grid_json(fitted);
        if (!json_file.empty()) write_text_file(json_file, document.dump(2) + "\n", overwrite);
        if (!table_file.empty()) write_text_file(table_file, profile_export_grid_table_csv(fitted), overwrite);
        py::dict out = json_object(document);
        out["precision"] = profile_precision_line(all);
        return out;
    }
    const auto profiles = solve_profiles_interruptible(solver, skin.material, request);
    auto exported = fit_profile_export(profiles, bands, fit_request);
    if (profile_shape_checked(solver, skin.material)) exported.shape = stated_profile_shape_interruptible(solver, skin.material, grid, solver_switches(switches));
    const auto document = profile_export_json(exported);
    if (!json_file.empty()) write_text_file(json_file, document.dump(2) + "\n", overwrite);
    if (!table_file.empty()) write_text_file(table_file, profile_export_table_csv(exported), overwrite);
    py::dict out = json_object(document);
    out["warnings"] = summarise_warnings(profiles.warnings);
    return out;
}

py::object export_lut(const std::string& material, const py::object& output, const std::string& melanin, const std::string& blood,
                      const py::object& set, double delta_e, const std::string& illuminant, const std::string& observer, const std::string& solver,
                      const py::object& seed, const py::object& max_rays, const std::string& geometry, const std::string& space, bool half,
                      const py::object& spectra, const py::object& preview, const std::string& display, const std::string& view,
                      const py::object& threads, const py::object& progress, bool overwrite, const py::kwargs& switches) {
    auto request = swatch_request_argument(material, set, delta_e, illuminant, observer, solver, seed, max_rays, geometry, switches);
    const auto u = lut_axis(lut_melanin_field, melanin, "melanin");
    const auto v = lut_axis(lut_blood_field, blood, "blood");
    request.sweeps = {u, v};
    const auto optional = [](const py::object& value, std::string_view what) { return value.is_none() ? std::filesystem::path() : path_argument(value, what); };
    const auto files = check_lut_files(
        LutFiles{path_argument(output, "output"), optional(spectra, "spectra"), optional(preview, "preview"), space, half, display, view, overwrite}, u, v);
    const auto start = std::chrono::steady_clock::now();
    const auto chart = compute_swatch_interruptible(request, threads, progress);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto summary = write_lut_files(chart, request, files);
    auto out = swatch_dict(chart, request, files.space);
    for (const auto& [key, value] : json_object(lut_summary_json(chart, request, files, summary, seconds, 1)).cast<py::dict>()) out[key] = value;
    std::vector<std::string> written{files.texture.string()};
    for (const auto& f : {files.spectra, files.preview}) {
        if (!f.empty()) written.push_back(f.string());
    }
    out["files"] = written;
    out["warnings"] = summarise_warnings(chart.warnings);
    return out;
}

const std::string scene_doc = std::string(R"doc(

    material: a skinspec.Material, preset name or .toml path (layered); output: the scene file; wavelengths: spectral
    media at these wavelengths in nm (default )doc") + std::string(renderer_sampled_wavelengths) + R"doc(, what the renderers sample; one .spd file per layer and
    coefficient beside the scene) or rgb: three wavelengths whose coefficients are taken as R, G, B (e.g. [650, 550, 450]; for pbrt-v4
    the absorption then scaled per channel to the spectral media's colour, rgb_match); phase: "hg" or
    "own"; phase_wavelength: the wavelength (nm) of the phase functions; overwrite: replace existing files. The
    files are read back after writing (read_back_largest_relative_difference). Returns the dict `--json` prints:
    files, wavelengths_nm and per layer thickness_mm, refractive_index, sigma_a_per_mm and sigma_s_per_mm (numpy, one
    value per wavelength), phase and mean_cosine.)doc";

}  // namespace

py::dict export_mcml(const py::object& material, const py::object& output, const py::object& wavelengths, const py::object& photons, double ring_mm,
                     double reach_mm, double depth_bin_mm, bool overwrite) {
    const auto skin = material_argument(material, "material");
    const auto* stack = std::get_if<LayerStack>(&skin.material);
    if (!stack) throw InputError("material is given per band (no layers); export_mcml writes the layers of a layered material");
    const auto file = path_argument(output, "output");
    check_output_path(file, overwrite, {".mci"});
    McmlExportRequest request;
    if (!wavelengths.is_none()) {
        const auto grid = wavelength_argument(wavelengths);
        request.wavelengths_nm.assign(grid.nm().begin(), grid.nm().end());
    }
    if (!photons.is_none()) request.photons = whole_number(photons, 1, 1e15, "photons");
    request.ring_mm = ring_mm;
    request.reach_mm = reach_mm;
    request.depth_bin_mm = depth_bin_mm;
    request.output_stem = file.stem().string();
    const auto exported = mcml_export(*stack, request);
    const auto comments = mcml_export_comments(exported, material_name(skin.material), request.wavelengths_nm);
    write_text_file(file, mci_text(exported.runs, comments), overwrite);
    py::dict out;
    out["file"] = file.string();
    out["wavelengths_nm"] = request.wavelengths_nm;
    out["photons"] = request.photons;
    out["substitutions"] = exported.substitutions;
    out["exported_reflectance"] = exported.exported_reflectance;
    out["own_reflectance"] = exported.own_reflectance;
    out["comments"] = comments;
    return out;
}

void bind_exports(py::module_& m) {
    m.def("export_mcml", &export_mcml, R"doc(The layers' volumetric description as an MCML input file, as `skinspec export mcml` writes it.

    material: a skinspec.Material, preset name or .toml path (layered); output: the .mci file; wavelengths: one run each
    (default 450, 550, 650 nm); photons per run (default 1e7); ring_mm, reach_mm: MCML's radial rings (dr) and how far
    they reach; depth_bin_mm: MCML's dz; overwrite: replace an existing file. Returns the file, what MCML could not hold
    and was substituted, and adding-doubling's diffuse R of the file's stack against the material's own description per
    wavelength (what the substitutions change).)doc",
          py::arg("material"), py::arg("output"), py::kw_only(), py::arg("wavelengths") = py::none(), py::arg("photons") = py::none(),
          py::arg("ring_mm") = McmlExportRequest{}.ring_mm, py::arg("reach_mm") = McmlExportRequest{}.reach_mm,
          py::arg("depth_bin_mm") = McmlExportRequest{}.depth_bin_mm, py::arg("overwrite") = false);
    m.def("export_lut", &export_lut, R"doc(A melanosome x blood look-up texture of diffuse skin albedo, as `skinspec export lut` writes it.

    material: a preset name or .toml path; output: the linear OpenEXR texture (one texel per melanin column and blood
    row); melanin, blood: "FIRST:LAST:STEPS[:log]" of epidermis.melanosome_fraction and dermis.blood_fraction; set:
    {field: value} overrides; delta_e: each texel's CIEDE2000 uncertainty target; mode (the solver, as --mode), seed, max_rays, geometry
    (default "sce"): as skinspec.swatch; space: the texture's linear working space; half: half float; spectra: also
    the reflectance spectra (.exr, one channel per wavelength, or .csv); preview: also a display-referred image with
    labelled axes (.png, .tif) in `display` / `view`; overwrite: replace existing files; the solver's switches as
    keywords (e.g. channels=16). Returns skinspec.swatch's
    arrays (rows = blood, columns = melanin) with the command's --json summary (rays, worst_delta_e_uncertainty,
    seconds) and the files written.)doc",
          py::arg("material"), py::arg("output"), py::kw_only(), py::arg("melanin") = "0.01:0.42:64:log",
          py::arg("blood") = "0.002:0.05:64:log", py::arg("set") = py::none(), py::arg("delta_e") = 0.5, py::arg("illuminant") = "D65",
          py::arg("observer") = "2", py::arg("mode") = "biospec", py::arg("seed") = py::none(), py::arg("max_rays") = py::none(),
          py::arg("geometry") = std::string(to_string(image_geometry)), py::arg("space") = "ACEScg", py::arg("half") = false, py::arg("spectra") = py::none(),
          py::arg("preview") = py::none(), py::arg("display") = "sRGB", py::arg("view") = "Standard", py::arg("threads") = py::none(),
          py::arg("progress") = py::none(), py::arg("overwrite") = false);
    m.def("export_profile", &export_profile, R"doc(R(r) fitted as a sum of Gaussians with shared variances (d'Eon et al. 2007), as `skinspec export profile` fits it.

    material: a skinspec.Material, preset name or .toml path; output: also write the fit as JSON (.json); table: also
    write the variances and weights as CSV (.csv); per: "rgb" (one fit per colour band: the profile's colour at each
    radius in the linear `space` under `illuminant` and `observer`, from 380-780 nm every 10) or "wavelength" (one per
    `wavelengths`, default 450, 550, 650 nm); gaussians: [1, 12]; radii_mm: where R(r) is fitted (default 0-10 mm by
    0.01); mode: a solver that computes profiles (default None: rte, the exact transport); rays, stderr, max_rays, seed and solver switches as
    skinspec.profiles takes them; vary: a dict {field: values} of one or two fields (a grid, as `export profile --vary`:
    every member's fit, one set of variances for all, the exact transport from one walk per wavelength where the members
    differ only in absorption); overwrite: replace existing files. Returns the JSON the command writes (variances_mm2
    and per channel its weights and the fit's errors; with vary, per member) and the solver's warnings.)doc",
          py::arg("material"), py::kw_only(), py::arg("output") = py::none(), py::arg("table") = py::none(), py::arg("per") = "rgb",
          py::arg("wavelengths") = py::none(), py::arg("space") = "ACEScg", py::arg("illuminant") = "D65", py::arg("observer") = "2",
          py::arg("gaussians") = ProfileExportRequest{}.gaussians, py::arg("radii_mm") = py::none(), py::arg("mode") = py::none(),
          py::arg("rays") = py::none(), py::arg("stderr") = py::none(), py::arg("max_rays") = py::none(), py::arg("seed") = py::none(),
          py::arg("vary") = py::none(), py::arg("overwrite") = false);
    // Both renderers: one function each, named and described by the renderer (pybind11 keeps the pointers: static).
    static const std::array<std::string, 2> names{"export_pbrt", "export_mitsuba"};
    static const std::array<std::string, 2> docs{
        std::string("The layered skin as pbrt-v4 media in a scene that renders as it is (uniform D65 light, camera straight down), as `skinspec export pbrt` writes it (phase default \"hg\": "
                    "pbrt-v4 media take Henyey-Greenstein only).") + scene_doc,
        std::string("The layered skin as Mitsuba 3 media in a scene that renders as it is (uniform D65 light, camera straight down), as `skinspec export mitsuba` writes it (phase default \"own\": "
                    "HG, isotropic, measured phases as tabphase).") + scene_doc};
    for (const auto renderer : {SceneRenderer::pbrt, SceneRenderer::mitsuba}) {
        const std::size_t i = renderer == SceneRenderer::pbrt ? 0 : 1;
        m.def(
            names[i].c_str(),
            [renderer](const py::object& material, const py::object& output, const py::object& wavelengths, const py::object& rgb,
                       const py::object& phase, double phase_wavelength, bool overwrite) {
                return export_scene_files(renderer, material, output, wavelengths, rgb, phase, phase_wavelength, overwrite);
            },
            docs[i].c_str(), py::arg("material"), py::arg("output"), py::kw_only(), py::arg("wavelengths") = py::none(), py::arg("rgb") = py::none(),
            py::arg("phase") = py::none(), py::arg("phase_wavelength") = MediaRequest{}.phase_wavelength_nm, py::arg("overwrite") = false);
    }
}

}  // namespace skinspec::python
