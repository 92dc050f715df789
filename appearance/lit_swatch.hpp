#pragma once
// A lit swatch (`skinspec swatch --lit`, skinspec.lit_swatch): one flat patch of a material under structured light
// (appearance/lit_patch.hpp) as a linear RGB image in a working space, and its files (linear OpenEXR, or a labelled
// display-referred PNG / TIFF through OpenColorIO).
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "appearance/lit_patch.hpp"
#include "spectral/chart_image.hpp"

namespace skinspec {

// A view `field_mm` wide in `pixels` (square); InputError for a field outside (0, 1000] mm.
PatchGeometry lit_view(double field_mm, int pixels);
// Lighting by an image (linear Rec.709): its luminance is the relative irradiance; the view takes the image's
// aspect (its height in pixels follows the width).
Illumination pattern_lighting(const LinearImage& image, PatchGeometry& view);

struct LitSwatch {
    LitPatch patch;
    LinearImage image;  // linear RGB in the request's working space (empty when partial)
    bool bands = false;  // a band material (R, G, B exitance planes) rather than wavelengths
};

// The patch's exitance and its colour image (per wavelength integrated against the observer under the illuminant;
// a band material's three bands taken as linear Rec.709). InputError for a band material without exactly three
// bands. Stopped through `cancel`: partial, no image.
LitSwatch render_lit_swatch(const Material& material, const WavelengthGrid& wavelengths, const Illumination& light, const PatchGeometry& view,
                            const SpectralSolver& solver, const ProfileRequest& settings, MeasurementGeometry geometry, IlluminantKind illuminant,
                            ObserverKind observer,
                            const std::string& space, const std::function<void(std::size_t done, std::size_t total)>& on_progress = {},
                            const std::atomic<bool>* cancel = nullptr);

// Writes the swatch's image to every file of `outputs` (as check_image_outputs returned them; the display-referred
// ones labelled, the geometry in the label), with its provenance (material, model, geometry, lighting, field, wavelengths) and, unless empty, the profiles'
// stated shape error (metadata skinspec:profile_shape).
void write_lit_swatch(const LitSwatch& swatch, const std::string& material, const Illumination& light, double field_mm,
                      const std::string& wavelengths_text, const ImageOutputs& outputs, const std::string& profile_shape = {});

}  // namespace skinspec
