#pragma once
// The smooth spectrum a spectral renderer makes of an RGB coefficient: Jakob & Hanika 2019 ("A Low-Dimensional
// Function Space for Efficient Spectral Upsampling", Computer Graphics Forum 38(2):147, Eqs. 3-4), a sigmoid of a
// quadratic in wavelength whose linear sRGB under D65 (CIE 1931 2 degrees) is the given one, scaled as pbrt-v4's
// RGBUnboundedSpectrum scales it (Pharr, Jakob & Humphreys 2023, Physically Based Rendering 4th ed., Sec. 4.6.6:
// s = 2 max(r, g, b), the sigmoid fitted to rgb / s). pbrt-v4 interpolates precomputed fits; this solves each one.
#include <array>

#include "spectral/colorimetry.hpp"

namespace skinspec {

// Linear sRGB (IEC 61966-2-1 primaries, D65 white) of CIE XYZ.
std::array<double, 3> linear_srgb(const XYZ& xyz);

class UpliftedSpectrum {
public:
    // InputError for a negative or non-finite component (renderers' coefficients are non-negative).
    explicit UpliftedSpectrum(const std::array<double, 3>& linear_srgb);
    double operator()(double wavelength_nm) const;
    double scale() const { return scale_; }

private:
    double scale_ = 0.0;
    std::array<double, 3> c_{};  // the quadratic's coefficients in t = (lambda - 360 nm) / 470 nm: c0 t^2 + c1 t + c2
};

}  // namespace skinspec
