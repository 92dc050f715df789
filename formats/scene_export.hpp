#pragma once
// A layered skin written as a renderer's scene and read back (`skinspec export pbrt|mitsuba`, skinspec.export_scene):
// the media (formats/renderer_media.hpp) as a pbrt-v4 or Mitsuba 3 scene (uniform D65 light, camera straight down) (formats/pbrt_scene.hpp,
// formats/mitsuba_scene.hpp), every output checked before anything is written, and the written files read back to
// check that they hold the coefficients they were given.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "formats/pbrt_rgb_match.hpp"
#include "formats/renderer_media.hpp"

namespace skinspec {

enum class SceneRenderer { pbrt, mitsuba };
std::string_view to_string(SceneRenderer renderer);        // "pbrt", "mitsuba"
std::string_view renderer_title(SceneRenderer renderer);   // "pbrt-v4", "Mitsuba 3"
std::string_view scene_extension(SceneRenderer renderer);  // ".pbrt", ".xml"
// pbrt-v4's media are Henyey-Greenstein only, so HG is its default; Mitsuba 3 takes each layer's own.
PhaseExport default_phase_export(SceneRenderer renderer);
// What an RGB export approximates in `renderer`, beyond taking three wavelengths as R, G, B ("" when nothing more).
std::string_view rgb_caveat(SceneRenderer renderer);

// What the renderer's media change in R against skinspec's own description: each layer's phase function as
// written (HG of its mean cosine for pbrt-v4, a table at the phase wavelength for Mitsuba 3; not spectral in either)
// in place of the description's at each wavelength, both solved by adding-doubling (exact transport at
// phase_error_channels channels, the quadrature's own error far below).
inline constexpr std::size_t phase_error_channels = 16;
struct PhaseApproximationError {
    std::vector<double> R_differences;  // R of the media as written - R of the description, per exported wavelength
    double largest_R_difference = 0.0;  // the largest in magnitude
    double at_nm = 0.0;
};

// The media are the skin's volumetric description (mu_s and a phase function per layer); `skinspec spectrum`'s
// default, the BioSpec walk, solves its BioSpec description (per-crossing measured profiles, Rayleigh and cosine
// turns), and the two differ (issue 31: CIEDE2000 3.6-4.6 on the skin presets). Stated by the exact solution of each
// (adding-doubling, biospec-adding-doubling; phase_error_channels channels), so that a render is compared with the
// skin it holds. Unset, with `why_not`, when the material's BioSpec description cannot be solved exactly.
struct DescriptionGap {
    std::vector<double> R_differences;  // R of the volumetric description - R of the BioSpec one, per exported wavelength
    double largest_R_difference = 0.0;  // the largest in magnitude
    double at_nm = 0.0;
    double accuracy = 0.0;  // the two solutions' stated accuracy of R there, added
    std::optional<double> delta_e2000;  // their colours (D65, 2 degrees) when the wavelengths cover 400-700 nm
};

// What every pixel of the written scene should read. Under a uniform environment that both renderers scale to a
// luminance of 1 (pbrt-v4 lights.cpp "equivalent to 1 nit"; Mitsuba 3's d65 spectrum), the radiance seen along the
// normal is, by reciprocity, the slab's reflectance for light arriving along the normal, specular included (R,
// geometry sci): here the media as written, solved by adding-doubling (phase_error_channels channels), in linear sRGB
// (D65, CIE 1931; the RGB film's output). Unset, with why_not, where the renderer would not hold those media.
struct ScenePixel {
    std::optional<std::array<double, 3>> linear_srgb;
    std::string how;      // how the value follows from the media (pbrt-v4's matched RGB, Mitsuba's RGB channels, spectral)
    std::string why_not;  // when linear_srgb is unset
};

struct SceneExport {
    RendererMedia media;
    std::vector<std::filesystem::path> files;                       // the scene, then its spectrum files
    std::vector<std::pair<double, double>> mean_cosine_spread;      // per layer over the exported wavelengths
    double read_back_difference = 0.0;                              // largest relative difference written vs read
    PhaseApproximationError phase_error;
    std::optional<DescriptionGap> description_gap;
    std::string description_gap_why_not;  // when description_gap is unset
    std::optional<PbrtRgbMatch> rgb_match;  // pbrt-v4's RGB media: their absorption matched to the spectral media's colour
    ScenePixel expected_pixel;
};

// The sentence the scene's comment and the export's summary carry: every pixel's expected linear sRGB, or why none.
std::string scene_pixel_note(const ScenePixel& pixel);

// Writes `stack` as `renderer`'s scene at `scene` and reads it back. InputError, before anything is written, for a
// wrong extension, a missing or read-only folder, or an existing file unless `overwrite` (the scene's and each
// spectrum file's); std::runtime_error when the files read back differ from the media (beyond 1e-12 relative).
SceneExport export_scene(const LayerStack& stack, const MediaRequest& request, SceneRenderer renderer, const std::filesystem::path& scene,
                         bool overwrite);

// The export as `skinspec export pbrt|mitsuba --json` prints it and skinspec.export_scene returns it: the files and
// per layer its thickness (mm), index, sigma_a and sigma_s (1/mm) per exported wavelength and its phase function.
nlohmann::ordered_json scene_export_json(const SceneExport& exported, SceneRenderer renderer);

}  // namespace skinspec
