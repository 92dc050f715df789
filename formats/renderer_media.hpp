#pragma once
// A layered material as the participating media of a path tracer (pbrt-v4, Mitsuba 3; formats/pbrt_scene.hpp,
// formats/mitsuba_scene.hpp): per layer the volumetric model's coefficients (transport/rte/rte_model.hpp, the
// ones the volumetric walk and adding-doubling use) at each exported wavelength, in 1/mm for a scene in mm, its
// thickness, index and phase function. No physics here: rte_stack_from computes, this converts units and
// chooses what the renderers can take.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "materials/layer_stack.hpp"
#include "spectral/wavelength_grid.hpp"

namespace skinspec {

// Phase functions renderers take: HG (both), isotropic (both), tabulated over cos theta (Mitsuba's tabphase).
struct RendererPhase {
    enum class Kind { henyey_greenstein, isotropic, tabulated };
    Kind kind = Kind::henyey_greenstein;
    double g = 0.0;                  // HG asymmetry; for the others their mean cosine
    std::vector<double> values;      // tabulated: p(cos theta) per sr at cos theta = -1 + 2 k / (n - 1)
    bool operator==(const RendererPhase&) const = default;
};

struct RendererLayer {
    std::string name;
    double thickness_mm = 0.0;
    double refractive_index = 1.0;
    std::vector<double> sigma_a_per_mm;  // one per exported wavelength (or R, G, B)
    std::vector<double> sigma_s_per_mm;
    RendererPhase phase;
    bool operator==(const RendererLayer&) const = default;
};

struct RendererMedia {
    std::string material;
    std::vector<double> wavelengths_nm;  // spectral: the exported wavelengths; RGB: the wavelengths taken as R, G, B
    bool rgb = false;
    double above_refractive_index = 1.0;
    double below_refractive_index = 1.0;
    bool bottom_reflector = true;        // an ideal Lambertian reflector below the last layer (R = 1)
    double phase_wavelength_nm = 550.0;  // phase functions are not spectral in either renderer: taken here
    std::vector<RendererLayer> layers;
    bool operator==(const RendererMedia&) const = default;
};

enum class PhaseExport {
    own,  // each layer's own phase (HG, isotropic, measured as tabulated); InputError for Rayleigh
    hg,   // every layer as HG with its phase function's mean cosine
};
std::string_view to_string(PhaseExport phase);  // "own", "hg"

// The spectral media's default wavelengths: the 360-830 nm that pbrt-v4 and Mitsuba 3 sample (a spectrum file is
// 0 outside its range in both, so narrower media vanish there), as --wavelengths text.
inline constexpr std::string_view renderer_sampled_wavelengths = "360:830:10";

// The scene both exports write around the media (docs/EXPORT.md): a uniform D65 environment and an orthographic
// camera straight down over scene_view_mm x scene_view_mm of the slab, scene_pixels square, scene_samples_per_pixel.
inline constexpr double scene_view_mm = 20.0;
inline constexpr int scene_pixels = 64;
inline constexpr int scene_samples_per_pixel = 256;

struct MediaRequest {
    std::vector<double> wavelengths_nm;  // spectral export, or exactly three (R, G, B) with rgb
    bool rgb = false;
    double phase_wavelength_nm = 550.0;
    PhaseExport phase = PhaseExport::own;
};

// How closely a tabulated phase's mean cosine, as a renderer interpolates the table, holds the profile's: the table
// is refined (181, 361, ... points over cos theta) until it does (181 points gave 0.9577 for 0.9591).
inline constexpr double tabulated_mean_cosine_tolerance = 1e-4;
// The mean cosine of p(cos theta) given at cos theta = -1 + 2 k / (n - 1) and interpolated linearly between (as
// Mitsuba 3's tabphase reads it).
double tabulated_mean_cosine(const std::vector<double>& values);

// InputError for a layer without volumetric scattering, a wavelength outside the material's data or an RGB
// export without exactly three wavelengths, and for Rayleigh scattering with PhaseExport::own.
RendererMedia renderer_media(const LayerStack& stack, const MediaRequest& request);

// The spread of each layer's mean cosine over the exported wavelengths: (smallest, largest) per layer.
std::vector<std::pair<double, double>> mean_cosine_spread(const LayerStack& stack, const std::vector<double>& wavelengths_nm);

// Spectrum files as pbrt-v4 and Mitsuba 3 read them: "wavelength value" pairs, one per line, '#' comments.
void write_spd_file(const std::filesystem::path& file, const std::vector<double>& wavelengths_nm, const std::vector<double>& values,
                    const std::string& comment);
// InputError naming the file and line for anything else.
std::pair<std::vector<double>, std::vector<double>> read_spd_file(const std::filesystem::path& file);

// Where a spectral export puts its spectrum files: `<scene stem>_spectra/` beside the scene; the file of
// `quantity` of `layer` is `<layer>_<quantity>.spd` in it, named in the scene relative to the scene's folder.
std::filesystem::path spectra_folder(const std::filesystem::path& scene);
std::filesystem::path spectrum_file_path(const std::filesystem::path& scene, const std::string& layer, const std::string& quantity);
std::string spectrum_file_reference(const std::filesystem::path& scene, const std::string& layer, const std::string& quantity);

// The scene and, for spectral media, the spectrum file of each layer and each of `quantities` (what a renderer's
// medium takes: pbrt-v4 sigma_a and sigma_s, Mitsuba 3 sigma_t and albedo).
std::vector<std::filesystem::path> scene_files(const RendererMedia& media, const std::filesystem::path& scene,
                                               const std::vector<std::string>& quantities);

}  // namespace skinspec
