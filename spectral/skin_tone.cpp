#include "spectral/skin_tone.hpp"

#include <cmath>
#include <numbers>

namespace skinspec {

std::string_view to_string(SkinToneCategory category) {
    switch (category) {
        case SkinToneCategory::very_light: return "very light";
        case SkinToneCategory::light: return "light";
        case SkinToneCategory::intermediate: return "intermediate";
        case SkinToneCategory::tan: return "tan";
        case SkinToneCategory::brown: return "brown";
        case SkinToneCategory::dark: return "dark";
    }
    return "intermediate";
}

std::optional<SkinTone> skin_tone(const Lab& lab, const Lab& lab_stderr) {
    if (!(lab.b > 0.0) || !std::isfinite(lab.L)) return std::nullopt;
    constexpr double deg = 180.0 / std::numbers::pi;
    const double x = (lab.L - 50.0) / lab.b;
    SkinTone t;
    t.ita_deg = std::atan(x) * deg;  // Chardon et al. 1991, Eq. 1
    // Del Bino et al. 2006, Table 1 (a boundary belongs to the lighter class).
    if (t.ita_deg > 55.0) t.category = SkinToneCategory::very_light;
    else if (t.ita_deg > 41.0) t.category = SkinToneCategory::light;
    else if (t.ita_deg > 28.0) t.category = SkinToneCategory::intermediate;
    else if (t.ita_deg > 10.0) t.category = SkinToneCategory::tan;
    else if (t.ita_deg > -30.0) t.category = SkinToneCategory::brown;
    else t.category = SkinToneCategory::dark;
    // d(ITA) = (b dL - (L - 50) db) / (b^2 + (L - 50)^2) radians.
    const double r2 = lab.b * lab.b + (lab.L - 50.0) * (lab.L - 50.0);
    t.ita_stderr_deg = deg * std::sqrt(std::pow(lab.b * lab_stderr.L, 2) + std::pow((lab.L - 50.0) * lab_stderr.b, 2)) / r2;
    return t;
}

}  // namespace skinspec
