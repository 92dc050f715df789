#include "transport/rte/rte_profiles.hpp"

#include <cmath>

#include <fmt/format.h>

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

SpectralProfiles solve_rte_profiles(const LayerStack& stack, const WavelengthGrid& wavelengths, std::span<const double> radii_mm, bool transmittance,
                                    const RteProfileOptions& options) {
    if (radii_mm.size() < 2) throw InputError("radial profiles of the volumetric walk need at least two radii (0 and a step)");
    const double step_mm = radii_mm[1] - radii_mm[0];
    for (std::size_t i = 0; i < radii_mm.size(); ++i) {
        if (!(std::abs(radii_mm[i] - static_cast<double>(i) * step_mm) <= 1e-9 * step_mm * static_cast<double>(i + 1)) || !(step_mm > 0.0)) {
            throw InputError("the volumetric walk tallies R(r) in rings: the radii must start at 0 mm with equal steps (radius " +
                             format_number(radii_mm[i]) + " mm is not " + std::to_string(i) + " x " + format_number(step_mm) + " mm)");
        }
    }
    SpectralProfiles out;
    out.material = stack.name;
    out.model = "rte";
    out.radii_mm.assign(radii_mm.begin(), radii_mm.end());
    const std::size_t n = radii_mm.size();
    for (const double nm : wavelengths.nm()) {
        RteRequest request;
        request.stack = rte_stack_from(stack, nm);
        request.photons = options.photons_per_wavelength;
        request.seed = options.seed;
        request.stream_key = nm;
        request.boundaries = options.boundaries;
        // 2n half-step rings: the last one also collects everything beyond (as MCML's last bin) and is not used.
        request.grid = RteGrid{0.01, 0.05 * step_mm, 0, static_cast<int>(2 * n), 0};
        request.cancel = options.cancel;
        const std::size_t index = out.channels.size(), total = wavelengths.size();
        if (options.on_progress) {
            request.on_progress = [&options, index, total, photons = options.photons_per_wavelength](const Progress& p) {
                options.on_progress(Progress{index * photons + p.rays_done, total * photons, index, total});
            };
        }
        const auto result = solve_rte(request);
        if (result.partial) {
            out.partial = true;
            break;
        }
        ChannelProfile c;
        c.label = fmt::format("{:g} nm", nm);
        c.wavelength_nm = nm;
        centred_rings(result.reflectance_r, n, c.reflectance_per_mm2, c.reflectance_stderr_per_mm2);
        if (transmittance) centred_rings(result.transmittance_r, n, c.transmittance_per_mm2, c.transmittance_stderr_per_mm2);
        c.total_reflectance = result.diffuse_reflectance.value;
        c.total_transmittance = result.transmittance.value;
        c.specular_reflectance = result.specular_reflectance.value;
        out.channels.push_back(std::move(c));
    }
    return out;
}

}  // namespace skinspec
