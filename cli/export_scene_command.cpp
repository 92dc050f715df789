// `skinspec export pbrt|mitsuba`: the layered skin as a renderer's media in a scene that renders as it is, written and
// read back by formats/scene_export.hpp.
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli/common_options.hpp"
#include "cli/export_command.hpp"
#include "cli/material_options.hpp"
#include "formats/scene_export.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

struct SceneOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    std::string wavelengths{renderer_sampled_wavelengths};
    std::string rgb;
    std::string phase;
    double phase_wavelength_nm = 550.0;
    std::string output;
    bool overwrite = false;
    bool json = false;
};

void run_export_scene(const SceneOptions& o, SceneRenderer renderer) {
    const std::string command = "export " + std::string(to_string(renderer));
    const std::string name = chosen_material(o.preset, o.material_file);
    if (o.output.empty()) throw InputError(command + ": give -o FILE (" + std::string(scene_extension(renderer)) + ")");
    const auto material = load_material(name, parsed_overrides(o.overrides));
    const auto* stack = std::get_if<LayerStack>(&material);
    if (!stack) {
        throw InputError("material '" + name + "' is given per band (a homogeneous half-space without layers); " + command +
                         " writes the layers of a layered material");
    }
    MediaRequest request;
    request.rgb = !o.rgb.empty();
    if (request.rgb) {
        for (const auto field : split_fields(o.rgb)) {
            const auto nm = parse_double(field);
            if (!nm || !std::isfinite(*nm) || *nm <= 0.0) throw InputError("--rgb: '" + std::string(field) + "' is not a wavelength in nm (0, inf)");
            request.wavelengths_nm.push_back(*nm);
        }
    } else {
        const auto grid = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
        request.wavelengths_nm.assign(grid.nm().begin(), grid.nm().end());
    }
    request.phase_wavelength_nm = o.phase_wavelength_nm;
    request.phase = o.phase.empty() ? default_phase_export(renderer)
                                    : parse_named_choice(o.phase, "--phase", std::array{PhaseExport::own, PhaseExport::hg}, "a phase export");
    const auto exported = export_scene(*stack, request, renderer, o.output, o.overwrite);
    const auto& media = exported.media;
    const auto& files = exported.files;
    std::cerr << "wrote " << files.front().string()
              << (files.size() > 1 ? fmt::format(" and {} spectrum files in {}", files.size() - 1, files[1].parent_path().string()) : "") << '\n';
    if (o.json) {
        std::cout << scene_export_json(exported, renderer).dump(2) << '\n';
        return;
    }
    std::cout << fmt::format("{} as {} media: {} layers, {} {}; phase functions at {} nm\n", name, renderer_title(renderer), media.layers.size(),
                             request.wavelengths_nm.size(), media.rgb ? "wavelengths as R, G, B" : "wavelengths", format_number(media.phase_wavelength_nm));
    std::cout << fmt::format("{:<20}{:>12}{:>8}{:>16}{:>16}  {}\n", "layer", "thickness mm", "index", "sigma_a 1/mm", "sigma_s 1/mm", "phase");
    for (std::size_t k = 0; k < media.layers.size(); ++k) {
        const auto& l = media.layers[k];
        const auto [lo_a, hi_a] = std::minmax_element(l.sigma_a_per_mm.begin(), l.sigma_a_per_mm.end());
        const auto [lo_s, hi_s] = std::minmax_element(l.sigma_s_per_mm.begin(), l.sigma_s_per_mm.end());
        const std::string kind = l.phase.kind == RendererPhase::Kind::tabulated ? fmt::format("tabulated ({} points, mean cos {:.4f}, as interpolated {:.5f})", l.phase.values.size(), l.phase.g, tabulated_mean_cosine(l.phase.values))
                                 : l.phase.kind == RendererPhase::Kind::isotropic ? std::string("isotropic")
                                                                                   : fmt::format("HG g {:.4f}", l.phase.g);
        const auto& spread = exported.mean_cosine_spread[k];
        const std::string g_range = spread.second - spread.first > 1e-9 ? fmt::format("; g {:.4f}-{:.4f} over the wavelengths", spread.first, spread.second) : "";
        std::cout << fmt::format("{:<20}{:>12.5g}{:>8.4g}{:>16}{:>16}  {}{}\n", l.name, l.thickness_mm, l.refractive_index,
                                 fmt::format("{:.3g}-{:.3g}", *lo_a, *hi_a), fmt::format("{:.3g}-{:.3g}", *lo_s, *hi_s), kind, g_range);
    }
    std::cout << fmt::format("bottom: {}; read back: largest relative difference {:.3g}\n",
                             media.bottom_reflector ? "Lambertian reflector (R = 1)" : "exit into index " + format_number(media.below_refractive_index),
                             exported.read_back_difference);
    if (media.rgb && !rgb_caveat(renderer).empty()) std::cout << "RGB: " << rgb_caveat(renderer) << '\n';
    if (exported.rgb_match) {
        const auto& m = *exported.rgb_match;
        std::cout << fmt::format("RGB match: sigma_a x {:.4f} / {:.4f} / {:.4f} (R / G / B); the slab's linear sRGB under D65 as pbrt-v4 renders "
                                 "the media {:.4f} / {:.4f} / {:.4f}, the spectral media's {:.4f} / {:.4f} / {:.4f} (largest relative difference "
                                 "{:.1e}; unmatched {:.4f} / {:.4f} / {:.4f}; adding-doubling, {} channels)\n",
                                 m.absorption_factors[0], m.absorption_factors[1], m.absorption_factors[2], m.matched_srgb[0], m.matched_srgb[1],
                                 m.matched_srgb[2], m.spectral_srgb[0], m.spectral_srgb[1], m.spectral_srgb[2], m.largest_relative_difference,
                                 m.point_srgb[0], m.point_srgb[1], m.point_srgb[2], pbrt_rgb_match_channels);
    }
    std::cout << fmt::format("phase functions as written (at {} nm, not spectral in the renderer): R {:+.4f} against the material's own "
                             "description at {} nm, the largest difference (adding-doubling, {} channels, both)\n",
                             format_number(media.phase_wavelength_nm), exported.phase_error.largest_R_difference, format_number(exported.phase_error.at_nm),
                             phase_error_channels);
    if (const auto& gap = exported.description_gap) {
        std::cout << fmt::format("the media are the skin's volumetric description: against its BioSpec description (spectrum's default mode) R "
                                 "{:+.4f} +- {:.4f} at {} nm, the largest difference{} (adding-doubling and biospec-adding-doubling, {} channels, with their "
                                 "stated accuracy)\n",
                                 gap->largest_R_difference, gap->accuracy, format_number(gap->at_nm),
                                 gap->delta_e2000 ? fmt::format(", colour CIEDE2000 {:.2f}", *gap->delta_e2000) : std::string(), phase_error_channels);
    } else {
        std::cout << "the media are the skin's volumetric description; its BioSpec description is not solved exactly (" << exported.description_gap_why_not
                  << "), so their difference is not stated\n";
    }
    std::cout << fmt::format("scene: uniform D65 light, camera straight down over {} x {} mm, {} x {} px; {}\n", format_number(scene_view_mm),
                             format_number(scene_view_mm), scene_pixels, scene_pixels, scene_pixel_note(exported.expected_pixel));
}

