#pragma once
// A flat patch of a translucent material under structured light, from a solver's radial profiles (by default the
// exact transport, the volumetric walk; or a diffusion mode): the diffuse exitance is
// the illumination convolved with the material's radial reflectance profile (Jensen et al. 2001 Eq. 5 and Donner & Jensen 2005
// Eq. 17 integrated over the surface for uniform angular response), per wavelength or band. The convolution
// runs through FFTW (real-to-complex 2-D transforms). The specular first-surface reflection is not included
// (it depends on the viewing direction) unless the geometry is sci, which counts it as an integrating sphere does (the
// first-surface reflectance times the irradiance at each point); see docs/PROFILES.md, "One geometry".
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "solvers/spectral_solver.hpp"

namespace skinspec {

struct PatchGeometry {
    int width_px = 256;
    int height_px = 256;
    double pixel_mm = 0.08;
};

// Relative irradiance (1 = fully lit) over the plane; the view is centred on the origin.
class Illumination {
public:
    static Illumination spot(double radius_mm);  // a lit disc centred in the view
    static Illumination edge();                   // lit for x > 0: a sharp shadow edge down the middle
    // An image (relative irradiance per pixel, row-major, top row first) filling the view; dark outside.
    static Illumination pattern(std::vector<float> irradiance, int width_px, int height_px);

    // Pixel-averaged irradiance (8 x 8 samples per pixel) on the view's pixel grid widened by `margin` pixels
    // on every side, row-major.
    std::vector<double> rasterize(const PatchGeometry& view, int margin) const;
    std::string description() const;

private:
    enum class Kind { spot, edge, pattern } kind_ = Kind::spot;
    double radius_mm_ = 1.0;
    std::vector<float> image_;
    int image_w_ = 0, image_h_ = 0;
};

struct LitPatch {
    PatchGeometry geometry;
    SpectralProfiles profiles;                 // the profiles used (radii up to the kernel's reach)
    std::vector<std::vector<float>> exitance;  // per channel, view pixels row-major: diffuse exitance / irradiance scale
    int kernel_radius_px = 0;
    // Largest share of a channel's total diffuse reflectance outside the kernel or lost to sampling, put back
    // at the kernel's centre so that energy is conserved.
    double largest_kernel_correction = 0.0;
    MeasurementGeometry geometry_measured = MeasurementGeometry::sce;  // what the exitance counts (sci: the first-surface reflection too)
    bool partial = false;
};

// InputError for a view outside [8, 4096] pixels a side or a pitch outside (0, 100] mm.
// `settings`: the solver's switches and Monte Carlo settings (precision, budget or count, seed, what the user gave); its
// wavelengths, radii and progress are the patch's own. `geometry`: sce or sci (InputError for 0-45: a lit patch has
// light leaving at every angle).
LitPatch render_lit_patch(const Material& material, const WavelengthGrid& wavelengths, const Illumination& light,
                          const PatchGeometry& view, const SpectralSolver& solver, const ProfileRequest& settings, MeasurementGeometry geometry,
                          const std::function<void(std::size_t done, std::size_t total)>& on_progress = {},
                          const std::atomic<bool>* cancel = nullptr);

}  // namespace skinspec
