#pragma once
// Images stored as one plane per spectral sample (or per RGB band) turned into scene-linear RGB.
#include <span>
#include <string_view>
#include <vector>

#include "spectral/chart_image.hpp"
#include "spectral/colorimetry.hpp"

namespace skinspec {

// Planes are reflectance-like factors at `wavelengths_nm` (held constant outside them); each pixel's
// spectrum is integrated against the illuminant and observer (XYZ with the illuminant's white at Y = 1),
// then converted to `working_space` through ColorManagement::from_xyz.
LinearImage spectral_planes_to_image(const std::vector<std::vector<float>>& planes, int width, int height,
                                     std::span<const double> wavelengths_nm, IlluminantKind illuminant, ObserverKind observer,
                                     std::string_view working_space, const ColorManagement& cm);

// Three planes that already are linear R, G, B in `band_space` (e.g. "Linear Rec.709"), converted to `working_space`.
LinearImage rgb_planes_to_image(const std::vector<std::vector<float>>& planes, int width, int height, std::string_view band_space,
                                std::string_view working_space, const ColorManagement& cm);

}  // namespace skinspec
