#pragma once
// A command's profiles on the terminal: their warnings, then the R(r) shape check (appearance/profile_shape_report.hpp).
#include <string>
#include <vector>

#include "solvers/profile_shape_check.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec::cli {

// print_warning_summary of the profiles' warnings, their precision (a Monte Carlo profile), then the check's lines on
// standard error: a warning when profile_shape_warns, else a note.
void print_profile_summary(const SpectralProfiles& profiles, const ProfileShapeCheck& shape);

}  // namespace skinspec::cli
