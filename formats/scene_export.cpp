#include "formats/scene_export.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "formats/mitsuba_scene.hpp"
#include "formats/pbrt_scene.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/ciede2000.hpp"
#include "spectral/colorimetry.hpp"
#include "spectral/input_error.hpp"
#include "spectral/rgb_uplift.hpp"
#include "spectral/text_fields.hpp"
#include "spectral/wavelength_grid.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

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

std::string_view phase_kind(RendererPhase::Kind kind) {
    switch (kind) {
        case RendererPhase::Kind::henyey_greenstein: return "henyey-greenstein";
        case RendererPhase::Kind::isotropic: return "isotropic";
        case RendererPhase::Kind::tabulated: return "tabulated";
    }
    return "henyey-greenstein";
}

// R of the volumetric description (what the media hold before the renderer's phase approximation).
AdResult volumetric_solution(const RteStack& stack, AdCache& cache, bool accuracy_check = false) {
    return solve_adding_doubling(stack, AdIncidence{false, 0.0}, AdOptions{phase_error_channels, accuracy_check}, &cache);
}
double volumetric_reflectance(const RteStack& stack, AdCache& cache) {
    const auto r = volumetric_solution(stack, cache);
    return r.diffuse_reflectance + r.specular_reflectance;
}

// `volumetric`: the volumetric description's R at each of `wavelengths_nm` (solved once for both statements).
DescriptionGap description_gap(const LayerStack& stack, const std::vector<double>& wavelengths_nm, const std::vector<double>& volumetric,
                               AdCache& volumetric_cache) {
    AdCache biospec_cache;
    const auto biospec_solution = [&](double nm, bool accuracy_check) {
        BiospecAdOptions options;
        options.ad = AdOptions{phase_error_channels, accuracy_check};
        return solve_biospec_adding_doubling(stack, nm, 0.0, options, &biospec_cache).totals;
    };
    DescriptionGap gap;
    std::vector<double> biospec;
    for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
        const auto b = biospec_solution(wavelengths_nm[i], false);
        biospec.push_back(b.diffuse_reflectance + b.specular_reflectance);
        gap.R_differences.push_back(volumetric[i] - biospec.back());
        if (std::abs(gap.R_differences.back()) > std::abs(gap.largest_R_difference)) {
            gap.largest_R_difference = gap.R_differences.back();
            gap.at_nm = wavelengths_nm[i];
        }
    }
    // Where the gap is largest, the two solutions' own accuracy (adding-doubling's check with every segment's channels
    // doubled): a gap within it is not resolved.
    gap.accuracy = volumetric_solution(rte_stack_from(stack, gap.at_nm), volumetric_cache, true).accuracy + biospec_solution(gap.at_nm, true).accuracy;
    if (has_color_span(wavelengths_nm)) {
        const TristimulusWeights weights(wavelengths_nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
        const auto lab = [&](const std::vector<double>& r) { return xyz_to_lab(weights.integrate(r), weights.white()); };
        gap.delta_e2000 = ciede2000(lab(biospec), lab(volumetric));
    }
    return gap;
}

// The media's phase functions in the description's transport: per layer HG, isotropic, or for a table the
// description's own phase function at the phase wavelength (the table holds its mean cosine to 1e-4); `described`:
// the description's R at each exported wavelength.
PhaseApproximationError phase_approximation_error(const LayerStack& stack, const RendererMedia& media, const std::vector<double>& described,
                                                  AdCache& cache) {
    const auto at_phase_wavelength = rte_stack_from(stack, media.phase_wavelength_nm);
    PhaseApproximationError out;
    for (std::size_t i = 0; i < media.wavelengths_nm.size(); ++i) {
        const double nm = media.wavelengths_nm[i];
        const auto own = rte_stack_from(stack, nm);
        auto written = own;
        for (std::size_t k = 0; k < written.layers.size(); ++k) {
            constexpr double mm_per_cm = 10.0;
            written.layers[k].mu_a_per_cm = media.layers[k].sigma_a_per_mm[i] * mm_per_cm;
            written.layers[k].mu_s_per_cm = media.layers[k].sigma_s_per_mm[i] * mm_per_cm;
            const auto& phase = media.layers[k].phase;
            written.layers[k].phase = phase.kind == RendererPhase::Kind::henyey_greenstein ? PhaseFunction::henyey_greenstein(phase.g)
                                      : phase.kind == RendererPhase::Kind::isotropic       ? PhaseFunction::isotropic()
                                                                                           : at_phase_wavelength.layers[k].phase;
        }
        const double difference = volumetric_reflectance(written, cache) - described[i];
        out.R_differences.push_back(difference);
        if (std::abs(difference) > std::abs(out.largest_R_difference)) {
            out.largest_R_difference = difference;
            out.at_nm = nm;
        }
    }
    return out;
}

