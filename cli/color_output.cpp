#include "cli/color_output.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "spectral/input_error.hpp"

namespace skinspec::cli {
namespace {

// OpenColorIO computes in 32-bit float: report RGB to the 6 decimals that carries.
nlohmann::ordered_json rgb_json(const RGB& rgb) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const double c : rgb) out.push_back(std::round(c * 1e6) / 1e6);
    return out;
}

}  // namespace

ColorSummary summarize_color(const XYZ& xyz, const TristimulusWeights& weights, IlluminantKind illuminant,
                             ObserverKind observer, const std::vector<std::string>& extra_spaces,
                             const std::optional<ColorUncertainty>& uncertainty) {
    const auto& cm = ColorManagement::builtin();
    ColorSummary s{illuminant, observer, xyz, weights.white(), chromaticity(xyz), xyz_to_lab(xyz, weights.white()),
                   cm.from_xyz(xyz, weights.white(), "sRGB"), true, "", cm.from_xyz(xyz, weights.white(), "Linear Rec.709"),
                   cm.from_xyz(xyz, weights.white(), "ACEScg"), {}, {}, {}};
    // OCIO computes in float32: XYZ beyond ~1e38 (values of 1e100 with --allow-over-one) gives no colour.
    const auto finite = [](const RGB& v) { return std::all_of(v.begin(), v.end(), [](double c) { return std::isfinite(c); }); };
    if (!std::isfinite(s.xyz.X) || !std::isfinite(s.xyz.Y) || !std::isfinite(s.xyz.Z) || !finite(s.srgb) || !finite(s.linear_rec709) || !finite(s.acescg) ||
        !std::isfinite(s.lab.L) || std::abs(s.lab.L) > 1e30) {
        throw InputError(fmt::format("the colour of XYZ {:.3g} {:.3g} {:.3g} is outside what colour management computes (float32: values up to ~1e30)",
                                     s.xyz.X, s.xyz.Y, s.xyz.Z));
    }
    s.srgb_in_gamut = std::all_of(s.srgb.begin(), s.srgb.end(), [](double c) { return c >= 0.0 && c <= 1.0; });
    s.srgb_hex = hex_rgb8(s.srgb);
    for (const auto& space : extra_spaces) {
        const auto name = cm.canonical_space(space, "--space");
        s.extra_spaces[name] = cm.from_xyz(xyz, weights.white(), name);
    }
    if (uncertainty) {
        s.uncertainty = ColorSpread{uncertainty->lab, uncertainty->delta_e2000, rgb_uncertainty(xyz, weights.white(), uncertainty->xyz_covariance, "sRGB")};
    }
    s.skin_tone = skin_tone(s.lab, s.uncertainty ? s.uncertainty->lab : Lab{});
    return s;
}

nlohmann::ordered_json to_json(const ColorSummary& s) {
    nlohmann::ordered_json j;
    j["illuminant"] = std::string(short_name(s.illuminant));
    j["observer"] = std::string(display_name(s.observer));
    j["XYZ"] = {s.xyz.X, s.xyz.Y, s.xyz.Z};
    j["white_XYZ"] = {s.white.X, s.white.Y, s.white.Z};
    j["xy"] = {s.xy.x, s.xy.y};
    j["Lab"] = {s.lab.L, s.lab.a, s.lab.b};
    if (s.uncertainty) {
        const auto& u = *s.uncertainty;
        j["Lab_uncertainty"] = {u.lab.L, u.lab.a, u.lab.b};
        j["delta_e2000_uncertainty"] = u.delta_e2000;
        j["srgb_uncertainty"] = rgb_json(u.srgb);
        j["uncertainty_meaning"] = "standard uncertainties, R's standard errors (and a solver's stated error, common to every wavelength) propagated linearly through the CIE integrals";
    }
    if (s.skin_tone) {
        j["ITA_deg"] = s.skin_tone->ita_deg;
        if (s.uncertainty) j["ITA_uncertainty_deg"] = s.skin_tone->ita_stderr_deg;
        j["skin_tone_category"] = std::string(to_string(s.skin_tone->category));
        j["skin_tone_meaning"] = "individual typology angle atan((L* - 50) / b*) (Chardon et al. 1991) under this illuminant and observer; categories of Del Bino et al. 2006";
    }
    j["srgb"] = rgb_json(s.srgb);
    j["srgb_hex"] = s.srgb_hex;
    j["srgb_in_gamut"] = s.srgb_in_gamut;
    j["linear_rec709"] = rgb_json(s.linear_rec709);
    j["acescg"] = rgb_json(s.acescg);
    if (!s.extra_spaces.empty()) {
        auto& spaces = j["spaces"];
        for (const auto& [name, rgb] : s.extra_spaces) spaces[name] = rgb_json(rgb);
    }
    return j;
}

std::string to_table(const ColorSummary& s) {
    const auto row = [](std::string_view label, const RGB& v) {
        return fmt::format("{:<16}{:9.6f} {:9.6f} {:9.6f}\n", label, v[0], v[1], v[2]);
    };
    std::string out;
    out += fmt::format("{:<16}{} (observer {}; white XYZ {:.5f} {:.5f} {:.5f})\n", "illuminant", short_name(s.illuminant),
                       display_name(s.observer), s.white.X, s.white.Y, s.white.Z);
    out += row("XYZ", {s.xyz.X, s.xyz.Y, s.xyz.Z});
    out += fmt::format("{:<16}{:9.6f} {:9.6f}\n", "xy", s.xy.x, s.xy.y);
    out += fmt::format("{:<16}{:9.4f} {:9.4f} {:9.4f}\n", "Lab", s.lab.L, s.lab.a, s.lab.b);
    if (s.uncertainty) {
        out += fmt::format("{:<16}{:9.4f} {:9.4f} {:9.4f}   (standard uncertainty; CIEDE2000 {:.4f})\n", "  +-", s.uncertainty->lab.L,
                           s.uncertainty->lab.a, s.uncertainty->lab.b, s.uncertainty->delta_e2000);
    }
    if (s.skin_tone) {
        out += fmt::format("{:<16}{:9.2f}{} deg: {} (individual typology angle, Chardon et al. 1991; categories of Del Bino et al. 2006)\n", "ITA",
                           s.skin_tone->ita_deg, s.uncertainty ? fmt::format(" +- {:.2f}", s.skin_tone->ita_stderr_deg) : std::string(),
                           to_string(s.skin_tone->category));
    }
    out += row("sRGB", s.srgb);
    if (s.uncertainty) out += row("  +-", s.uncertainty->srgb);
    out += fmt::format("{:<16}{}{}\n", "sRGB hex", s.srgb_hex,
                       s.srgb_in_gamut ? "" : "  (outside the sRGB gamut: channels clipped to [0, 1] for the hex code)");
    out += row("Linear Rec.709", s.linear_rec709);
    out += row("ACEScg", s.acescg);
    for (const auto& [name, rgb] : s.extra_spaces) out += row(name, rgb);
    return out;
}

std::string delta_e_target_text(double worst, double target, std::uint64_t rays) {
    if (worst <= target) return fmt::format("target {}", target);
    return fmt::format("target {} NOT met: {}", target, rays == 0 ? "the solver's own stated error" : "the ray budget (--max-rays) was spent");
}

}  // namespace skinspec::cli
