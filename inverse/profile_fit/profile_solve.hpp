#pragma once
// The profile at the distance bins from l = W r (Mukaigawa et al. 2009 Eq. 24): r = W^+ l, the minimum-norm least-squares
// solution (Eigen's complete orthogonal decomposition), as in the paper. Options, both off by default:
// Tikhonov regularisation (min |W r - l|^2 + lambda^2 |r|^2) and non-negativity (r >= 0, bounded L-BFGS
// through NLopt from the clipped unconstrained solution).
#include <vector>

#include "inverse/profile_fit/profile_system.hpp"

namespace skinspec {

struct ProfileSolveOptions {
    double tikhonov_lambda = 0.0;
    bool non_negative = false;
};

struct ProfileEstimate {
    std::vector<double> distances_mm;
    std::vector<double> profile_per_mm2;  // R'_i
    std::vector<char> has_data;           // bins some patch pair falls near
    double residual_norm = 0.0;           // |W r - l|
    long rank = 0;                        // numerical rank of W
};

// InputError for a negative or non-finite lambda.
ProfileEstimate solve_profile(const ProfileSystem& system, const ProfileSolveOptions& options = {});

}  // namespace skinspec
