#include "cli/profile_shape_output.hpp"

#include <iostream>

#include "appearance/profile_shape_report.hpp"
#include "cli/spectral_output.hpp"

namespace skinspec::cli {

void print_profile_summary(const std::string& subject, const std::vector<ResultWarning>& warnings, const ProfileShapeCheck& shape) {
    print_warning_summary(subject, warnings);
    const char* level = profile_shape_warns(shape) ? "warning" : "note";
    for (const auto& line : profile_shape_lines(shape)) std::cerr << "skinspec: " << level << ": " << subject << ": " << line << '\n';
}

}  // namespace skinspec::cli
