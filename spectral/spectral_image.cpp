#include "spectral/spectral_image.hpp"

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {
void check_planes(const std::vector<std::vector<float>>& planes, std::size_t expected, int width, int height) {
    if (planes.size() != expected) throw InputError("image: " + std::to_string(planes.size()) + " planes, expected " + std::to_string(expected));
    for (const auto& p : planes) {
        if (p.size() != static_cast<std::size_t>(width) * height) throw InputError("image: a plane does not match the image size");
    }
}
}  // namespace

LinearImage spectral_planes_to_image(const std::vector<std::vector<float>>& planes, int width, int height,
                                     std::span<const double> wavelengths_nm, IlluminantKind illuminant, ObserverKind observer,
                                     std::string_view working_space, const ColorManagement& cm) {
    check_planes(planes, wavelengths_nm.size(), width, height);
    const TristimulusWeights weights(wavelengths_nm, illuminant, observer, OutOfRangePolicy::hold);
    LinearImage out{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 3)};
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) {
        XYZ xyz{0.0, 0.0, 0.0};
        for (std::size_t i = 0; i < planes.size(); ++i) {
            const auto w = weights.weights(i);
            const double v = planes[i][p];
            xyz.X += w[0] * v;
            xyz.Y += w[1] * v;
            xyz.Z += w[2] * v;
        }
        const auto rgb = cm.from_xyz(xyz, weights.white(), working_space);
        for (int c = 0; c < 3; ++c) out.rgb[p * 3 + c] = static_cast<float>(rgb[c]);
    }
    return out;
}

LinearImage rgb_planes_to_image(const std::vector<std::vector<float>>& planes, int width, int height, std::string_view band_space,
                                std::string_view working_space, const ColorManagement& cm) {
    check_planes(planes, 3, width, height);
    LinearImage out{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 3)};
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) {
        for (int c = 0; c < 3; ++c) out.rgb[p * 3 + c] = planes[c][p];
    }
    cm.convert_pixels(out.rgb, band_space, working_space);
    return out;
}

}  // namespace skinspec
