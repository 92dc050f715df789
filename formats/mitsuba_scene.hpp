#pragma once
// Layered media as a Mitsuba 3 scene (XML scene format, mitsuba.readthedocs.io "Scene format"; plugins
// "homogeneous" medium: sigma_t in inverse scene units and single-scattering albedo; phase "hg", "isotropic",
// "tabphase" (values over cos theta regularly spaced in [-1, 1]); "rectangle" shapes with "interior"/"exterior"
// media (exterior on the normal's side, +z) and a "dielectric" BSDF of absolute int_ior/ext_ior, or "null" where
// the indices match; "diffuse" bottom of reflectance 1). Scene in mm, coefficients in 1/mm; a uniform D65 environment
// ("constant" emitter) and an orthographic camera straight down (docs/EXPORT.md), rendered with the "volpath" integrator.
#include <filesystem>
#include <string_view>
#include <vector>

#include "formats/renderer_media.hpp"

namespace skinspec {

// Every file write_mitsuba_scene writes (the scene, then the spectrum files of spectral media).
std::vector<std::filesystem::path> mitsuba_scene_files(const RendererMedia& media, const std::filesystem::path& scene);
// Writes the spectrum files, then the scene, each atomically; existing files are replaced (the caller checks
// mitsuba_scene_files first).
// `note`: one more sentence of the scene's header comment (what the render should show), none when empty.
void write_mitsuba_scene(const RendererMedia& media, const std::filesystem::path& scene, std::string_view note = {});
// The media of a scene write_mitsuba_scene wrote, read back (pugixml); InputError for anything else.
RendererMedia read_mitsuba_scene(const std::filesystem::path& scene);

}  // namespace skinspec
