#pragma once
// Colour summaries shared by every command that reports colours: one computation, two renderings
// (a readable table and JSON).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "spectral/color_management.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/colorimetry.hpp"
#include "spectral/skin_tone.hpp"

namespace skinspec::cli {

// Standard uncertainties of a colour (spectral/color_uncertainty.hpp: linear propagation through the CIE integrals).
struct ColorSpread {
    Lab lab;
    double delta_e2000 = 0.0;  // RMS CIEDE2000 from the true colour
    RGB srgb{};                // of the encoded sRGB values (its Jacobian by central differences of the OCIO transform)
};

struct ColorSummary {
    IlluminantKind illuminant;
    ObserverKind observer;
    XYZ xyz;
    XYZ white;
    Chromaticity xy;
    Lab lab;
    RGB srgb;            // encoded, unclipped
    bool srgb_in_gamut;  // all three channels in [0, 1]
    std::string srgb_hex;  // from sRGB clipped to [0, 1] (clipping reported by srgb_in_gamut)
    RGB linear_rec709;
    RGB acescg;
    std::map<std::string, RGB> extra_spaces;  // spaces asked for with --space
    std::optional<ColorSpread> uncertainty;   // when the spectrum came with standard errors or a stated error
    std::optional<SkinTone> skin_tone;        // ITA and its category (none where b* <= 0)
};

ColorSummary summarize_color(const XYZ& xyz, const TristimulusWeights& weights, IlluminantKind illuminant,
                             ObserverKind observer, const std::vector<std::string>& extra_spaces,
                             const std::optional<ColorUncertainty>& uncertainty = std::nullopt);

nlohmann::ordered_json to_json(const ColorSummary& summary);
std::string to_table(const ColorSummary& summary);

// "target T", or "target T NOT met: " and why, for a chart's or a texture's worst colour uncertainty: above the target a
// deterministic solver's stated error (no rays to add) or a spent ray budget is the cause.
std::string delta_e_target_text(double worst, double target, std::uint64_t rays);

}  // namespace skinspec::cli
