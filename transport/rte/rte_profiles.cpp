#include "transport/rte/rte_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include <fmt/format.h>

#include "materials/path_key.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double mm2_per_cm2 = 100.0;

// Ring i of width h centred on r_i from the half-step rings j (area-weighted mean); 1/cm^2 -> 1/mm^2.
void centred_rings(const std::vector<Estimate>& half_rings, std::size_t n, std::vector<double>& values, std::vector<double>& errors) {
    // Half-step ring j covers [j, j + 1) in units of h/2; its area is proportional to 2 j + 1.
    for (std::size_t i = 0; i < n; ++i) {
        double sum = 0.0, variance = 0.0, area = 0.0;
        for (const std::size_t j : i == 0 ? std::vector<std::size_t>{0} : std::vector<std::size_t>{2 * i - 1, 2 * i}) {
            const double a = 2.0 * static_cast<double>(j) + 1.0;
            sum += a * half_rings[j].value;
            variance += a * a * half_rings[j].stderr * half_rings[j].stderr;
            area += a;
        }
        values.push_back(sum / area / mm2_per_cm2);
        errors.push_back(std::sqrt(variance) / area / mm2_per_cm2);
    }
}

}  // namespace

std::vector<double> within_radii_mm(std::span<const double> radii_mm) {
    std::vector<double> out;
    if (radii_mm.size() < 2) return out;
    const double step = radii_mm[1] - radii_mm[0], reach = radii_mm.back() + 0.5 * step;
    for (double decade = std::pow(10.0, std::floor(std::log10(step))); decade < reach; decade *= 10.0) {
        for (const double m : {1.0, 2.0, 5.0}) {
            if (m * decade >= step * (1.0 - 1e-9) && m * decade < reach * (1.0 - 1e-9)) out.push_back(m * decade);
        }
    }
    out.push_back(reach);
    return out;
}

namespace {

// One channel of a profile: its label, wavelength (0 for a band) and the key of its random streams.
struct ProfileChannel {
    std::string label;
    double wavelength_nm = 0.0;
    double stream_key = 0.0;
};

// One channel's profile from the walk's result (n centred rings).
ChannelProfile channel_profile(const ProfileChannel& channel, const RteResult& result, std::size_t n, bool transmittance, const RteProfileOptions& options) {
    ChannelProfile c;
    c.label = channel.label;
    c.wavelength_nm = channel.wavelength_nm;
    centred_rings(result.reflectance_r, n, c.reflectance_per_mm2, c.reflectance_stderr_per_mm2);
    if (transmittance) centred_rings(result.transmittance_r, n, c.transmittance_per_mm2, c.transmittance_stderr_per_mm2);
    c.total_reflectance = result.diffuse_reflectance.value;
    c.total_transmittance = result.transmittance.value;
    c.specular_reflectance = result.specular_reflectance.value;
    c.rays = result.photons;
    for (const auto* within : {&result.reflectance_within, &result.transmittance_within}) {
        for (const auto& e : *within) c.within_radius_stderr = std::max(c.within_radius_stderr, e.stderr);
    }
    c.converged = !options.stderr_target || c.within_radius_stderr <= *options.stderr_target;
    return c;
}

// The walk channel by channel, material m's medium `medium(channel, m)`: one material MCML's way, several by the exit
// replay (solve_rte_exit_sets: the first one's paths, every material's absorption).
std::vector<SpectralProfiles> walk_profiles(const std::vector<std::string>& materials, const std::vector<ProfileChannel>& channels,
                                            const std::function<RteStack(std::size_t, std::size_t)>& medium, std::span<const double> radii_mm,
                                            bool transmittance, const RteProfileOptions& options) {
    if (radii_mm.size() < 2) throw InputError("radial profiles of the volumetric walk need at least two radii (0 and a step)");
    const double step_mm = radii_mm[1] - radii_mm[0];
    for (std::size_t i = 0; i < radii_mm.size(); ++i) {
        if (!(std::abs(radii_mm[i] - static_cast<double>(i) * step_mm) <= 1e-9 * step_mm * static_cast<double>(i + 1)) || !(step_mm > 0.0)) {
            throw InputError("the volumetric walk tallies R(r) in rings: the radii must start at 0 mm with equal steps (radius " +
                             format_number(radii_mm[i]) + " mm is not " + std::to_string(i) + " x " + format_number(step_mm) + " mm)");
        }
    }
    std::vector<SpectralProfiles> out(materials.size());
    for (std::size_t m = 0; m < materials.size(); ++m) {
        out[m].material = materials[m];
        out[m].model = "rte";
        out[m].stderr_target = options.stderr_target;
        out[m].radii_mm.assign(radii_mm.begin(), radii_mm.end());
    }
    const std::size_t n = radii_mm.size();
    std::vector<double> within_cm;
    for (const double r : within_radii_mm(radii_mm)) within_cm.push_back(r / 10.0);
    std::uint64_t rays_before = 0;
    for (std::size_t index = 0; index < channels.size(); ++index) {
        RteRequest request;
        request.stack = medium(index, 0);
        request.photons = options.photons_per_wavelength;
        request.stderr_target = options.stderr_target;
        request.within_radii_cm = within_cm;
        request.seed = options.seed;
        request.stream_key = channels[index].stream_key;
        request.boundaries = options.boundaries;
        // 2n half-step rings: the last one also collects everything beyond (as MCML's last bin) and is not used.
        request.grid = RteGrid{0.01, 0.05 * step_mm, 0, static_cast<int>(2 * n), 0};
        request.cancel = options.cancel;
        const std::size_t total = channels.size();
        if (options.on_progress) {
            // The wavelengths to come are expected to take as many photons as this one (unknown until it is estimated).
            request.on_progress = [&options, index, total, rays_before](const Progress& p) {
                const std::uint64_t expected = p.rays_expected > 0 ? rays_before + p.rays_expected * (total - index) : 0;
                options.on_progress(Progress{rays_before + p.rays_done, expected, index, total});
            };
        }
        std::vector<RteResult> results;
        if (materials.size() == 1) {
            results.push_back(solve_rte(request));
        } else {
            std::vector<std::vector<double>> mu_a_sets;
            for (std::size_t m = 0; m < materials.size(); ++m) {
                auto& set = mu_a_sets.emplace_back();
                for (const auto& layer : medium(index, m).layers) set.push_back(layer.mu_a_per_cm);
            }
            results = solve_rte_exit_sets(request, mu_a_sets);
        }
        rays_before += results.front().photons;
        if (results.front().partial) {
            for (auto& o : out) o.partial = true;
            break;
        }
        for (std::size_t m = 0; m < materials.size(); ++m) out[m].channels.push_back(channel_profile(channels[index], results[m], n, transmittance, options));
    }
    return out;
}

}  // namespace


