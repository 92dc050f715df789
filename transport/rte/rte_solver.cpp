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
    std::size_t a_z, r_r, t_r, r_a, t_a, a_rz, r_ra, t_ra, count = 0;
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
        truncated = t_ra + nr * na;
        count = truncated + 1;
    }
    std::size_t truncated;  // 1 for a photon stopped at the step limit (per absorption set in white mode)
};

// Per-photon state of the absorption sets in white mode: optical depth, log of the roulette boosts, and the
// depth beyond which a set plays roulette (+inf once it has lost).
struct WhiteState {
    std::vector<double> tau, boost_log, limit;
    std::size_t alive = 0;
};

class Walk {
public:
    // `mu_a_sets` (white mode): per set, mu_a per layer in 1/cm; empty: the stack's own absorption, MCML's way.
    Walk(const RteRequest& r, const Channels& c, std::vector<std::vector<double>> mu_a_sets)
        : request_(r), stack_(r.stack), ch_(c), sets_(std::max<std::size_t>(1, mu_a_sets.size())), white_(!mu_a_sets.empty()) {
        for (std::size_t k = 0; k < stack_.layers.size(); ++k) {
            for (std::size_t s = 0; s < mu_a_sets.size(); ++s) mu_a_per_cm_.push_back(mu_a_sets[s].at(k));
        }
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
        if (!white_) {
            trace_rays(ch_.count, photons, tally, [&](RayScore& score, std::uint64_t& truncated) { trace_one(random, score, truncated); });
            return;
        }
        WhiteState state{std::vector<double>(sets_), std::vector<double>(sets_), std::vector<double>(sets_), 0};
        trace_rays(ch_.count * sets_, photons, tally, [&](RayScore& score, std::uint64_t&) { trace_white(random.bits64(), score, state); });
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

    // `set` offsets the channels of one absorption set (white mode); 0 otherwise.
    void absorb(RayScore& s, std::size_t layer, double x, double y, double z, double w, std::size_t set = 0) const {
        const std::size_t o = set * ch_.count;
        s.add(o + ch_.absorbed, w);
        s.add(o + ch_.first_layer + layer, w);
        if (ch_.nz > 0) {
            const auto iz = std::min(static_cast<std::size_t>(z / request_.grid.dz_cm), ch_.nz - 1);
            s.add(o + ch_.a_z + iz, w);
            if (ch_.nr > 0) s.add(o + ch_.a_rz + r_bin(x, y) * ch_.nz + iz, w);
        }
    }

    void escape(RayScore& s, bool top, double x, double y, double cos_exit, double w, std::size_t set = 0) const {
        const std::size_t o = set * ch_.count;
        s.add(o + (top ? ch_.reflectance : ch_.transmittance), w);
        if (ch_.nr > 0) s.add(o + (top ? ch_.r_r : ch_.t_r) + r_bin(x, y), w);
        if (ch_.na > 0) s.add(o + (top ? ch_.r_a : ch_.t_a) + a_bin(cos_exit), w);
        if (ch_.nr > 0 && ch_.na > 0) s.add(o + (top ? ch_.r_ra : ch_.t_ra) + r_bin(x, y) * ch_.na + a_bin(cos_exit), w);
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
                const auto c = cross_boundary(random, d, k);
                if (c.escaped > 0.0) escape(s, c.top, x, y, c.cos_exit, w * c.escaped);
                if (c.left) return;
                w *= c.kept;
                if (!(w > 0.0)) return;
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

    // Fresnel at the boundary the photon is on (d and k updated): the fraction of its weight that leaves (through
    // the top when `top`, at cos_exit) and the fraction that goes on; `left` when nothing goes on.
    struct Crossing {
        double escaped = 0.0;
        double kept = 1.0;
        bool top = false;
        double cos_exit = 0.0;
        bool left = false;
    };
    Crossing cross_boundary(RandomStream& random, Direction& d, std::size_t& k) const {
        const bool down = d.z > 0.0;
        const std::size_t last = stack_.layers.size() - 1;
        if (down && k == last && stack_.bottom_reflector) {
            d = sample_cosine_hemisphere(random.uniform(), sample_azimuth(random), false);
            return {};
        }
        const bool outer = down ? k == last : k == 0;
        const double n1 = stack_.layers[k].refractive_index;
        const double n2 = outer ? (down ? stack_.below_refractive_index : stack_.above_refractive_index)
                                : stack_.layers[down ? k + 1 : k - 1].refractive_index;
        const double reflect = fresnel_reflectance(d.z, n1, n2);
        const auto transmitted = refract(d, n1, n2);
        if (outer && transmitted && request_.boundaries == BoundaryMode::split) {
            d = mirror(d);
            return {1.0 - reflect, reflect, !down, std::abs(transmitted->z), !(reflect > 0.0)};
        }
        if (!transmitted || (reflect > 0.0 && random.uniform() < reflect)) {
            d = mirror(d);
            return {};
        }
        if (outer) return {1.0, 0.0, !down, std::abs(transmitted->z), true};
        d = *transmitted;
        k = down ? k + 1 : k - 1;
        return {};
    }

    // White Monte Carlo (Alerstam et al. 2008, J. Biomed. Opt. 13:041304): free paths and scattering from mu_s
    // alone, so the path serves every absorption set; set s loses weight by Beer-Lambert along each segment,
    // w_s = (1 - R_sp) c exp(b_s - tau_s) with tau_s its optical depth, b_s its roulette boosts and c the
    // product of the weights kept at split boundaries. Absorption is deposited at the segment's end. Each photon
    // has its own stream; roulette (weight below 1e-4, survival 0.1, energy-conserving) draws a number keyed by
    // (photon, step) shared by every set, so a set's numbers equal those of its own white run to rounding.
    void trace_white(std::uint64_t key, RayScore& s, WhiteState& state) const {
        auto random = RandomStream::for_ray(key);
        for (std::size_t set = 0; set < sets_; ++set) s.add(set * ch_.count + ch_.specular, specular_);
        if (1.0 - specular_ <= 0.0) return;
        double log_common = std::log(1.0 - specular_);
        Direction d = *refract(incident_, stack_.above_refractive_index, stack_.layers.front().refractive_index);
        double x = 0.0, y = 0.0, z = 0.0;
        std::size_t k = 0;
        double tau_left = 0.0;  // scattering optical depth left to travel
        std::fill(state.tau.begin(), state.tau.end(), 0.0);
        std::fill(state.boost_log.begin(), state.boost_log.end(), 0.0);
        std::fill(state.limit.begin(), state.limit.end(), -std::log(roulette_weight));
        state.alive = sets_;
        const auto alive = [&](std::size_t set) { return state.limit[set] != std::numeric_limits<double>::infinity(); };
        const auto weight = [&](std::size_t set) { return std::exp(log_common + state.boost_log[set] - state.tau[set]); };
        for (std::uint64_t step = 0;; ++step) {
            const RteLayer& layer = stack_.layers[k];
            if (step >= request_.max_steps_per_photon) {
                for (std::size_t set = 0; set < sets_; ++set) {
                    if (!alive(set)) continue;
                    absorb(s, k, x, y, z, weight(set), set);
                    s.add(set * ch_.count + ch_.truncated, 1.0);
                }
                return;
            }
            if (tau_left <= 0.0) tau_left = -std::log(1.0 - random.uniform());  // Eq. 3.7 with mu_s
            const double step_cm = layer.mu_s_per_cm > 0.0 ? tau_left / layer.mu_s_per_cm : std::numeric_limits<double>::infinity();
            const double to_boundary = d.z > 0.0 ? (bottom_[k] - z) / d.z
                                       : d.z < 0.0 ? (top_[k] - z) / d.z
                                                   : std::numeric_limits<double>::infinity();
            const bool hits = step_cm >= to_boundary;
            const double segment = hits ? to_boundary : step_cm;
            x += segment * d.x;
            y += segment * d.y;
            z = hits ? (d.z > 0.0 ? bottom_[k] : top_[k]) : z + segment * d.z;
            const double* mu_a = &mu_a_per_cm_[k * sets_];
            for (std::size_t set = 0; set < sets_; ++set) {
                if (!alive(set) || mu_a[set] <= 0.0) continue;
                const double before = weight(set);
                state.tau[set] += mu_a[set] * segment;
                absorb(s, k, x, y, z, before - weight(set), set);
                if (state.tau[set] - state.boost_log[set] - log_common <= state.limit[set]) continue;
                const double w = weight(set);
                if (RandomStream::keyed_uniform(key, step) < roulette_survival) {
                    state.boost_log[set] -= std::log(roulette_survival);
                    absorb(s, k, x, y, z, w - weight(set), set);  // negative: the survivor's gain
                } else {
                    absorb(s, k, x, y, z, w, set);
                    state.limit[set] = std::numeric_limits<double>::infinity();
                    --state.alive;
                }
            }
            if (state.alive == 0) return;
            if (hits) {
                if (layer.mu_s_per_cm > 0.0) tau_left -= to_boundary * layer.mu_s_per_cm;
                const auto c = cross_boundary(random, d, k);
                if (c.escaped > 0.0) {
                    for (std::size_t set = 0; set < sets_; ++set) {
                        if (alive(set)) escape(s, c.top, x, y, c.cos_exit, weight(set) * c.escaped, set);
                    }
                }
                if (c.left) return;
                if (c.kept < 1.0) log_common += std::log(c.kept);
                continue;
            }
            tau_left = 0.0;
            if (layer.mu_s_per_cm > 0.0) {
                const double cs = layer.phase.sample_cos(random);
                d = deflect(d, cs, std::sqrt(std::max(0.0, 1.0 - cs * cs)), sample_azimuth(random));
            }
        }
    }

    const RteRequest& request_;
    const RteStack& stack_;
    const Channels& ch_;
    std::size_t sets_;
    bool white_;
    std::vector<double> mu_a_per_cm_;  // white mode: [layer * sets + set]
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

namespace {

// Runs the walk (MCML's way without `mu_a_sets`, white with them) and returns one result per set.
std::vector<RteResult> run_walk(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets) {
    validate(request.stack);
    if (!std::isfinite(request.incidence_deg) || request.incidence_deg < 0.0 || request.incidence_deg >= 90.0) {
        throw InputError("incidence angle " + format_number(request.incidence_deg) + " deg is outside [0, 90)");
    }
    if (request.photons < 1) throw InputError("photon count 0 is outside [1, inf)");
    const auto& g = request.grid;
    if (g.nz < 0 || g.nr < 0 || g.na < 0 || ((g.nz > 0 || g.nr > 0) && !(g.dz_cm > 0.0 && g.dr_cm > 0.0))) {
        throw InputError("grid: bin counts must be >= 0 and dz, dr > 0");
    }
    for (const auto& set : mu_a_sets) {
        if (set.size() != request.stack.layers.size()) throw InputError("absorption set: one mu_a per layer is needed");
        for (const double mu : set) {
            if (!(std::isfinite(mu) && mu >= 0.0)) throw InputError("absorption set: mu_a [1/cm] = " + format_number(mu) + " is outside [0, inf)");
        }
    }
    const Channels channels(request.stack.layers.size(), g);
    const Walk walk(request, channels, mu_a_sets);
    const std::size_t sets = std::max<std::size_t>(1, mu_a_sets.size());

    SpectralRequest driver;
    driver.wavelengths = WavelengthGrid::list({request.stream_key});
    driver.max_rays_per_wavelength = request.photons;
    driver.stderr_target = request.stderr_target;
    driver.seed = request.seed;
    driver.on_progress = request.on_progress;
    driver.cancel = request.cancel;
    const auto outcome = run_batches(driver, channels.count * sets, {channels.reflectance, channels.transmittance},
                                     [&](std::size_t, RandomStream& random, std::uint64_t n, RayTally& tally) { walk.trace(random, n, tally); },
                                     sets);

    std::vector<RteResult> results;
    const auto& t = outcome.tallies.front();
    // MCML 1.2 scaling (ScaleRdTt, ScaleA): per area of the ring, per solid angle 2 pi sin(a) da, per volume.
    const double dz = g.dz_cm, dr = g.dr_cm, da = g.na > 0 ? 0.5 * pi / g.na : 0.0;
    const auto ring = [&](std::size_t ir) { return 2.0 * pi * (ir + 0.5) * dr * dr; };
    const auto cone = [&](std::size_t ia) { return 2.0 * pi * std::sin((ia + 0.5) * da) * da; };
    const auto one = [](std::size_t) { return 1.0; };
    const auto ra_scale = [&](std::size_t i) {
        const std::size_t ir = i / std::max<std::size_t>(1, channels.na), ia = i % std::max<std::size_t>(1, channels.na);
        return 1.0 / (4.0 * pi * pi * dr * dr * std::sin(da / 2.0) * (ir + 0.5) * std::sin(2.0 * (ia + 0.5) * da));
    };
    for (std::size_t set = 0; set < sets; ++set) {
        const std::size_t o = set * channels.count;
        RteResult r;
        r.partial = outcome.cancelled;
        r.photons = t.rays();
        r.truncated_photons = mu_a_sets.empty() ? t.truncated() : static_cast<std::uint64_t>(std::llround(t.sum(o + channels.truncated)));
        if (r.photons > 0) {
            r.specular_reflectance = t.estimate(o + channels.specular);
            r.diffuse_reflectance = t.estimate(o + channels.reflectance);
            r.transmittance = t.estimate(o + channels.transmittance);
            r.absorption_layers = scaled(t, o + channels.first_layer, channels.layers, one);
            r.absorbed = t.estimate(o + channels.absorbed);
            r.absorption_z = scaled(t, o + channels.a_z, channels.nz, [&](std::size_t) { return 1.0 / dz; });
            r.reflectance_r = scaled(t, o + channels.r_r, channels.nr, [&](std::size_t ir) { return 1.0 / ring(ir); });
            r.transmittance_r = scaled(t, o + channels.t_r, channels.nr, [&](std::size_t ir) { return 1.0 / ring(ir); });
            r.reflectance_a = scaled(t, o + channels.r_a, channels.na, [&](std::size_t ia) { return 1.0 / cone(ia); });
            r.transmittance_a = scaled(t, o + channels.t_a, channels.na, [&](std::size_t ia) { return 1.0 / cone(ia); });
            r.absorption_rz = scaled(t, o + channels.a_rz, channels.nr * channels.nz,
                                     [&](std::size_t i) { return 1.0 / (ring(i / std::max<std::size_t>(1, channels.nz)) * dz); });
            r.reflectance_ra = scaled(t, o + channels.r_ra, channels.nr * channels.na, ra_scale);
            r.transmittance_ra = scaled(t, o + channels.t_ra, channels.nr * channels.na, ra_scale);
        }
        results.push_back(std::move(r));
    }
    return results;
}

std::vector<double> own_absorption(const RteStack& stack) {
    std::vector<double> mu_a;
    for (const auto& l : stack.layers) mu_a.push_back(l.mu_a_per_cm);
    return mu_a;
}

}  // namespace

RteResult solve_rte(const RteRequest& request) {
    return run_walk(request, request.white ? std::vector<std::vector<double>>{own_absorption(request.stack)} : std::vector<std::vector<double>>{})
        .front();
}

std::vector<RteResult> solve_rte_sets(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets) {
    if (mu_a_sets.empty()) throw InputError("absorption replay: no absorption sets");
    return run_walk(request, mu_a_sets);
}

SpectralResult solve_rte_spectrum(const LayerStack& stack, const SpectralRequest& request, BoundaryMode boundaries) {
    return solve_rte_spectra({&stack}, request, boundaries, false).front();
}

std::vector<SpectralResult> solve_rte_spectra(const std::vector<const LayerStack*>& stacks, const SpectralRequest& request,
                                              BoundaryMode boundaries, bool white) {
    if (stacks.empty()) throw InputError("absorption replay: no stacks to simulate");
    const bool replay = stacks.size() > 1 || white;
    for (const auto* stack : stacks) {
        if (const auto why = volumetric_path_difference(*stacks.front(), *stack); !why.empty()) {
            throw InputError("absorption sets '" + stacks.front()->name + "' and '" + stack->name + "' differ in " + why +
                             ", which changes paths (trace them separately)");
        }
    }
    std::vector<SpectralResult> out(stacks.size());
    for (std::size_t s = 0; s < stacks.size(); ++s) {
        auto& o = out[s];
        o.model = "rte";
        o.material = stacks[s]->name;
        o.quantities = Quantities{true, true, true, false};
        for (const auto& l : stacks[s]->layers) o.layer_names.push_back(l.name);
        o.settings = {{"incidence_deg", request.incidence_deg},
                      {"seed", request.seed},
                      {"max_rays_per_wavelength", request.max_rays_per_wavelength},
                      {"boundaries", std::string(boundaries == BoundaryMode::split ? "split" : "random")},
                      {"bottom", std::string(to_string(stacks[s]->bottom))},
                      {"absorption", std::string(replay ? "white Monte Carlo (Beer-Lambert along mu_s paths)" : "MCML (albedo per interaction)")},
                      {"absorption_sets_traced_together", std::uint64_t{stacks.size()}},
                      {"roulette", std::string("weight < 1e-4, survival 0.1, energy-conserving")}};
        if (request.stderr_target) o.settings["stderr_target"] = *request.stderr_target;
    }
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
        r.stack = rte_stack_from(*stacks.front(), nm);
        r.photons = request.max_rays_per_wavelength;
        r.stderr_target = request.stderr_target;
        r.seed = request.seed;
        r.stream_key = nm;
        r.incidence_deg = request.incidence_deg;
        r.boundaries = boundaries;
        r.on_progress = progress;
        r.cancel = request.cancel;
        std::vector<RteResult> results;
        if (replay) {
            std::vector<std::vector<double>> sets;
            for (const auto* stack : stacks) sets.push_back(own_absorption(rte_stack_from(*stack, nm)));
            results = solve_rte_sets(r, sets);
        } else {
            results = {solve_rte(r)};
        }
        rays_before += results.front().photons;
        ++index;
        if (results.front().partial) {
            for (auto& o : out) o.partial = true;
            break;
        }
        for (std::size_t s = 0; s < stacks.size(); ++s) {
            const auto& res = results[s];
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
            out[s].wavelengths.push_back(std::move(w));
        }
    }
    return out;
}

}  // namespace skinspec