// R of the media as written at each exported wavelength is the description's plus the phase approximation's
// difference (both solved above); its colour is the pixel's (ScenePixel).
ScenePixel expected_pixel(const RendererMedia& point, const std::vector<double>& described, const PhaseApproximationError& phase_error,
                          const std::optional<PbrtRgbMatch>& rgb_match) {
    ScenePixel out;
    if (rgb_match) {
        out.linear_srgb = rgb_match->matched_srgb;
        out.how = "the matched RGB media's colour (rgb_match)";
        return out;
    }
    std::vector<double> written(described.size());
    for (std::size_t i = 0; i < described.size(); ++i) written[i] = described[i] + phase_error.R_differences[i];
    if (point.rgb) {
        out.linear_srgb = std::array<double, 3>{written[0], written[1], written[2]};
        out.how = "R of each channel's coefficients (an RGB variant transports each channel on its own)";
        return out;
    }
    const auto sampled = WavelengthGrid::parse(renderer_sampled_wavelengths, "the renderers' wavelengths");
    if (point.wavelengths_nm.front() > sampled.nm().front() || point.wavelengths_nm.back() < sampled.nm().back()) {
        out.why_not = fmt::format("the media cover {}-{} nm; outside them the renderer's media are empty (export {} nm for a prediction)",
                                  format_number(point.wavelengths_nm.front()), format_number(point.wavelengths_nm.back()), renderer_sampled_wavelengths);
        return out;
    }
    const TristimulusWeights weights(point.wavelengths_nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    out.linear_srgb = linear_srgb(weights.integrate(written));
    out.how = "R of the spectral media at the exported wavelengths, linear between them";
    return out;
}

}  // namespace

std::string scene_pixel_note(const ScenePixel& pixel) {
    if (!pixel.linear_srgb) return "no expected pixel value: " + pixel.why_not;
    const auto& c = *pixel.linear_srgb;
    return fmt::format("every pixel should read linear sRGB {:.4f} {:.4f} {:.4f} (R with the specular, normal incidence, D65: {}; adding-doubling)", c[0],
                       c[1], c[2], pixel.how);
}

std::string_view to_string(SceneRenderer renderer) { return renderer == SceneRenderer::pbrt ? "pbrt" : "mitsuba"; }

std::string_view renderer_title(SceneRenderer renderer) { return renderer == SceneRenderer::pbrt ? "pbrt-v4" : "Mitsuba 3"; }

std::string_view scene_extension(SceneRenderer renderer) { return renderer == SceneRenderer::pbrt ? ".pbrt" : ".xml"; }

PhaseExport default_phase_export(SceneRenderer renderer) { return renderer == SceneRenderer::pbrt ? PhaseExport::hg : PhaseExport::own; }

std::string_view rgb_caveat(SceneRenderer renderer) {
    // pbrt-v4 renders spectrally: an "rgb" coefficient becomes its RGBUnboundedSpectrum, a smooth spectrum through the
    // three values, not the skin's (issue 37's render of the unmatched coefficients: red 0.32 against the spectral
    // export's 0.354); the absorption is therefore matched (formats/pbrt_rgb_match.hpp).
    if (renderer == SceneRenderer::pbrt) {
        return "pbrt-v4 renders spectrally and turns each RGB coefficient into a smooth spectrum of its own (RGBUnboundedSpectrum): the "
               "absorption coefficients are scaled per channel so that the slab's colour under D65 is the spectral export's (rgb_match); "
               "its spectrum R(lambda) is still not the skin's: use the spectral export for spectral work";
    }
    return "";
}