std::vector<SpectralProfiles> solve_rte_profiles(const std::vector<const LayerStack*>& stacks, const WavelengthGrid& wavelengths,
                                                 std::span<const double> radii_mm, bool transmittance, const RteProfileOptions& options) {
    if (stacks.empty()) throw InputError("radial profiles of the volumetric walk: no materials");
    require_shared_paths(stacks, TracedPaths::volumetric);
    std::vector<ProfileChannel> channels;
    for (const double nm : wavelengths.nm()) channels.push_back({fmt::format("{:g} nm", nm), nm, nm});
    std::vector<std::string> names;
    for (const auto* stack : stacks) names.push_back(stack->name);
    return walk_profiles(names, channels, [&](std::size_t c, std::size_t m) { return rte_stack_from(*stacks[m], channels[c].wavelength_nm); }, radii_mm,
                         transmittance, options);
}

SpectralProfiles solve_rte_profiles(const LayerStack& stack, const WavelengthGrid& wavelengths, std::span<const double> radii_mm, bool transmittance,
                                    const RteProfileOptions& options) {
    return solve_rte_profiles(std::vector<const LayerStack*>{&stack}, wavelengths, radii_mm, transmittance, options).front();
}

SpectralProfiles solve_rte_profiles(const HomogeneousMaterial& material, std::span<const double> radii_mm, bool transmittance,
                                    const RteProfileOptions& options) {
    // Streams keyed by the band's number, as solve_rte_bands keys them.
    std::vector<ProfileChannel> channels;
    for (std::size_t b = 0; b < material.bands.size(); ++b) channels.push_back({material.bands[b], 0.0, static_cast<double>(b + 1)});
    return walk_profiles({material.name}, channels, [&](std::size_t c, std::size_t) { return rte_band_slab(material, c); }, radii_mm, transmittance,
                         options)
        .front();
}

}  // namespace skinspec
