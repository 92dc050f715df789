#include "solvers/profile_shape_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

constexpr double ring_mm = 0.01, reach_mm = 5.0;

// The area of each ring (mm^2) whose mean R_i (per mm^2) stands at r_i = i h: [r_i - h/2, r_i + h/2), the disc of radius
// h/2 at 0 (transport/rte/rte_profiles.hpp).
std::vector<double> ring_areas_mm2(const std::vector<double>& radii_mm) {
    std::vector<double> out(radii_mm.size());
    for (std::size_t i = 0; i < radii_mm.size(); ++i) out[i] = i == 0 ? std::numbers::pi * 0.25 * ring_mm * ring_mm : 2.0 * std::numbers::pi * radii_mm[i] * ring_mm;
    return out;
}

// Per ring: values per mm^2 times the ring's area, squared with `squared` (a variance from a standard error).
std::vector<double> per_ring(const std::vector<double>& per_mm2, const std::vector<double>& areas_mm2, bool squared = false) {
    std::vector<double> out(areas_mm2.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = squared ? std::pow(per_mm2[i] * areas_mm2[i], 2) : per_mm2[i] * areas_mm2[i];
    return out;
}

double sum(const std::vector<double>& v, std::size_t first, std::size_t last) {
    double s = 0.0;
    for (std::size_t i = first; i < last; ++i) s += v[i];
    return s;
}

}  // namespace

bool profile_shape_checked(const SpectralSolver& solver, const Material& material) {
    const auto& caps = solver.capabilities();
    return caps.radial_profiles && !caps.uncertainty && std::holds_alternative<LayerStack>(material);
}

std::vector<double> profile_shape_wavelengths(const WavelengthGrid& wavelengths) {
    std::vector<double> chosen;
    for (const double target : {450.0, 550.0, 650.0}) {
        const auto nm = wavelengths.nm();
        const double nearest = *std::min_element(nm.begin(), nm.end(), [&](double a, double b) { return std::abs(a - target) < std::abs(b - target); });
        if (std::find(chosen.begin(), chosen.end(), nearest) == chosen.end()) chosen.push_back(nearest);
    }
    std::sort(chosen.begin(), chosen.end());
    return chosen;
}

ProfileShapeCheck check_profile_shape(const SpectralSolver& solver, const Material& material, const WavelengthGrid& wavelengths,
                                      const SolverSwitches& switches, std::uint64_t photons, const CancelFlag* cancel) {
    std::vector<double> radii;
    for (int i = 0; i * ring_mm <= reach_mm + 1e-9; ++i) radii.push_back(i * ring_mm);
    ProfileRequest walk_request;
    walk_request.wavelengths = WavelengthGrid::list(profile_shape_wavelengths(wavelengths));
    walk_request.radii_mm = radii;
    walk_request.rays_per_wavelength = photons;
    walk_request.seed = 1;
    walk_request.cancel = cancel;
    const auto walk = solve_profiles(find_solver("rte"), material, walk_request);
    ProfileShapeCheck check;
    check.stopped = walk.partial;
    if (walk.channels.empty()) return check;
    ProfileRequest solver_request;
    std::vector<double> finished;
    for (const auto& c : walk.channels) finished.push_back(c.wavelength_nm);
    solver_request.wavelengths = WavelengthGrid::list(finished);
    solver_request.radii_mm = walk.radii_mm;
    solver_request.switches = switches;
    const auto model = solve_profiles(solver, material, solver_request);
    const std::size_t n = walk.radii_mm.size();
    // Ring i stands for radius r_i (its mean): within 0.1 mm are the rings of r_i <= 0.1 mm, beyond 1 mm those of r_i >= 1 mm.
    const auto rings_within = [&](double r_mm) { return static_cast<std::size_t>(std::floor(r_mm / ring_mm + 1e-9)) + 1; };
    const auto areas = ring_areas_mm2(walk.radii_mm);
    for (std::size_t c = 0; c < walk.channels.size(); ++c) {
        const auto& w = walk.channels[c];
        const auto walk_rings = per_ring(w.reflectance_per_mm2, areas);
        const auto model_rings = per_ring(model.channels[c].reflectance_per_mm2, areas);
        const auto walk_variance = per_ring(w.reflectance_stderr_per_mm2, areas, true);
        const double walk_total = sum(walk_rings, 0, n), model_total = sum(model_rings, 0, n);
        ProfileShapeError e;
        e.wavelength_nm = w.wavelength_nm;
        e.photons = photons;
        if (!(walk_total > 0.0) || !(model_total > 0.0)) {
            e.compared = false;
            check.errors.push_back(e);
            continue;
        }
        double walk_within = 0.0, model_within = 0.0, variance_within = 0.0;
        const double variance_total = sum(walk_variance, 0, n);
        for (std::size_t i = 0; i < n; ++i) {
            walk_within += walk_rings[i];
            model_within += model_rings[i];
            variance_within += walk_variance[i];
            const double difference = model_within / model_total - walk_within / walk_total;
            if (std::abs(difference) > std::abs(e.largest_share_difference)) {
                e.largest_share_difference = difference;
                e.at_radius_mm = walk.radii_mm[i] + 0.5 * ring_mm;
                // F = S_in / (S_in + S_out): var F = (S_out^2 var S_in + S_in^2 var S_out) / S^4 (rings independent).
                const double outside = walk_total - walk_within, variance_outside = variance_total - variance_within;
                e.walk_share_stderr = std::sqrt(outside * outside * variance_within + walk_within * walk_within * variance_outside) / (walk_total * walk_total);
            }
        }
        const std::size_t near = std::min(rings_within(0.1), n), far = std::min(rings_within(1.0) - 1, n);
        e.walk_share_within_0_1_mm = sum(walk_rings, 0, near) / walk_total;
        e.solver_share_within_0_1_mm = sum(model_rings, 0, near) / model_total;
        e.walk_share_beyond_1_mm = sum(walk_rings, far, n) / walk_total;
        e.solver_share_beyond_1_mm = sum(model_rings, far, n) / model_total;
        check.errors.push_back(e);
    }
    return check;
}

ProfileShapeCheck stated_profile_shape(const SpectralSolver& solver, const Material& material, const WavelengthGrid& wavelengths,
                                       const SolverSwitches& switches, const CancelFlag* cancel) {
    ProfileShapeCheck check;
    if (!profile_shape_checked(solver, material)) return check;
    try {
        check = check_profile_shape(solver, material, wavelengths, switches, profile_shape_photons, cancel);
    } catch (const InputError& e) {
        check.not_checked = e.what();
    }
    return check;
}

}  // namespace skinspec
