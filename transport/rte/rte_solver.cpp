// The volumetric walk: MCML's photon loop (Wang, Jacques & Zheng 1995, Comput. Methods Programs Biomed.
// 47:131-146, Sec. 3-4): exponential free paths (Eq. 3.7), absorption by weight mu_a / mu_t at each
// interaction (Eq. 3.23), scattering by the layer's phase function, Fresnel at every boundary (Eq. 3.31),
// Russian roulette below weight 1e-4 with survival 0.1 (Sec. 3.9). Differences from MCML: PCG32 streams per
// batch (no ran3), oblique incidence, an optional Lambertian bottom reflector, roulette that conserves each
// photon's energy exactly (the survivor's gain is taken back from the absorption tally where it happened),
// and standard errors for every tally.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "transport/cosine_hemisphere.hpp"
#include "transport/direction.hpp"
#include "transport/fresnel.hpp"
#include "transport/rte/rte_model.hpp"
#include "transport/ray_planner.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double roulette_weight = 1e-4;
constexpr double roulette_survival = 0.1;

// Channel layout of a photon's score.
struct Channels {
    std::size_t layers, nz, nr, na;
    std::size_t specular = 0, reflectance = 1, transmittance = 2, absorbed = 3, first_layer = 4;
    std::size_t a_z, r_r, t_r, r_a, t_a, a_rz, r_ra, t_ra, count;
    Channels(std::size_t l, const RteGrid& g)
        : layers(l), nz(static_cast<std::size_t>(g.nz)), nr(static_cast<std::size_t>(g.nr)), na(static_cast<std::size_t>(g.na)) {
        a_z = first_layer + layers;
        r_r = a_z + nz;
        t_r = r_r + nr;
        r_a = t_r + nr;
        t_a = r_a + na;
        a_rz = t_a + na;
        r_ra = a_rz + nr * nz;
        t_ra = r_ra + nr * na;
        count = t_ra + nr * na;
    }
};

class Walk {
public:
    Walk(const RteRequest& r, const Channels& c) : request_(r), stack_(r.stack), ch_(c) {
        double z = 0.0;
        for (const auto& l : stack_.layers) {
            top_.push_back(z);
            z += l.thickness_cm;
            bottom_.push_back(z);
        }
        const double theta = r.incidence_deg * pi / 180.0;
        incident_ = Direction{std::sin(theta), 0.0, std::cos(theta)};
        specular_ = fresnel_reflectance(incident_.z, stack_.above_refractive_index, stack_.layers.front().refractive_index);
    }

    void trace(RandomStream& random, std::uint64_t photons, RayTally& tally) const {
        trace_rays(ch_.count, photons, tally, [&](RayScore& score, std::uint64_t& truncated) { trace_one(random, score, truncated); });
    }

private:
    std::size_t r_bin(double x, double y) const {
        const double r = std::sqrt(x * x + y * y);
        return std::min(static_cast<std::size_t>(r / request_.grid.dr_cm), ch_.nr - 1);  // beyond the grid: last bin (MCML)
    }
    std::size_t a_bin(double cos_exit) const {
        const double a = std::acos(std::clamp(cos_exit, 0.0, 1.0));
        return std::min(static_cast<std::size_t>(a / (0.5 * pi / static_cast<double>(ch_.na))), ch_.na - 1);
    }

    void absorb(RayScore& s, std::size_t layer, double x, double y, double z, double w) const {
        s.add(ch_.absorbed, w);
        s.add(ch_.first_layer + layer, w);
        if (ch_.nz > 0) {
            const auto iz = std::min(static_cast<std::size_t>(z / request_.grid.dz_cm), ch_.nz - 1);
            s.add(ch_.a_z + iz, w);
            if (ch_.nr > 0) s.add(ch_.a_rz + r_bin(x, y) * ch_.nz + iz, w);
        }
    }

