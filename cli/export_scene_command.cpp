// `skinspec export pbrt|mitsuba`: the layered skin as a renderer's media in a minimal lit-slab scene

// (formats/renderer_media.hpp, formats/pbrt_scene.hpp, formats/mitsuba_scene.hpp), read back after writing to
// check that the renderer's files hold the coefficients they were given.
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli/common_options.hpp"
#include "cli/export_command.hpp"
#include "cli/material_options.hpp"
#include "formats/mitsuba_scene.hpp"
#include "formats/pbrt_scene.hpp"
#include "materials/material_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

enum class Renderer { pbrt, mitsuba };

struct SceneOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    std::string wavelengths = "400:700:10";
    std::string rgb;
    std::string phase;
    double phase_wavelength_nm = 550.0;
    std::string output;
    bool overwrite = false;
};

// The largest relative difference between what was written and what reading the files back gives.
double largest_difference(const RendererMedia& a, const RendererMedia& b) {
    if (a.layers.size() != b.layers.size()) return INFINITY;
    double worst = 0.0;
    const auto compare = [&](double x, double y) {
        const double scale = std::max(std::abs(x), std::abs(y));
        if (scale > 0.0) worst = std::max(worst, std::abs(x - y) / scale);
    };
    for (std::size_t k = 0; k < a.layers.size(); ++k) {
        const auto& x = a.layers[k];
        const auto& y = b.layers[k];
        if (x.name != y.name || x.sigma_a_per_mm.size() != y.sigma_a_per_mm.size() || x.phase.kind != y.phase.kind ||
            x.phase.values.size() != y.phase.values.size()) {
            return INFINITY;
        }
        compare(x.thickness_mm, y.thickness_mm);
        compare(x.refractive_index, y.refractive_index);
        for (std::size_t i = 0; i < x.sigma_a_per_mm.size(); ++i) {
            compare(x.sigma_a_per_mm[i], y.sigma_a_per_mm[i]);
            compare(x.sigma_s_per_mm[i], y.sigma_s_per_mm[i]);
        }
        if (x.phase.kind == RendererPhase::Kind::henyey_greenstein) compare(x.phase.g, y.phase.g);
        for (std::size_t i = 0; i < x.phase.values.size(); ++i) compare(x.phase.values[i], y.phase.values[i]);
    }
    if (a.bottom_reflector != b.bottom_reflector) return INFINITY;
    return worst;
}

