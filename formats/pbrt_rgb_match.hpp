#pragma once
// RGB media that pbrt-v4 renders in the spectral media's colour. pbrt-v4 is spectral: it turns each RGB coefficient
// into a smooth spectrum of its own (spectral/rgb_uplift.hpp), which cannot follow blood's and melanin's absorption
// across a channel, so the coefficients at three wavelengths render 10 % low in red (issue 37). Here the absorption
// coefficients' R, G and B are scaled, one factor per channel for every layer, until the slab's linear sRGB under D65
// with those smooth spectra equals the spectral media's; both are solved by adding-doubling (normal incidence, R with
// the first-surface reflection: the measurement of bench/renderer_validation.py), so the match is as exact as the
// model of pbrt's conversion.
#include <array>

#include "formats/renderer_media.hpp"

namespace skinspec {

struct PbrtRgbMatch {
    RendererMedia media;                         // `point` with the absorption coefficients scaled
    std::array<double, 3> absorption_factors{};  // per channel, over the coefficients at the three wavelengths
    std::array<double, 3> spectral_srgb{};       // the slab's linear sRGB (D65): the spectral media (360-830 nm)
    std::array<double, 3> matched_srgb{};        // the matched RGB media as pbrt-v4 renders them
    std::array<double, 3> point_srgb{};          // the coefficients at the three wavelengths, as pbrt-v4 renders them
    double largest_relative_difference = 0.0;    // matched against spectral, over the channels
};

// The wavelengths the spectral side is solved at (the 360-830 nm pbrt-v4 samples).
inline constexpr std::string_view pbrt_rgb_match_wavelengths = renderer_sampled_wavelengths;
// Adding-doubling's channels on both sides (the quadrature's error is common to both and far below the match's).
inline constexpr std::size_t pbrt_rgb_match_channels = 16;
// The match stops within this relative difference per channel (or after 12 steps, reporting what it reached).
inline constexpr double pbrt_rgb_match_tolerance = 1e-5;

// `point`: the RGB media of `request` (renderer_media); the same phase functions are used on both sides.
PbrtRgbMatch match_pbrt_rgb(const LayerStack& stack, const MediaRequest& request, const RendererMedia& point);

}  // namespace skinspec