    void escape(RayScore& s, bool top, double x, double y, double cos_exit, double w) const {
        s.add(top ? ch_.reflectance : ch_.transmittance, w);
        if (ch_.nr > 0) s.add((top ? ch_.r_r : ch_.t_r) + r_bin(x, y), w);
        if (ch_.na > 0) s.add((top ? ch_.r_a : ch_.t_a) + a_bin(cos_exit), w);
        if (ch_.nr > 0 && ch_.na > 0) s.add((top ? ch_.r_ra : ch_.t_ra) + r_bin(x, y) * ch_.na + a_bin(cos_exit), w);
    }

    void trace_one(RandomStream& random, RayScore& s, std::uint64_t& truncated) const {
        // Launch: specular reflection taken deterministically, the rest refracted into layer 1 (MCML Sec. 3.3).
        s.add(ch_.specular, specular_);
        double w = 1.0 - specular_;
        if (w <= 0.0) return;
        Direction d = *refract(incident_, stack_.above_refractive_index, stack_.layers.front().refractive_index);
        double x = 0.0, y = 0.0, z = 0.0;
        std::size_t k = 0;
        double tau = 0.0;  // optical depth left to travel
        for (std::uint64_t step = 0;; ++step) {
            const RteLayer& layer = stack_.layers[k];
            if (step >= request_.max_steps_per_photon) {
                absorb(s, k, x, y, z, w);
                ++truncated;
                return;
            }
            const double mu_t = layer.mu_a_per_cm + layer.mu_s_per_cm;
            if (tau <= 0.0) tau = -std::log(1.0 - random.uniform());  // Eq. 3.7, u in [0, 1)
            const double step_cm = mu_t > 0.0 ? tau / mu_t : std::numeric_limits<double>::infinity();
            const double to_boundary = d.z > 0.0 ? (bottom_[k] - z) / d.z
                                       : d.z < 0.0 ? (top_[k] - z) / d.z
                                                   : std::numeric_limits<double>::infinity();
            if (step_cm >= to_boundary) {
                // Move to the boundary, keep the optical depth left (MCML's "sleft").
                x += to_boundary * d.x;
                y += to_boundary * d.y;
                z = d.z > 0.0 ? bottom_[k] : top_[k];
                if (mu_t > 0.0) tau -= to_boundary * mu_t;
                if (!cross_boundary(random, s, d, k, x, y, w)) return;
                continue;
            }
            x += step_cm * d.x;
            y += step_cm * d.y;
            z += step_cm * d.z;
            tau = 0.0;
            // Absorption by weight (Eq. 3.23), then scattering.
            const double absorbed = w * layer.mu_a_per_cm / mu_t;
            absorb(s, k, x, y, z, absorbed);
            w -= absorbed;
            if (layer.mu_s_per_cm > 0.0) {
                const double c = layer.phase.sample_cos(random);
                d = deflect(d, c, std::sqrt(std::max(0.0, 1.0 - c * c)), sample_azimuth(random));
            }
            if (w < roulette_weight) {
                if (w <= 0.0) return;
                if (random.uniform() < roulette_survival) {
                    absorb(s, k, x, y, z, w - w / roulette_survival);  // negative: the survivor's gain
                    w /= roulette_survival;
                } else {
                    absorb(s, k, x, y, z, w);
                    return;
                }
            }
        }
    }

    // Returns false when the photon has left the slab (its weight tallied).
    bool cross_boundary(RandomStream& random, RayScore& s, Direction& d, std::size_t& k, double x, double y, double& w) const {
        const bool down = d.z > 0.0;
        const std::size_t last = stack_.layers.size() - 1;
        if (down && k == last && stack_.bottom_reflector) {
            d = sample_cosine_hemisphere(random.uniform(), sample_azimuth(random), false);
            return true;
        }
        const bool outer = down ? k == last : k == 0;
        const double n1 = stack_.layers[k].refractive_index;
        const double n2 = outer ? (down ? stack_.below_refractive_index : stack_.above_refractive_index)
                                : stack_.layers[down ? k + 1 : k - 1].refractive_index;
        const double reflect = fresnel_reflectance(d.z, n1, n2);
        const auto transmitted = refract(d, n1, n2);
        if (outer && transmitted && request_.boundaries == BoundaryMode::split) {
            escape(s, !down, x, y, std::abs(transmitted->z), w * (1.0 - reflect));
            w *= reflect;
            d = mirror(d);
            return w > 0.0;
        }
        if (!transmitted || (reflect > 0.0 && random.uniform() < reflect)) {
            d = mirror(d);
            return true;
        }
        if (outer) {
            escape(s, !down, x, y, std::abs(transmitted->z), w);
            return false;
        }
        d = *transmitted;
        k = down ? k + 1 : k - 1;
        return true;
    }

