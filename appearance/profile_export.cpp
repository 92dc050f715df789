#include "appearance/profile_export.hpp"

#include <fmt/format.h>

#include "appearance/profile_shape_report.hpp"
#include "skinspec/version.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// The colour of the profile at each radius: R(r, lambda) integrated against the observer under the illuminant
// (white = 1, so the channel integrates to the diffuse albedo), in the linear RGB space `space`.
void rgb_channels(const SpectralProfiles& p, const ProfileExportRequest& request, ProfileExport& out,
                  std::vector<std::vector<double>>& profiles_per_mm2) {
    const auto& cm = ColorManagement::builtin();
    std::vector<double> nm;
    for (const auto& c : p.channels) nm.push_back(c.wavelength_nm);
    const TristimulusWeights weights(nm, request.illuminant, request.observer, OutOfRangePolicy::hold);
    out.names = {"R", "G", "B"};
    profiles_per_mm2.assign(3, {});
    std::vector<double> at(nm.size()), totals(nm.size());
    for (std::size_t k = 0; k < p.radii_mm.size(); ++k) {
        for (std::size_t w = 0; w < nm.size(); ++w) at[w] = p.channels[w].reflectance_per_mm2[k];
        const auto rgb = cm.from_xyz(weights.integrate(at), weights.white(), request.space);
        for (std::size_t c = 0; c < 3; ++c) profiles_per_mm2[c].push_back(rgb[c]);
    }
    for (std::size_t w = 0; w < nm.size(); ++w) totals[w] = p.channels[w].total_reflectance;
    const auto total = cm.from_xyz(weights.integrate(totals), weights.white(), request.space);
    out.total_reflectance.assign(total.begin(), total.end());
}

}  // namespace

ProfileChannels parse_profile_channels(const std::string& text, std::string_view option) {
    if (text == "rgb") return ProfileChannels::rgb;
    if (text == "wavelength") return ProfileChannels::wavelength;
    throw InputError(std::string(option) + ": '" + text + "' is not what to fit per (allowed: rgb, wavelength)");
}

WavelengthGrid rgb_profile_wavelengths() { return WavelengthGrid::range(380.0, 780.0, 10.0); }

void check_profile_export(const std::string& material, bool bands, const ProfileExportRequest& request) {
    if (bands && request.per == ProfileChannels::wavelength) {
        throw InputError("--per wavelength: material '" + material + "' is given per band; it has no wavelengths");
    }
    check_gaussian_count(request.gaussians);
}

ProfileExport fit_profile_export(const SpectralProfiles& profiles, bool bands, const ProfileExportRequest& request) {
    check_profile_export(profiles.material, bands, request);
    ProfileExport out;
    out.material = profiles.material;
    out.model = profiles.model;
    out.radii_mm = profiles.radii_mm;
    std::vector<std::vector<double>> profiles_per_mm2;
    if (bands || request.per == ProfileChannels::wavelength) {
        for (const auto& c : profiles.channels) {
            out.names.push_back(c.label);
            profiles_per_mm2.push_back(c.reflectance_per_mm2);
            out.total_reflectance.push_back(c.total_reflectance);
        }
        out.channels_text = bands ? "bands" : "wavelengths";
    } else {
        rgb_channels(profiles, request, out, profiles_per_mm2);
        out.channels_text = "RGB in " + request.space + " (" + std::string(short_name(request.illuminant)) + ", " + std::string(short_name(request.observer)) + ")";
    }
    out.fit = fit_gaussian_sum(GaussianSumRequest{out.radii_mm, profiles_per_mm2, request.gaussians, out.total_reflectance});
    return out;
}

nlohmann::ordered_json profile_export_json(const ProfileExport& e) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (std::size_t c = 0; c < e.names.size(); ++c) {
        const double total = e.total_reflectance[c];
        nlohmann::ordered_json entry;
        entry["name"] = e.names[c];
        entry["weights"] = e.fit.weights[c];
        entry["total_reflectance_fit"] = e.fit.fitted_total[c];
        entry["total_reflectance_model"] = total;
        entry["total_reflectance_relative_error"] = total != 0.0 ? (e.fit.fitted_total[c] - total) / total : 0.0;
        entry["total_reflectance_profile_range"] = e.fit.profile_total[c];
        entry["profile_relative_l2_error"] = e.fit.relative_l2_error[c];
        channels.push_back(std::move(entry));
    }
    nlohmann::ordered_json document;
    document["skinspec_version"] = version;
    document["kind"] = "sum of Gaussians: R(r) = sum_i w_i exp(-r^2 / (2 v_i)) / (2 pi v_i)";
    document["reference"] = "d'Eon, Luebke & Enderton 2007; d'Eon & Luebke, GPU Gems 3 ch. 14";
    document["material"] = e.material;
    document["model"] = e.model;
    document["channels"] = e.channels_text;
    document["radii_mm"] = {{"first", e.radii_mm.front()}, {"last", e.radii_mm.back()}, {"count", e.radii_mm.size()}};
    document["variances_mm2"] = e.fit.variances_mm2;
    document["fit"] = channels;
    if (e.shape) document["profile_shape"] = profile_shape_json(*e.shape);
    document["units"] = {{"variances", "mm^2"}, {"r", "mm"}, {"R(r)", "1/mm^2"}, {"weights", "unitless"}};
    return document;
}

std::string profile_export_header(const ProfileExport& e) {
    return fmt::format("# skinspec {} sum-of-{}-Gaussians fit of R(r): material {}, model {}, channels {}, r {}-{} mm\n", version,
                       e.fit.variances_mm2.size(), e.material, e.model, e.channels_text, format_number(e.radii_mm.front()),
                       format_number(e.radii_mm.back()));
}

std::string profile_export_table_csv(const ProfileExport& e) {
    std::string out = profile_export_header(e) + "# units: variance_mm2 [mm^2]; weights unitless (each Gaussian integrates to 1 over the plane)\n";
    out += "variance_mm2";
    for (const auto& n : e.names) out += ",weight_" + n;
    out += '\n';
    for (std::size_t i = 0; i < e.fit.variances_mm2.size(); ++i) {
        out += fmt::format("{:.9g}", e.fit.variances_mm2[i]);
        for (const auto& w : e.fit.weights) out += fmt::format(",{:.9g}", w[i]);
        out += '\n';
    }
    return out;
}

}  // namespace skinspec