SceneExport export_scene(const LayerStack& stack, const MediaRequest& request, SceneRenderer renderer, const std::filesystem::path& scene,
                         bool overwrite) {
    SceneExport out;
    out.media = renderer_media(stack, request);
    const bool pbrt = renderer == SceneRenderer::pbrt;
    out.files = pbrt ? pbrt_scene_files(out.media, scene) : mitsuba_scene_files(out.media, scene);
    check_output_path(scene, overwrite, {std::string(scene_extension(renderer))});
    for (std::size_t i = 1; i < out.files.size(); ++i) {
        if (std::filesystem::exists(out.files[i]) && !overwrite) throw InputError(out.files[i].string() + " exists (use --overwrite to replace it)");
        OutputClaims::claim(out.files[i], overwrite);
    }
    // The statements below are about the coefficients at the exported wavelengths (the point media).
    const RendererMedia point = out.media;
    if (pbrt && request.rgb) {
        out.rgb_match = match_pbrt_rgb(stack, request, point);
        out.media = out.rgb_match->media;
    }
    // The description's R at every exported wavelength: the reference of both statements and, with the phase
    // approximation's difference, of the pixel the scene should show (written into it).
    AdCache cache;
    std::vector<double> described;
    for (const double nm : point.wavelengths_nm) described.push_back(volumetric_reflectance(rte_stack_from(stack, nm), cache));
    out.phase_error = phase_approximation_error(stack, point, described, cache);
    out.expected_pixel = expected_pixel(point, described, out.phase_error, out.rgb_match);
    const auto note = scene_pixel_note(out.expected_pixel);
    if (pbrt) write_pbrt_scene(out.media, scene, note);
    else write_mitsuba_scene(out.media, scene, note);
    const auto back = pbrt ? read_pbrt_scene(scene, out.media.above_refractive_index) : read_mitsuba_scene(scene);
    out.read_back_difference = largest_difference(out.media, back);
    if (!(out.read_back_difference <= 1e-12)) {
        throw std::runtime_error("the written scene does not read back as the media given (difference " + format_number(out.read_back_difference) + ")");
    }
    out.mean_cosine_spread = mean_cosine_spread(stack, request.wavelengths_nm);
    try {
        out.description_gap = description_gap(stack, point.wavelengths_nm, described, cache);
    } catch (const InputError& e) {
        out.description_gap_why_not = e.what();  // e.g. an authors'-code variant biospec-adding-doubling does not model
    }
    return out;
}

namespace {

nlohmann::ordered_json description_gap_json(const SceneExport& exported) {
    const auto& gap = exported.description_gap;
    if (!gap) return {{"why_not", exported.description_gap_why_not}};
    return {{"R_difference", gap->R_differences},
            {"largest_R_difference", gap->largest_R_difference},
            {"at_nm", gap->at_nm},
            {"accuracy", gap->accuracy},
            {"delta_e2000", gap->delta_e2000 ? nlohmann::ordered_json(*gap->delta_e2000) : nlohmann::ordered_json(nullptr)},
            {"meaning", fmt::format("R of the material's volumetric description (what the media hold) minus R of its BioSpec description "
                                    "(what `skinspec spectrum` solves by default), both exact (adding-doubling, biospec-adding-doubling; {} "
                                    "channels), per wavelength, then the largest with the two solutions' stated accuracy there, and their colours' CIEDE2000 (D65, 2 degrees)",
                                    phase_error_channels)}};
}

nlohmann::ordered_json rgb_match_json(const SceneExport& exported) {
    if (!exported.rgb_match) return nullptr;
    const auto& m = *exported.rgb_match;
    return {{"absorption_factors", m.absorption_factors},
            {"spectral_srgb", m.spectral_srgb},
            {"matched_srgb", m.matched_srgb},
            {"unmatched_srgb", m.point_srgb},
            {"largest_relative_difference", m.largest_relative_difference},
            {"meaning", fmt::format("sigma_a's R, G, B are the coefficients at the three wavelengths times absorption_factors, chosen so that the "
                                    "slab's linear sRGB (D65, CIE 1931; R at normal incidence with the first surface) with pbrt-v4's smooth "
                                    "spectra of the RGB media (Jakob & Hanika 2019, scaled as RGBUnboundedSpectrum) equals the spectral media's "
                                    "({} nm); both by adding-doubling ({} channels). unmatched_srgb: the coefficients at the three wavelengths as pbrt-v4 renders them",
                                    pbrt_rgb_match_wavelengths, pbrt_rgb_match_channels)}};
}

}  // namespace

