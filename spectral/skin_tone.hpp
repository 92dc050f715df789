#pragma once
// Where a skin colour sits on the scale dermatology and cosmetics use: the individual typology angle
// ITA = atan((L* - 50) / b*) in degrees (Chardon, Cretois & Hourseau 1991, Int. J. Cosmet. Sci. 13:191, Eq. 1) and
// its six categories (Del Bino et al. 2006, Pigment Cell Res. 19:606, Table 1): very light > 55, light 41-55,
// intermediate 28-41, tan 10-28, brown -30-10, dark < -30 degrees. Computed from the Lab it is given (the papers
// measured under D65; the illuminant and observer are the caller's to state).
#include <optional>
#include <string_view>

#include "spectral/colorimetry.hpp"

namespace skinspec {

enum class SkinToneCategory { very_light, light, intermediate, tan, brown, dark };
std::string_view to_string(SkinToneCategory category);  // "very light", "light", ...

struct SkinTone {
    double ita_deg = 0.0;  // in (-90, 90)
    SkinToneCategory category = SkinToneCategory::intermediate;
    double ita_stderr_deg = 0.0;  // from the Lab standard uncertainties (L* and b* taken as uncorrelated)
};

// None where b* <= 0 (the angle leaves (-90, 90): not a skin colour, no category).
std::optional<SkinTone> skin_tone(const Lab& lab, const Lab& lab_stderr = {});

}  // namespace skinspec