void add_scene_command(CLI::App& exporter, SceneRenderer renderer) {
    auto o = std::make_shared<SceneOptions>();
    const bool pbrt = renderer == SceneRenderer::pbrt;
    auto* cmd = exporter.add_subcommand(pbrt ? "pbrt" : "mitsuba", pbrt ? "The layered skin as pbrt-v4 media in a scene that renders as it is: uniform D65 light, camera straight down (.pbrt and .spd files)"
                                                                        : "The layered skin as Mitsuba 3 media in a scene that renders as it is: uniform D65 light, camera straight down (.xml and .spd files)");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    cmd->add_option("--wavelengths", o->wavelengths, "Spectral media at these wavelengths (nm), one .spd file per layer and coefficient")->capture_default_str();
    cmd->add_option("--rgb", o->rgb, "RGB media instead: three wavelengths (nm) whose coefficients are taken as R, G, B, e.g. 650,550,450 (pbrt: the absorption then scaled per channel so that pbrt-v4's smooth spectra of it give the spectral media's colour)");
    cmd->add_option("--phase", o->phase, pbrt ? "hg (default: pbrt-v4 media take HG only; measured phases as HG of their mean cosine) or own"
                                              : "own (default: HG, isotropic, measured phases as tabphase) or hg (every layer HG of its mean cosine)");
    cmd->add_option("--phase-wavelength", o->phase_wavelength_nm, "Wavelength (nm) of the phase functions (neither renderer's are spectral)")->capture_default_str();
    cmd->add_option("-o,--output", o->output, pbrt ? "Scene file .pbrt" : "Scene file .xml")->required();
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->add_flag("--json", o->json, "Print the media written as JSON (per layer sigma_a, sigma_s per wavelength, phase)");
    cmd->callback([o, renderer] { run_export_scene(*o, renderer); });
}

}  // namespace

void add_export_scene_commands(CLI::App& exporter) {
    add_scene_command(exporter, SceneRenderer::pbrt);
    add_scene_command(exporter, SceneRenderer::mitsuba);
}

}  // namespace skinspec::cli
