#pragma once
// Layered media as a pbrt-v4 scene (file format: pbrt.org/fileformat-v4, "Media" and "Shapes"; Pharr, Jakob &
// Humphreys, PBR 4th ed., Sec. 11.3): one "homogeneous" named medium per layer (sigma_a, sigma_s in 1/mm for a
// scene in mm, g), each interface a large horizontal quad with the media below and above it (MediumInterface
// "interior" "exterior": interior is the side opposite the normal, +z) and a "dielectric" of the relative index
// (or "interface" where the indices match), the bottom a "diffuse" reflector of reflectance 1 or the last
// interface; a uniform D65 environment and an orthographic camera straight down (docs/EXPORT.md: a scene a path
// tracer renders as it is, every pixel the slab's R). pbrt-v4 media take Henyey-Greenstein only.
#include <filesystem>
#include <string_view>
#include <vector>

#include "formats/renderer_media.hpp"

namespace skinspec {

// Every file write_pbrt_scene writes (the scene, then the spectrum files of spectral media).
std::vector<std::filesystem::path> pbrt_scene_files(const RendererMedia& media, const std::filesystem::path& scene);
// InputError for a phase function pbrt-v4 cannot take (tabulated). Writes the spectrum files, then the scene,
// each atomically; existing files are replaced (the caller checks pbrt_scene_files first). `note`: one more line of
// the scene's header comment (what the render should show), none when empty.
void write_pbrt_scene(const RendererMedia& media, const std::filesystem::path& scene, std::string_view note = {});
// The media of a scene write_pbrt_scene wrote, read back through pbrt-v4's syntax (directives, typed parameter
// lists, spectrum files relative to the scene). `above_refractive_index`: the index the scene's outside stands
// for (pbrt-v4's dielectric "eta" is relative). InputError for anything else.
RendererMedia read_pbrt_scene(const std::filesystem::path& scene, double above_refractive_index = 1.0);

}  // namespace skinspec
