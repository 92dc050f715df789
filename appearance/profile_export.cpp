#include "appearance/profile_export.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "appearance/profile_shape_report.hpp"
#include "skinspec/version.hpp"
#include "solvers/spectral_solver.hpp"
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

WavelengthGrid profile_export_wavelengths(const ProfileExportRequest& request, const std::optional<WavelengthGrid>& given, std::string_view option) {
    if (request.per == ProfileChannels::wavelength) return given.value_or(WavelengthGrid::list({450.0, 550.0, 650.0}));
    if (given) {
        throw InputError(std::string(option) + ": an RGB fit (per rgb) integrates R(r) over 380-780 nm every 10 nm; wavelengths are for per wavelength");
    }
    return rgb_profile_wavelengths();
}

void check_profile_export(const std::string& material, bool bands, const ProfileExportRequest& request) {
    if (bands && request.per == ProfileChannels::wavelength) {
        throw InputError("--per wavelength: material '" + material + "' is given per band; it has no wavelengths");
    }
    check_gaussian_count(request.gaussians);
}

namespace {

// The export without its fit: the channels' names, totals and profiles (R(r) per channel, 1/mm^2).
ProfileExport export_channels(const SpectralProfiles& profiles, bool bands, const ProfileExportRequest& request, std::vector<std::vector<double>>& profiles_per_mm2) {
    check_profile_export(profiles.material, bands, request);
    ProfileExport out;
    out.material = profiles.material;
    out.model = profiles.model;
    out.radii_mm = profiles.radii_mm;
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
    return out;
}

}  // namespace

ProfileExport fit_profile_export(const SpectralProfiles& profiles, bool bands, const ProfileExportRequest& request) {
    std::vector<std::vector<double>> profiles_per_mm2;
    auto out = export_channels(profiles, bands, request, profiles_per_mm2);
    out.fit = fit_gaussian_sum(GaussianSumRequest{out.radii_mm, profiles_per_mm2, request.gaussians, out.total_reflectance, {}});
    return out;
}

std::vector<Material> profile_grid_members(const Material& base, const std::vector<SweepAxis>& axes) {
    if (axes.empty() || axes.size() > 2) throw InputError("vary: one or two fields (they form a grid); got " + std::to_string(axes.size()));
    const SweepMembers lattice(std::make_shared<const Material>(base), nullptr, axes);
    if (lattice.size() > max_profile_grid_members) {
        throw InputError("vary: " + std::to_string(lattice.size()) + " members is outside [1, " + std::to_string(max_profile_grid_members) + "]: split the grid");
    }
    std::vector<Material> members;
    members.reserve(lattice.size());
    for (std::size_t i = 0; i < lattice.size(); ++i) members.push_back(lattice[i].material());
    return members;
}

std::vector<std::size_t> grid_corners_and_middle(const std::vector<std::size_t>& axis_sizes) {
    std::size_t count = 1;
    for (const auto n : axis_sizes) count *= n;
    std::vector<std::size_t> out;
    // Member index of a position (the first axis fastest, sweep_grid's order).
    const auto index = [&](const std::vector<std::size_t>& at) {
        std::size_t i = 0, stride = 1;
        for (std::size_t a = 0; a < axis_sizes.size(); ++a) {
            i += at[a] * stride;
            stride *= axis_sizes[a];
        }
        return i;
    };
    for (std::size_t corner = 0; corner < (std::size_t{1} << axis_sizes.size()); ++corner) {
        std::vector<std::size_t> at;
        for (std::size_t a = 0; a < axis_sizes.size(); ++a) at.push_back((corner >> a) & 1 ? axis_sizes[a] - 1 : 0);
        out.push_back(index(at));
    }
    std::vector<std::size_t> middle;
    for (const auto n : axis_sizes) middle.push_back(n / 2);
    out.push_back(index(middle));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    if (!out.empty() && out.back() >= count) throw InputError("profile grid: positions beyond its members");
    return out;
}

ProfileExportGrid fit_profile_export_grid(const std::vector<SpectralProfiles>& members, std::vector<SweepAxis> axes, bool bands,
                                          const ProfileExportRequest& request) {
    std::vector<std::size_t> sizes;
    std::size_t count = 1;
    for (const auto& a : axes) {
        sizes.push_back(a.values.size());
        count *= a.values.size();
    }
    if (members.empty() || members.size() != count) {
        throw InputError("profile grid: " + std::to_string(members.size()) + " members' profiles for a grid of " + std::to_string(count));
    }
    ProfileExportGrid grid;
    grid.axes = std::move(axes);
    std::vector<std::vector<std::vector<double>>> profiles(members.size());
    for (std::size_t i = 0; i < members.size(); ++i) grid.members.push_back(export_channels(members[i], bands, request, profiles[i]));
    // One set of variances for the grid, fitted to its corners and middle together (every channel of each).
    grid.variances_fitted_to = grid_corners_and_middle(sizes);
    GaussianSumRequest joint{grid.members.front().radii_mm, {}, request.gaussians, {}, {}};
    for (const auto i : grid.variances_fitted_to) {
        joint.profiles_per_mm2.insert(joint.profiles_per_mm2.end(), profiles[i].begin(), profiles[i].end());
        joint.total_reflectance.insert(joint.total_reflectance.end(), grid.members[i].total_reflectance.begin(), grid.members[i].total_reflectance.end());
    }
    const auto variances = fit_gaussian_sum(joint).variances_mm2;
    for (std::size_t i = 0; i < members.size(); ++i) {
        auto& m = grid.members[i];
        m.fit = fit_gaussian_sum(GaussianSumRequest{m.radii_mm, profiles[i], request.gaussians, m.total_reflectance, variances});
    }
    return grid;
}

