#pragma once
// The whole estimation of Mukaigawa et al. 2009 for one channel: quantised system, r = W^+ l, dipole fit, re-synthesis and
// PSNR; or, for a measured radial profile, the dipole fit alone.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inverse/profile_fit/dipole_fit.hpp"
#include "inverse/profile_fit/profile_solve.hpp"

namespace skinspec {

struct ProfileFitOptions {
    double step_mm = 0.1;
    ProfileSolveOptions solve;
    DipoleFitOptions dipole;
    double fit_from_mm = 0.0;  // bins (or radii) closer than this are left out of the dipole fit
};

struct ProfileFitReport {
    ProfileEstimate estimate;            // R'(d_i) per bin (for radial input: the given profile)
    std::vector<char> fitted_bins;       // bins used by the dipole fit
    DipoleFitResult fit;
    std::vector<double> fitted_profile;  // the fitted dipole at the bins
    std::vector<double> synthesised;     // Eq. 10 with the fitted dipole (image inputs; empty for radial)
    std::optional<double> psnr_db;       // re-synthesis against the input (image inputs)
};

ProfileFitReport fit_planar(const PlanarScene& scene, const ProfileFitOptions& options);
ProfileFitReport fit_patches(const std::vector<SurfacePatch>& patches, const ProfileFitOptions& options);
// InputError for radii that are negative, non-finite or not increasing, or values that are not finite.
ProfileFitReport fit_radial(const std::vector<double>& radii_mm, const std::vector<double>& profile_per_mm2, const ProfileFitOptions& options);

// One channel's fit as `skinspec fit-profile --json` reports it and skinspec.fit_profile returns it.
nlohmann::ordered_json profile_fit_json(const ProfileFitReport& report, const std::string& channel);

}  // namespace skinspec