    const RteRequest& request_;
    const RteStack& stack_;
    const Channels& ch_;
    std::vector<double> top_, bottom_;
    Direction incident_;
    double specular_ = 0.0;
};

std::vector<Estimate> scaled(const RayTally& t, std::size_t first, std::size_t n, const std::function<double(std::size_t)>& scale) {
    std::vector<Estimate> out;
    for (std::size_t i = 0; i < n; ++i) {
        const auto e = t.estimate(first + i);
        out.push_back({e.value * scale(i), e.stderr * scale(i)});
    }
    return out;
}

}  // namespace

RteResult solve_rte(const RteRequest& request) {
    validate(request.stack);
    if (!std::isfinite(request.incidence_deg) || request.incidence_deg < 0.0 || request.incidence_deg >= 90.0) {
        throw InputError("incidence angle " + format_number(request.incidence_deg) + " deg is outside [0, 90)");
    }
    if (request.photons < 1) throw InputError("photon count 0 is outside [1, inf)");
    const auto& g = request.grid;
    if (g.nz < 0 || g.nr < 0 || g.na < 0 || ((g.nz > 0 || g.nr > 0) && !(g.dz_cm > 0.0 && g.dr_cm > 0.0))) {
        throw InputError("grid: bin counts must be >= 0 and dz, dr > 0");
    }
    const Channels channels(request.stack.layers.size(), g);
    const Walk walk(request, channels);

    SpectralRequest driver;
    driver.wavelengths = WavelengthGrid::list({request.stream_key});
    driver.max_rays_per_wavelength = request.photons;
    driver.stderr_target = request.stderr_target;
    driver.seed = request.seed;
    driver.on_progress = request.on_progress;
    driver.cancel = request.cancel;
    const auto outcome = run_batches(driver, channels.count, {channels.reflectance, channels.transmittance},
                                     [&](std::size_t, RandomStream& random, std::uint64_t n, RayTally& tally) { walk.trace(random, n, tally); });

    RteResult r;
    r.partial = outcome.cancelled;
    const auto& t = outcome.tallies.front();
    r.photons = t.rays();
    r.truncated_photons = t.truncated();
    if (r.photons == 0) return r;
    r.specular_reflectance = t.estimate(channels.specular);
    r.diffuse_reflectance = t.estimate(channels.reflectance);
    r.transmittance = t.estimate(channels.transmittance);
    const auto one = [](std::size_t) { return 1.0; };
    r.absorption_layers = scaled(t, channels.first_layer, channels.layers, one);
    r.absorbed = t.estimate(channels.absorbed);
    // MCML 1.2 scaling (ScaleRdTt, ScaleA): per area of the ring, per solid angle 2 pi sin(a) da, per volume.
    const double dz = g.dz_cm, dr = g.dr_cm, da = g.na > 0 ? 0.5 * pi / g.na : 0.0;
    const auto ring = [&](std::size_t ir) { return 2.0 * pi * (ir + 0.5) * dr * dr; };
    const auto cone = [&](std::size_t ia) { return 2.0 * pi * std::sin((ia + 0.5) * da) * da; };
    r.absorption_z = scaled(t, channels.a_z, channels.nz, [&](std::size_t) { return 1.0 / dz; });
    r.reflectance_r = scaled(t, channels.r_r, channels.nr, [&](std::size_t ir) { return 1.0 / ring(ir); });
    r.transmittance_r = scaled(t, channels.t_r, channels.nr, [&](std::size_t ir) { return 1.0 / ring(ir); });
    r.reflectance_a = scaled(t, channels.r_a, channels.na, [&](std::size_t ia) { return 1.0 / cone(ia); });
    r.transmittance_a = scaled(t, channels.t_a, channels.na, [&](std::size_t ia) { return 1.0 / cone(ia); });
    r.absorption_rz = scaled(t, channels.a_rz, channels.nr * channels.nz, [&](std::size_t i) { return 1.0 / (ring(i / std::max<std::size_t>(1, channels.nz)) * dz); });
    const auto ra_scale = [&](std::size_t i) {
        const std::size_t ir = i / std::max<std::size_t>(1, channels.na), ia = i % std::max<std::size_t>(1, channels.na);
        return 1.0 / (4.0 * pi * pi * dr * dr * std::sin(da / 2.0) * (ir + 0.5) * std::sin(2.0 * (ia + 0.5) * da));
    };
    r.reflectance_ra = scaled(t, channels.r_ra, channels.nr * channels.na, ra_scale);
    r.transmittance_ra = scaled(t, channels.t_ra, channels.nr * channels.na, ra_scale);
    return r;
}