namespace {

// The fit's channels: weights, totals and errors of each.
nlohmann::ordered_json fit_entries(const ProfileExport& e) {
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
    return channels;
}

// What every export document begins with, from `e` (for a grid: its first member, the material it varies).
nlohmann::ordered_json document_head(const ProfileExport& e) {
    nlohmann::ordered_json document;
    document["skinspec_version"] = version;
    document["kind"] = "sum of Gaussians: R(r) = sum_i w_i exp(-r^2 / (2 v_i)) / (2 pi v_i)";
    document["reference"] = "d'Eon, Luebke & Enderton 2007; d'Eon & Luebke, GPU Gems 3 ch. 14";
    document["material"] = e.material;
    document["model"] = e.model;
    document["channels"] = e.channels_text;
    document["radii_mm"] = {{"first", e.radii_mm.front()}, {"last", e.radii_mm.back()}, {"count", e.radii_mm.size()}};
    document["variances_mm2"] = e.fit.variances_mm2;
    return document;
}

const nlohmann::ordered_json& units() {
    static const nlohmann::ordered_json u = {{"variances", "mm^2"}, {"r", "mm"}, {"R(r)", "1/mm^2"}, {"weights", "unitless"}};
    return u;
}

}  // namespace

nlohmann::ordered_json profile_export_json(const ProfileExport& e) {
    auto document = document_head(e);
    document["fit"] = fit_entries(e);
    if (e.shape) document["profile_shape"] = profile_shape_json(*e.shape);
    document["units"] = units();
    return document;
}

nlohmann::ordered_json profile_export_grid_json(const ProfileExportGrid& grid) {
    auto document = document_head(grid.members.front());
    document["variances_fitted_to"] = "the grid's corners and middle member together (members " + [&] {
        std::string list;
        for (const auto i : grid.variances_fitted_to) list += (list.empty() ? "" : ", ") + std::to_string(i);
        return list;
    }() + "); every member's weights for them";
    nlohmann::ordered_json axes = nlohmann::ordered_json::array();
    for (const auto& a : grid.axes) axes.push_back({{"field", a.field}, {"values", a.values}});
    document["axes"] = axes;
    document["member_order"] = "the first axis fastest";
    nlohmann::ordered_json members = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < grid.members.size(); ++i) {
        nlohmann::ordered_json values;
        std::size_t rest = i;
        for (const auto& a : grid.axes) {
            values[a.field] = a.values[rest % a.values.size()];
            rest /= a.values.size();
        }
        members.push_back({{"values", values}, {"fit", fit_entries(grid.members[i])}});
    }
    document["members"] = members;
    document["units"] = units();
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

std::string profile_export_grid_table_csv(const ProfileExportGrid& grid) {
    const auto& first = grid.members.front();
    std::string out = profile_export_header(first) + "# variances_mm2 [mm^2], shared by every member:";
    for (const double v : first.fit.variances_mm2) out += fmt::format(" {:.9g}", v);
    out += "\n# units: weights unitless (each Gaussian integrates to 1 over the plane); total_reflectance_fit unitless; profile_relative_l2_error unitless\n";
    for (const auto& a : grid.axes) out += a.field + ",";
    out += "channel";
    for (std::size_t i = 0; i < first.fit.variances_mm2.size(); ++i) out += fmt::format(",weight_{}", i + 1);
    out += ",total_reflectance_fit,profile_relative_l2_error\n";
    for (std::size_t m = 0; m < grid.members.size(); ++m) {
        std::string values;
        std::size_t rest = m;
        for (const auto& a : grid.axes) {
            values += fmt::format("{:.9g},", a.values[rest % a.values.size()]);
            rest /= a.values.size();
        }
        const auto& e = grid.members[m];
        for (std::size_t c = 0; c < e.names.size(); ++c) {
            out += values + e.names[c];
            for (const double w : e.fit.weights[c]) out += fmt::format(",{:.9g}", w);
            out += fmt::format(",{:.9g},{:.9g}\n", e.fit.fitted_total[c], e.fit.relative_l2_error[c]);
        }
    }
    return out;
}

}  // namespace skinspec
