#include "inverse/profile_fit/profile_fit.hpp"

#include <cmath>

#include <fmt/format.h>

#include "transport/diffusion/dipole.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// The dipole fit over the bins with data from `fit_from_mm` on, and the fitted profile at every bin.
void fit_estimate(ProfileFitReport& report, const ProfileFitOptions& options) {
    const auto& e = report.estimate;
    report.fitted_bins.resize(e.distances_mm.size());
    for (std::size_t i = 0; i < e.distances_mm.size(); ++i) report.fitted_bins[i] = e.has_data[i] && e.distances_mm[i] >= options.fit_from_mm;
    report.fit = fit_dipole(e.distances_mm, e.profile_per_mm2, report.fitted_bins, options.dipole);
    const Dipole dipole({report.fit.reduced_scattering_per_mm, report.fit.absorption_per_mm, options.dipole.eta});
    for (const double d : e.distances_mm) report.fitted_profile.push_back(dipole.radial_reflectance(d));
}

std::function<double(double)> fitted(const ProfileFitReport& report, double eta) {
    const Dipole dipole({report.fit.reduced_scattering_per_mm, report.fit.absorption_per_mm, eta});
    return [dipole](double d) { return dipole.radial_reflectance(d); };
}

// A fit needs light in and light out: all-zero inputs gave a "fitted" profile of nothing.
void require_light(const std::vector<double>& values, const std::vector<char>& used, const char* what) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if ((used.empty() || used[i]) && values[i] > 0.0) return;
    }
    throw InputError(std::string("the ") + what + " is zero everywhere it is used: there is no light to fit");
}

}  // namespace

ProfileFitReport fit_planar(const PlanarScene& scene, const ProfileFitOptions& options) {
    require_light(scene.incident, {}, "irradiance");
    require_light(scene.observed, scene.valid, "observed exitance");
    ProfileFitReport report;
    report.estimate = solve_profile(planar_system(scene, options.step_mm), options.solve);
    fit_estimate(report, options);
    report.synthesised = render_planar(scene, fitted(report, options.dipole.eta));
    report.psnr_db = psnr_db(scene.observed, report.synthesised, scene.valid);
    return report;
}

ProfileFitReport fit_patches(const std::vector<SurfacePatch>& patches, const ProfileFitOptions& options) {
    std::vector<double> incident, observed_light;
    std::vector<char> visible;
    for (const auto& p : patches) {
        incident.push_back(p.incident);
        observed_light.push_back(p.observed);
        visible.push_back(p.visible ? 1 : 0);
    }
    require_light(incident, {}, "incident light of the patches");
    require_light(observed_light, visible, "observed light of the patches");
    ProfileFitReport report;
    report.estimate = solve_profile(patch_system(patches, options.step_mm), options.solve);
    fit_estimate(report, options);
    report.synthesised = render_patches(patches, fitted(report, options.dipole.eta));
    std::vector<double> observed;
    std::vector<char> used;
    for (const auto& p : patches) {
        observed.push_back(p.observed);
        used.push_back(p.visible ? 1 : 0);
    }
    report.psnr_db = psnr_db(observed, report.synthesised, used);
    return report;
}

ProfileFitReport fit_radial(const std::vector<double>& radii_mm, const std::vector<double>& profile, const ProfileFitOptions& options) {
    if (radii_mm.size() != profile.size() || radii_mm.empty()) throw InputError("radial profile: no samples, or radii and values differ in number");
    require_light(profile, {}, "radial profile");
    for (std::size_t i = 0; i < radii_mm.size(); ++i) {
        if (!std::isfinite(radii_mm[i]) || radii_mm[i] < 0.0) throw InputError("radial profile: r = " + format_number(radii_mm[i]) + " mm is outside [0, inf)");
        if (i > 0 && radii_mm[i] <= radii_mm[i - 1]) throw InputError("radial profile: radii must increase (" + format_number(radii_mm[i]) + " mm after " + format_number(radii_mm[i - 1]) + " mm)");
        if (!std::isfinite(profile[i])) throw InputError(fmt::format("radial profile: R at {} mm is not a finite number", format_number(radii_mm[i])));
    }
    ProfileFitReport report;
    report.estimate.distances_mm = radii_mm;
    report.estimate.profile_per_mm2 = profile;
    report.estimate.has_data.assign(radii_mm.size(), 1);
    fit_estimate(report, options);
    return report;
}

nlohmann::ordered_json profile_fit_json(const ProfileFitReport& r, const std::string& channel) {
    using Json = nlohmann::ordered_json;
    Json j{{"channel", channel},
           {"reduced_scattering_per_mm", r.fit.reduced_scattering_per_mm},
           {"absorption_per_mm", r.fit.absorption_per_mm},
           {"reduced_scattering_stderr_per_mm", std::isfinite(r.fit.reduced_scattering_stderr_per_mm) ? Json(r.fit.reduced_scattering_stderr_per_mm) : Json(nullptr)},
           {"absorption_stderr_per_mm", std::isfinite(r.fit.absorption_stderr_per_mm) ? Json(r.fit.absorption_stderr_per_mm) : Json(nullptr)},
           {"residual_per_mm4", r.fit.residual},
           {"grid", {{"reduced_scattering_per_mm", r.fit.grid_reduced_scattering_per_mm}, {"absorption_per_mm", r.fit.grid_absorption_per_mm}, {"residual_per_mm4", r.fit.grid_residual}}},
           {"bins", r.estimate.distances_mm.size()},
           {"rank", r.estimate.rank},
           {"least_squares_residual", r.estimate.residual_norm},
           {"distance_mm", r.estimate.distances_mm},
           {"profile_estimate_per_mm2", r.estimate.profile_per_mm2}};
    if (r.psnr_db) j["psnr_db"] = std::isfinite(*r.psnr_db) ? Json(*r.psnr_db) : Json("identical");
    j["at_bounds"] = r.fit.at_bounds;
    return j;
}

}  // namespace skinspec
