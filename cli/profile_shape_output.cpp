#include "cli/profile_shape_output.hpp"

#include <iostream>

#include "appearance/profile_shape_report.hpp"
#include "cli/spectral_output.hpp"

namespace skinspec::cli {

void print_profile_summary(const SpectralProfiles& profiles, const ProfileShapeCheck& shape) {
    const auto& subject = profiles.material;
    print_warning_summary(subject, profiles.warnings);
    if (const auto precision = profile_precision_line(profiles); !precision.empty()) std::cerr << "skinspec: note: " << subject << ": " << precision << '\n';
    const char* level = profile_shape_warns(shape) ? "warning" : "note";
    for (const auto& line : profile_shape_lines(shape)) std::cerr << "skinspec: " << level << ": " << subject << ": " << line << '\n';
}

}  // namespace skinspec::cli
