#pragma once
// Colour management through OpenColorIO with skinspec's own config (data/ocio/config.ocio), whose
// reference space is CIE-XYZ-D65 (D65 white xy = 0.3127, 0.3290 at Y = 1).
//
// XYZ computed under another illuminant (or another observer, whose D65 white differs slightly from the
// nominal one) is first Bradford-adapted from that computation's own white to the config's D65 white, so
// the perfect reflector always maps to RGB (1, 1, 1) in every D65 space. Only then does OCIO transform it.
#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/colorimetry.hpp"

namespace skinspec {

using RGB = std::array<double, 3>;

// "#RRGGBB" of an encoded (display) RGB, each component clipped to [0, 1] and rounded to 8 bits.
std::string hex_rgb8(const RGB& encoded);

class ColorManagement {
public:
    explicit ColorManagement(const std::filesystem::path& config_file);
    ~ColorManagement();
    ColorManagement(const ColorManagement&) = delete;
    ColorManagement& operator=(const ColorManagement&) = delete;

    // The config shipped in data/ocio/config.ocio, loaded once.
    static const ColorManagement& builtin();

    // Reference white of the config: D65 (ITU-R BT.709) at Y = 1.
    static XYZ reference_white();

    const std::filesystem::path& config_file() const { return config_file_; }
    std::vector<std::string> color_spaces() const;
    std::vector<std::string> displays() const;
    std::vector<std::string> views(std::string_view display) const;
    // InputError naming --display or --view, the value and the allowed names, unless `display` is a display of the
    // config and `view` one of its views (OCIO's own message for a bad view was "Display color space name is unspecified").
    void check_display_view(std::string_view display, std::string_view view) const;
    // The config's own spelling of a colour space name given case-insensitively; InputError listing the
    // available spaces when unknown. `what` names the option in the message.
    std::string canonical_space(std::string_view name, std::string_view what) const;

    // XYZ whose perfect reflector is `white` -> colour space `space`, through an OCIO processor.
    RGB from_xyz(const XYZ& xyz, const XYZ& white, std::string_view space) const;
    // Any space -> any space (OCIO processor).
    RGB convert(const RGB& rgb, std::string_view from_space, std::string_view to_space) const;
    // In place over packed RGB floats (an image), one OCIO processor for all pixels.
    void convert_pixels(std::vector<float>& rgb, std::string_view from_space, std::string_view to_space) const;
    void display_view_pixels(std::vector<float>& rgb, std::string_view from_space, std::string_view display,
                             std::string_view view) const;
    // Scene-linear `from_space` -> display-referred values through the display/view transform.
    RGB display_view(const RGB& rgb, std::string_view from_space, std::string_view display, std::string_view view) const;

    struct Impl;  // OCIO state; defined in the .cpp

private:
    std::filesystem::path config_file_;
    std::unique_ptr<Impl> impl_;
};

}  // namespace skinspec