nlohmann::ordered_json scene_export_json(const SceneExport& exported, SceneRenderer renderer) {
    const auto& media = exported.media;
    nlohmann::ordered_json layers = nlohmann::ordered_json::array();
    for (std::size_t k = 0; k < media.layers.size(); ++k) {
        const auto& l = media.layers[k];
        nlohmann::ordered_json layer{{"name", l.name},
                                     {"thickness_mm", l.thickness_mm},
                                     {"refractive_index", l.refractive_index},
                                     {"sigma_a_per_mm", l.sigma_a_per_mm},
                                     {"sigma_s_per_mm", l.sigma_s_per_mm},
                                     {"phase", phase_kind(l.phase.kind)},
                                     {"mean_cosine", l.phase.g},
                                     {"mean_cosine_over_wavelengths", {exported.mean_cosine_spread[k].first, exported.mean_cosine_spread[k].second}}};
        if (l.phase.kind == RendererPhase::Kind::tabulated) layer["phase_per_sr_over_cos_theta"] = l.phase.values;
        layers.push_back(std::move(layer));
    }
    std::vector<std::string> files;
    for (const auto& f : exported.files) files.push_back(f.string());
    return {{"skinspec_version", version},
            {"renderer", renderer_title(renderer)},
            {"material", media.material},
            {"files", files},
            {"wavelengths_nm", media.wavelengths_nm},
            {"rgb", media.rgb},
            {"rgb_caveat", media.rgb ? std::string(rgb_caveat(renderer)) : std::string()},
            {"phase_wavelength_nm", media.phase_wavelength_nm},
            {"above_refractive_index", media.above_refractive_index},
            {"below_refractive_index", media.below_refractive_index},
            {"bottom_reflector", media.bottom_reflector},
            {"units", {{"thickness", "mm"}, {"sigma_a, sigma_s", "1/mm"}, {"phase", "1/sr"}}},
            {"layers", layers},
            {"read_back_largest_relative_difference", exported.read_back_difference},
            {"phase_approximation", {{"R_difference", exported.phase_error.R_differences},
                                     {"largest_R_difference", exported.phase_error.largest_R_difference},
                                     {"at_nm", exported.phase_error.at_nm},
                                     {"meaning", fmt::format("R of the media as written minus R of the material's own description (per "
                                                             "wavelength, then the largest), both by "
                                                             "adding-doubling ({} channels): the phase functions as the renderer takes them, "
                                                             "at {} nm, in place of each layer's own at each wavelength",
                                                             phase_error_channels, format_number(media.phase_wavelength_nm))}}},
            {"description_gap", description_gap_json(exported)},
            {"rgb_match", rgb_match_json(exported)},
            {"expected_pixel", exported.expected_pixel.linear_srgb
                                   ? nlohmann::ordered_json{{"linear_srgb", *exported.expected_pixel.linear_srgb},
                                                            {"how", exported.expected_pixel.how},
                                                            {"meaning", "every pixel of the scene as written (uniform D65 light of luminance 1, camera "
                                                                        "straight down): the slab's R for light along the normal, specular included, "
                                                                        "in linear sRGB (D65, CIE 1931), by adding-doubling"}}
                                   : nlohmann::ordered_json{{"why_not", exported.expected_pixel.why_not}}}};
}

}  // namespace skinspec