SpectralResult solve_rte_spectrum(const LayerStack& stack, const SpectralRequest& request, BoundaryMode boundaries) {
    SpectralResult out;
    out.model = "rte";
    out.material = stack.name;
    out.quantities = Quantities{true, true, true, false};
    for (const auto& l : stack.layers) out.layer_names.push_back(l.name);
    out.settings = {{"incidence_deg", request.incidence_deg},
                    {"seed", request.seed},
                    {"max_rays_per_wavelength", request.max_rays_per_wavelength},
                    {"boundaries", std::string(boundaries == BoundaryMode::split ? "split" : "random")},
                    {"bottom", std::string(to_string(stack.bottom))},
                    {"roulette", std::string("weight < 1e-4, survival 0.1, energy-conserving")}};
    if (request.stderr_target) out.settings["stderr_target"] = *request.stderr_target;
    // One progress for the whole spectrum: rays and wavelengths count on across the per-wavelength runs.
    const std::size_t total = request.wavelengths.size();
    std::uint64_t rays_before = 0;
    std::size_t index = 0;
    const auto progress = [&](const Progress& p) {
        if (!request.on_progress) return;
        const std::uint64_t expected_rest = (total - index - 1) * std::max<std::uint64_t>(p.rays_expected, 1);
        request.on_progress(Progress{rays_before + p.rays_done, rays_before + p.rays_expected + expected_rest,
                                     index + p.wavelengths_done, total});
    };
    for (const double nm : request.wavelengths.nm()) {
        RteRequest r;
        r.stack = rte_stack_from(stack, nm);
        r.photons = request.max_rays_per_wavelength;
        r.stderr_target = request.stderr_target;
        r.seed = request.seed;
        r.stream_key = nm;
        r.incidence_deg = request.incidence_deg;
        r.boundaries = boundaries;
        r.on_progress = progress;
        r.cancel = request.cancel;
        const auto res = solve_rte(r);
        rays_before += res.photons;
        ++index;
        if (res.partial) {
            out.partial = true;
            break;
        }
        WavelengthResult w;
        w.wavelength_nm = nm;
        w.reflectance = {res.specular_reflectance.value + res.diffuse_reflectance.value, res.diffuse_reflectance.stderr};
        w.specular_reflectance = res.specular_reflectance;
        w.transmittance = res.transmittance;
        w.absorptance_layers = res.absorption_layers;
        w.rays = res.photons;
        w.truncated_rays = res.truncated_photons;
        w.converged = !request.stderr_target || (res.diffuse_reflectance.stderr <= *request.stderr_target &&
                                                 res.transmittance.stderr <= *request.stderr_target);
        out.wavelengths.push_back(std::move(w));
    }
    return out;
}

}  // namespace skinspec