void run_export_scene(const SceneOptions& o, Renderer renderer) {
    const char* command = renderer == Renderer::pbrt ? "export pbrt" : "export mitsuba";
    const std::string name = chosen_material(o.preset, o.material_file);
    if (o.output.empty()) throw InputError(std::string(command) + ": give -o FILE (" + (renderer == Renderer::pbrt ? ".pbrt" : ".xml") + ")");
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
    // pbrt-v4's media are Henyey-Greenstein only, so HG is its default; Mitsuba 3 takes each layer's own.
    const std::string phase = o.phase.empty() ? (renderer == Renderer::pbrt ? "hg" : "own") : o.phase;
    request.phase = parse_named_choice(phase, "--phase", std::array{PhaseExport::own, PhaseExport::hg}, "a phase export");
    const auto media = renderer_media(*stack, request);
    const std::filesystem::path scene = o.output;
    const auto files = renderer == Renderer::pbrt ? pbrt_scene_files(media, scene) : mitsuba_scene_files(media, scene);
    check_output_path(scene, o.overwrite, {renderer == Renderer::pbrt ? ".pbrt" : ".xml"});
    for (std::size_t i = 1; i < files.size(); ++i) {
        if (std::filesystem::exists(files[i]) && !o.overwrite) {
            throw InputError(files[i].string() + " exists (use --overwrite to replace it)");
        }
        OutputClaims::claim(files[i], o.overwrite);
    }
    if (renderer == Renderer::pbrt) write_pbrt_scene(media, scene);
    else write_mitsuba_scene(media, scene);
    const auto back = renderer == Renderer::pbrt ? read_pbrt_scene(scene, media.above_refractive_index) : read_mitsuba_scene(scene);
    const double difference = largest_difference(media, back);
    std::cerr << "wrote " << scene.string() << (files.size() > 1 ? fmt::format(" and {} spectrum files in {}", files.size() - 1, files[1].parent_path().string()) : "")
              << '\n';

    const auto spread = mean_cosine_spread(*stack, request.wavelengths_nm);
    std::cout << fmt::format("{} as {} media: {} layers, {} {}; phase functions at {} nm\n", name, renderer == Renderer::pbrt ? "pbrt-v4" : "Mitsuba 3",
                             media.layers.size(), request.wavelengths_nm.size(), media.rgb ? "wavelengths as R, G, B" : "wavelengths",
                             format_number(media.phase_wavelength_nm));
    std::cout << fmt::format("{:<20}{:>12}{:>8}{:>16}{:>16}  {}\n", "layer", "thickness mm", "index", "sigma_a 1/mm", "sigma_s 1/mm", "phase");
    for (std::size_t k = 0; k < media.layers.size(); ++k) {
        const auto& l = media.layers[k];
        const auto [lo_a, hi_a] = std::minmax_element(l.sigma_a_per_mm.begin(), l.sigma_a_per_mm.end());
        const auto [lo_s, hi_s] = std::minmax_element(l.sigma_s_per_mm.begin(), l.sigma_s_per_mm.end());
        const std::string kind = l.phase.kind == RendererPhase::Kind::tabulated ? fmt::format("tabulated ({} points, mean cos {:.4f})", l.phase.values.size(), l.phase.g)
                                 : l.phase.kind == RendererPhase::Kind::isotropic ? std::string("isotropic")
                                                                                   : fmt::format("HG g {:.4f}", l.phase.g);
        const std::string g_range = spread[k].second - spread[k].first > 1e-9 ? fmt::format("; g {:.4f}-{:.4f} over the wavelengths", spread[k].first, spread[k].second) : "";
        std::cout << fmt::format("{:<20}{:>12.5g}{:>8.4g}{:>16}{:>16}  {}{}\n", l.name, l.thickness_mm, l.refractive_index,
                                 fmt::format("{:.3g}-{:.3g}", *lo_a, *hi_a), fmt::format("{:.3g}-{:.3g}", *lo_s, *hi_s), kind, g_range);
    }
    std::cout << fmt::format("bottom: {}; read back: largest relative difference {:.3g}\n",
                             media.bottom_reflector ? "Lambertian reflector (R = 1)" : "exit into index " + format_number(media.below_refractive_index), difference);
    if (!(difference <= 1e-12)) throw std::runtime_error("the written scene does not read back as the media given (difference " + format_number(difference) + ")");
}

void add_scene_command(CLI::App& exporter, Renderer renderer) {
    auto o = std::make_shared<SceneOptions>();
    const bool pbrt = renderer == Renderer::pbrt;
    auto* cmd = exporter.add_subcommand(pbrt ? "pbrt" : "mitsuba", pbrt ? "The layered skin as pbrt-v4 media in a lit-slab scene (.pbrt and .spd files)"
                                                                        : "The layered skin as Mitsuba 3 media in a lit-slab scene (.xml and .spd files)");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    cmd->add_option("--wavelengths", o->wavelengths, "Spectral media at these wavelengths (nm), one .spd file per layer and coefficient")->capture_default_str();
    cmd->add_option("--rgb", o->rgb, "RGB media instead: three wavelengths (nm) whose coefficients are taken as R, G, B, e.g. 650,550,450");
    cmd->add_option("--phase", o->phase, pbrt ? "hg (default: pbrt-v4 media take HG only; measured phases as HG of their mean cosine) or own"
                                              : "own (default: HG, isotropic, measured phases as tabphase) or hg (every layer HG of its mean cosine)");
    cmd->add_option("--phase-wavelength", o->phase_wavelength_nm, "Wavelength (nm) of the phase functions (neither renderer's are spectral)")->capture_default_str();
    cmd->add_option("-o,--output", o->output, pbrt ? "Scene file .pbrt" : "Scene file .xml")->required();
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing output files");
    cmd->callback([o, renderer] { run_export_scene(*o, renderer); });
}

}  // namespace

void add_export_scene_commands(CLI::App& exporter) {
    add_scene_command(exporter, Renderer::pbrt);
    add_scene_command(exporter, Renderer::mitsuba);
}

}  // namespace skinspec::cli
