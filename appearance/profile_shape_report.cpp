#include "appearance/profile_shape_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace skinspec {

std::vector<std::string> profile_shape_lines(const ProfileShapeCheck& check) {
    if (!check.not_checked.empty()) return {"R(r) shape not checked against the exact transport: " + check.not_checked};
    if (check.errors.empty()) return {};
    std::vector<std::string> lines{fmt::format(
        "R(r) shape against the exact transport (the volumetric walk, {:g} photons per wavelength; shape only, each normalised to its R "
        "within 5 mm){}; `--mode rte` gives the exact profile with standard errors:",
        static_cast<double>(check.errors.front().photons), check.stopped ? ", stopped: the wavelengths finished" : "")};
    for (const auto& e : check.errors) {
        if (!e.compared) {
            lines.push_back(fmt::format("  {:g} nm: no light leaves within 5 mm in the walk's or the solver's profile: nothing to compare", e.wavelength_nm));
            continue;
        }
        lines.push_back(fmt::format("  {:g} nm: the share of R leaving within a radius r is off by up to {:+.3f} +- {:.3f} (r = {:.3g} mm); "
                                    "within 0.1 mm {:.0f} % (exact {:.0f} %), beyond 1 mm {:.0f} % (exact {:.0f} %)",
                                    e.wavelength_nm, e.largest_share_difference, e.walk_share_stderr, e.at_radius_mm,
                                    100.0 * e.solver_share_within_0_1_mm, 100.0 * e.walk_share_within_0_1_mm, 100.0 * e.solver_share_beyond_1_mm,
                                    100.0 * e.walk_share_beyond_1_mm));
    }
    return lines;
}

std::string profile_precision_line(const SpectralProfiles& profiles) { return profile_precision_line(std::span<const SpectralProfiles>(&profiles, 1)); }

std::string profile_precision_line(std::span<const SpectralProfiles> members) {
    if (members.empty() || members.front().channels.empty() || members.front().channels.front().reflectance_stderr_per_mm2.empty()) return {};
    std::uint64_t fewest = members.front().channels.front().rays, most = 0;
    double largest = 0.0;
    std::size_t missed = 0, channels = 0;
    for (const auto& profiles : members) {
        for (const auto& c : profiles.channels) {
            fewest = std::min(fewest, c.rays);
            most = std::max(most, c.rays);
            largest = std::max(largest, c.within_radius_stderr);
            missed += c.converged ? 0 : 1;
            ++channels;
        }
    }
    const auto& first = members.front();
    const auto target = first.stderr_target ? fmt::format(" (target {:g}{})", *first.stderr_target,
                                                          missed ? fmt::format(", NOT met at {} of {} channels: the photon budget was spent", missed, channels)
                                                                 : std::string())
                                            : std::string(" (a fixed photon count)");
    const auto photons = fewest == most ? fmt::format("{:g}", static_cast<double>(most))
                                        : fmt::format("{:g}-{:g}", static_cast<double>(fewest), static_cast<double>(most));
    const auto shared = members.size() > 1 ? fmt::format(", shared by the {} members (the exit replay: one walk per wavelength)", members.size()) : std::string();
    return fmt::format("exact transport ({}, the volumetric walk): {} photons per channel{}; the diffuse reflectance leaving within any radius of a "
                       "1-2-5 series has a standard error of at most {:.2g}{}",
                       first.model, photons, shared, largest, target);
}

std::string profile_shape_text(const ProfileShapeCheck& check) {
    std::string text;
    for (const auto& line : profile_shape_lines(check)) text += (text.empty() ? "" : "\n") + line;
    return text;
}

bool profile_shape_warns(const ProfileShapeCheck& check) {
    return !check.not_checked.empty() || std::any_of(check.errors.begin(), check.errors.end(), [](const ProfileShapeError& e) {
               return std::abs(e.largest_share_difference) > profile_shape_worth_a_warning;
           });
}

nlohmann::ordered_json profile_shape_json(const ProfileShapeCheck& check) {
    nlohmann::ordered_json out;
    out["reference"] = "the volumetric walk (rte), rings of 0.01 mm to 5 mm; shares of the R within 5 mm";
    if (!check.not_checked.empty()) out["not_checked"] = check.not_checked;
    out["stopped"] = check.stopped;
    out["wavelengths"] = nlohmann::ordered_json::array();
    for (const auto& e : check.errors) {
        out["wavelengths"].push_back({{"wavelength_nm", e.wavelength_nm},
                                      {"photons", e.photons},
                                      {"compared", e.compared},
                                      {"largest_share_difference", e.largest_share_difference},
                                      {"at_radius_mm", e.at_radius_mm},
                                      {"walk_share_stderr", e.walk_share_stderr},
                                      {"share_within_0_1_mm", e.solver_share_within_0_1_mm},
                                      {"exact_share_within_0_1_mm", e.walk_share_within_0_1_mm},
                                      {"share_beyond_1_mm", e.solver_share_beyond_1_mm},
                                      {"exact_share_beyond_1_mm", e.walk_share_beyond_1_mm}});
    }
    return out;
}

}  // namespace skinspec
