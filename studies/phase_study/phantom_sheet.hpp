#pragma once
// Phantom sheets (Baranoski et al. 2005 Sec. 4, Figs. 10-12): a Lambertian textured background seen through a thin
// forward-scattering sheet at a separation s. Each viewing ray crosses the sheet along its normal, is
// deflected once by the sheet's profile (polar angle theta, uniform azimuth) and meets the background at
// a lateral offset s tan(theta); rays turned back (theta >= 90 deg) see nothing. Orthographic view.
#include <cstdint>
#include <vector>

#include "studies/phase_study/phase_sampling.hpp"
#include "spectral/chart_image.hpp"

namespace skinspec {

// The background: scene-linear RGB, sampled bilinearly with clamped edges.
using Texture = LinearImage;

struct PhantomView {
    double background_width = 8.0;  // length units covered by the texture (and by the view)
    double separation = 0.9;        // sheet-to-background distance, same units
    int width_px = 192;
    int height_px = 192;
    int samples_per_pixel = 32;
    std::uint64_t seed = 1;
};

// Scene-linear RGB, width_px x height_px, parallel over rows (oneTBB), reproducible for a seed.
LinearImage render_phantom(const Texture& background, const AngleSampler& sheet, const PhantomView& view);

}  // namespace skinspec
