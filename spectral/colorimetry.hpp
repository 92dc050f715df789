#pragma once
// Spectrum -> CIE XYZ -> xy and CIELAB (CIE 015:2018). Reflectance or transmittance factors are integrated
// against illuminant x observer at the 1 nm spacing of the CIE tables, normalised so that the perfect
// reflector has Y = 1.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "spectral/cie.hpp"
#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

struct XYZ {
    double X = 0.0;
    double Y = 0.0;
    double Z = 0.0;
};

struct Chromaticity {
    double x = 0.0;
    double y = 0.0;
};

struct Lab {
    double L = 0.0;
    double a = 0.0;
    double b = 0.0;
};

// CIE 015:2018 Eq. 7.3: x = X / (X + Y + Z), y = Y / (X + Y + Z); (0, 0) for black.
Chromaticity chromaticity(const XYZ& xyz);
// CIE 015:2018 Eq. 8.1-8.3 (CIELAB), relative to the reference white `white` (Y_n = 1 scale).
Lab xyz_to_lab(const XYZ& xyz, const XYZ& white);

// A reflectance sampled at `nm` (increasing) has a trustworthy colour when the samples span 400-700 nm and are at
// most max_color_step_nm apart (linear interpolation across a wider gap would misstate it).
inline constexpr double max_color_step_nm = 20.0;
bool has_color_span(std::span<const double> nm);
// Why `nm` has no colour ("a colour needs wavelengths covering 400-700 nm ... (these cover 500-600 nm)"); empty when it has.
std::string color_span_problem(std::span<const double> nm);

// Linear map from samples of a spectrum to XYZ. The spectrum is taken as piecewise-linear between its
// samples and treated outside them by `outside`, then summed at 1 nm over 360-830 nm with the illuminant
// and observer (CIE 015:2018 Eq. 7.1-7.2, k chosen so the perfect reflector has Y = 1). Because the
// interpolation is linear in the samples, XYZ = W r exactly: the same weights propagate standard errors.
class TristimulusWeights {
public:
    TristimulusWeights(std::span<const double> sample_wavelengths_nm, IlluminantKind illuminant,
                       ObserverKind observer, OutOfRangePolicy outside);

    XYZ integrate(std::span<const double> samples) const;
    // Weights of X, Y, Z for sample i.
    std::array<double, 3> weights(std::size_t i) const { return weights_[i]; }
    std::size_t size() const { return weights_.size(); }
    // XYZ of the perfect reflector (Y = 1): the reference white for CIELAB and chromatic adaptation.
    const XYZ& white() const { return white_; }

private:
    std::vector<std::array<double, 3>> weights_;
    XYZ white_;
};

// XYZ of a tabulated spectrum at its own samples, with its own out-of-range policy.
XYZ spectrum_to_xyz(const TabulatedSpectrum& spectrum, IlluminantKind illuminant, ObserverKind observer);

}  // namespace skinspec
