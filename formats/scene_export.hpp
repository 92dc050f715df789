#pragma once
// A layered skin written as a renderer's scene and read back (`skinspec export pbrt|mitsuba`, skinspec.export_scene):
// the media (formats/renderer_media.hpp) as a pbrt-v4 or Mitsuba 3 lit-slab scene (formats/pbrt_scene.hpp,
// formats/mitsuba_scene.hpp), every output checked before anything is written, and the written files read back to
// check that they hold the coefficients they were given.
#include <filesystem>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

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

struct SceneExport {
    RendererMedia media;
    std::vector<std::filesystem::path> files;                       // the scene, then its spectrum files
    std::vector<std::pair<double, double>> mean_cosine_spread;      // per layer over the exported wavelengths
    double read_back_difference = 0.0;                              // largest relative difference written vs read
    PhaseApproximationError phase_error;
};

// Writes `stack` as `renderer`'s scene at `scene` and reads it back. InputError, before anything is written, for a
// wrong extension, a missing or read-only folder, or an existing file unless `overwrite` (the scene's and each
// spectrum file's); std::runtime_error when the files read back differ from the media (beyond 1e-12 relative).
SceneExport export_scene(const LayerStack& stack, const MediaRequest& request, SceneRenderer renderer, const std::filesystem::path& scene,
                         bool overwrite);

// The export as `skinspec export pbrt|mitsuba --json` prints it and skinspec.export_scene returns it: the files and
// per layer its thickness (mm), index, sigma_a and sigma_s (1/mm) per exported wavelength and its phase function.
nlohmann::ordered_json scene_export_json(const SceneExport& exported, SceneRenderer renderer);

}  // namespace skinspec
