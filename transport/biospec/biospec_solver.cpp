#include "transport/biospec/biospec_solver.hpp"

#include <cmath>
#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <numbers>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "transport/biospec/biospec_walk.hpp"
#include "transport/biospec/exit_paths.hpp"
#include "transport/ray_planner.hpp"
#include "skinspec/version.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// The set-up of the wavelength each worker is on, built when the worker moves to another wavelength: memory is
// O(workers), not O(wavelengths) (a request may have 1e6), and a wavelength's batches, adjacent in a round, share
// it. Tables that are the same for many wavelengths are shared between set-ups (MeasuredProfile::shared_inverse_table).
template <class Setup>
class PerWorkerSetup {
public:
    explicit PerWorkerSetup(std::function<std::unique_ptr<Setup>(std::size_t)> make) : make_(std::move(make)) {}
    const Setup& at(std::size_t wavelength) {
        auto& slot = current_.local();
        if (!slot.setup || slot.wavelength != wavelength) {
            slot.setup.reset();
            slot.setup = make_(wavelength);
            slot.wavelength = wavelength;
        }
        return *slot.setup;
    }

private:
    struct Slot {
        std::size_t wavelength = 0;
        std::unique_ptr<Setup> setup;
    };
    std::function<std::unique_ptr<Setup>(std::size_t)> make_;
    tbb::enumerable_thread_specific<Slot> current_;
};

void validate(const LayerStack& stack, const SpectralRequest& r, const BiospecOptions& o) {
    if (stack.layers.empty()) throw InputError("material '" + stack.name + "': no layers to simulate");
    check_incidence_deg(r.incidence_deg);
    if (r.geometry == MeasurementGeometry::zero_45 && r.incidence_deg != 0.0) {
        throw InputError("geometry 0-45 defines normal incidence; incidence " + format_number(r.incidence_deg) + " deg given");
    }
    if (r.max_rays_per_wavelength < 1) throw InputError("ray budget 0 is outside [1, inf)");
    if (r.stderr_target && !(std::isfinite(*r.stderr_target) && *r.stderr_target > 0.0)) {
        throw InputError("standard error target " + format_number(*r.stderr_target) + " is outside (0, inf)");
    }
    if (r.rays_per_batch < 1) throw InputError("rays per batch 0 is outside [1, inf)");
    if ((r.stderr_target || r.stderr_targets) && !r.quantities.reflectance && !r.quantities.transmittance) {
        throw InputError("a standard error target needs R or T among the quantities");
    }
    const auto& edges = r.angular_bin_edges_deg;
    if (r.quantities.angular && !edges.empty()) {
        if (edges.size() < 2 || edges.front() != 0.0 || edges.back() != 90.0) {
            throw InputError("angular bin edges must start at 0 and end at 90 deg");
        }
        for (std::size_t i = 1; i < edges.size(); ++i) {
            if (!(edges[i] > edges[i - 1])) throw InputError("angular bin edges must increase strictly");
        }
    }
    if (o.profile_table_entries < 1) throw InputError("profile table entries 0 is outside [1, inf)");
    if (o.max_events_per_ray < 1 || o.max_events_per_ray > std::numeric_limits<std::int32_t>::max()) {
        throw InputError("maximum events per ray " + std::to_string(o.max_events_per_ray) + " is outside [1, 2147483647]");
    }
}

std::map<std::string, SettingValue> settings(const LayerStack& stack, const SpectralRequest& r, const BiospecOptions& o) {
    std::map<std::string, SettingValue> s{
        {"geometry", std::string(to_string(r.geometry))},
        {"absorption_estimator", std::string(to_string(o.estimator))},
        {"fold_into_skin", std::string(to_string(o.fold_into_skin))},
        {"fold_aspect_ratio", stack.fold_aspect_ratio},
        {"bottom", std::string(to_string(stack.bottom))},
        {"above_refractive_index", stack.above_refractive_index},
        {"below_refractive_index", stack.below_refractive_index},
        {"incidence_deg", r.incidence_deg},
        {"seed", r.seed},
        {"max_rays_per_wavelength", r.max_rays_per_wavelength},
        {"rays_per_batch", r.rays_per_batch},
        {"profile_table_entries", std::uint64_t{o.profile_table_entries}},
        {"max_events_per_ray", std::uint64_t{o.max_events_per_ray}},
        {"skinspec_version", std::string(version)},
        {"thin_layer_phase", o.thin_layer_hg ? "henyey_greenstein (" + o.thin_layer_hg->source + ")" : std::string("measured")},
    };
    if (r.stderr_target) s["stderr_target"] = *r.stderr_target;
    return s;
}

// A sweep that asks for R alone (issue 34): its paths are recorded a batch at a time, thinned by analog absorption at
// each layer's smallest absorption over the sets, and re-weighted for every set by the vector kernel of ExitPaths
// (white Monte Carlo, Alerstam et al. 2008, J. Biomed. Opt. 13:041304): per set and exit one exponential. The
// replay's per-set weights, roulette and tallies cost far more (100 levels over 31 wavelengths: 0.84 s above one
// level's walk, against 0.05 s here; docs/PERFORMANCE.md). Unbiased for every set (ExitPaths::thin), but another
// estimator: not equal to the bit to the set's own run. T, A per layer and the angular bins still use the replay.
bool reweighs_recorded_paths(std::size_t sets, const SpectralRequest& request, const BiospecOptions& options) {
    const auto& q = request.quantities;
    return sets > 1 && q.reflectance && !q.transmittance && !q.absorptance && !q.angular && options.estimator == AbsorptionEstimator::weighted;
}

// A wavelength's recording walk at the sets' floor and the sets' absorption, [set * layers + layer].
struct RecordedSets {
    std::vector<double> mu_a_per_cm;
    std::unique_ptr<BiospecWavelength> walk;
};

std::unique_ptr<RecordedSets> recorded_sets(const std::vector<const LayerStack*>& stacks, const SpectralRequest& request, const BiospecOptions& options,
                                            std::size_t w) {
    const double nm = request.wavelengths[w];
    auto out = std::make_unique<RecordedSets>();
    out->mu_a_per_cm = BiospecWavelength::sets_absorption_per_cm(stacks, nm);
    const std::size_t layers = stacks.front()->layers.size();
    std::vector<double> floor(layers, std::numeric_limits<double>::infinity());
    for (std::size_t s = 0; s < stacks.size(); ++s) {
        for (std::size_t k = 0; k < layers; ++k) floor[k] = std::min(floor[k], out->mu_a_per_cm[s * layers + k]);
    }
    out->walk = std::make_unique<BiospecWavelength>(*stacks.front(), nm, request.incidence_deg, request.geometry, options, std::move(floor));
    return out;
}

}  // namespace

SpectralResult solve_biospec(const LayerStack& stack, const SpectralRequest& request, const BiospecOptions& options) {
    return solve_biospec_sets({&stack}, request, options).front();
}

std::vector<SpectralResult> solve_biospec_sets(const std::vector<const LayerStack*>& stacks, const SpectralRequest& request,
                                               const BiospecOptions& options) {
    if (stacks.empty()) throw InputError("absorption replay: no stacks to simulate");
    for (const auto* stack : stacks) validate(*stack, request, options);
    const auto& first = *stacks.front();
    const auto edges = request.quantities.angular
                           ? (request.angular_bin_edges_deg.empty() ? default_angular_bin_edges_deg() : request.angular_bin_edges_deg)
                           : std::vector<double>{};
    const std::size_t bins = edges.empty() ? 0 : edges.size() - 1;
    const BiospecChannels channels(request.quantities, first.layers.size(), bins);
    const std::size_t sets = stacks.size();

    const auto make = [&](std::size_t w) {
        return std::make_unique<BiospecWavelength>(stacks, request.wavelengths[w], request.incidence_deg, request.geometry, options, channels, edges);
    };
    make(0);  // the sets' compatibility is checked before any ray is traced
    PerWorkerSetup<BiospecWavelength> setups(make);
    std::vector<std::size_t> targets;
    if (channels.reflectance >= 0) targets.push_back(static_cast<std::size_t>(channels.reflectance));
    if (channels.transmittance >= 0) targets.push_back(static_cast<std::size_t>(channels.transmittance));

    const bool reweighed = reweighs_recorded_paths(sets, request, options);
    PerWorkerSetup<RecordedSets> recorded([&](std::size_t w) { return recorded_sets(stacks, request, options, w); });
    const std::size_t layers = first.layers.size();
    const std::vector<double> unscaled(layers, 1.0);
    // Recorded: a batch's exits re-weighted for every set; R per ray is its exit's weight (a ray leaves once).
    const auto record = [&](std::size_t w, RandomStream& random, std::uint64_t rays, RayTally& tally) {
        const auto& setup = recorded.at(w);
        ExitPaths paths;
        setup.walk->record(random, rays, paths);
        tally.add_rays(rays);
        // The first-surface reflections and the rays stopped at the cap are the same for every set (a ray's 1 each).
        const auto specular = static_cast<double>(paths.surface_reflections);
        const auto truncated = static_cast<double>(paths.truncated_rays);
        std::vector<double> mu(layers);
        for (std::size_t s = 0; s < sets; ++s) {
            const std::size_t offset = s * channels.count;
            std::copy_n(setup.mu_a_per_cm.begin() + static_cast<std::ptrdiff_t>(s * layers), layers, mu.begin());
            const auto sums = paths.weight_sums(mu, unscaled);
            tally.add_exits(offset + static_cast<std::size_t>(channels.reflectance), paths.factor * sums.sum,
                            paths.factor * paths.factor * sums.sum_of_squares);
            if (channels.specular >= 0) tally.add_exits(offset + static_cast<std::size_t>(channels.specular), specular, specular);
            tally.add_exits(offset + static_cast<std::size_t>(channels.truncated), truncated, truncated);
        }
    };
    const auto outcome = run_batches(request, channels.count * sets, targets,
                                     [&](std::size_t w, std::uint64_t, RandomStream& random, std::uint64_t rays, RayTally& tally) {
                                         if (reweighed) record(w, random, rays, tally);
                                         else setups.at(w).trace(random, rays, tally);
                                     },
                                     sets);

    std::vector<SpectralResult> results;
    for (std::size_t s = 0; s < sets; ++s) {
        const auto& stack = *stacks[s];
        SpectralResult result;
        result.model = "biospec";
        result.material = stack.name;
        result.settings = settings(stack, request, options);
        result.settings["absorption_sets_traced_together"] = std::uint64_t{sets};
        if (sets > 1) {
            result.settings["absorption_sets_estimator"] = std::string(
                reweighed ? "recorded paths, thinned at the sets' smallest absorption and re-weighted per set" : "replay (per-set weights and roulette)");
        }
        for (const auto& layer : stack.layers) result.layer_names.push_back(layer.name);
        result.angular_bin_edges_deg = edges;
        result.quantities = request.quantities;
        result.partial = outcome.cancelled;
        const int offset = static_cast<int>(s * channels.count);
        for (std::size_t w = 0; w < request.wavelengths.size(); ++w) {
            if (!outcome.finished[w]) continue;
            const auto& t = outcome.tallies[w];
            WavelengthResult r;
            r.wavelength_nm = request.wavelengths[w];
            const auto channel = [&](int c) { return c >= 0 ? t.estimate(static_cast<std::size_t>(offset + c)) : Estimate{}; };
            r.reflectance = channel(channels.reflectance);
            r.specular_reflectance = channel(channels.specular);
            r.transmittance = channel(channels.transmittance);
            r.absorptance_surface = channel(channels.absorptance_surface);
            if (channels.absorptance_first_layer >= 0) {
                for (std::size_t k = 0; k < stack.layers.size(); ++k) {
                    r.absorptance_layers.push_back(channel(channels.absorptance_first_layer + static_cast<int>(k)));
                }
            }
            // Virtual goniometer (Baranoski et al. 2005 Eq. 10): f = F_i / (delta omega_i cos theta_i), the fraction
            // F_i of the incident flux leaving through polar bin i, delta omega_i its solid angle, theta_i its centre.
            for (std::size_t b = 0; b < bins; ++b) {
                constexpr double deg = std::numbers::pi / 180.0;
                const double solid_angle = 2.0 * std::numbers::pi * (std::cos(edges[b] * deg) - std::cos(edges[b + 1] * deg));
                const double cos_centre = std::cos(0.5 * (edges[b] + edges[b + 1]) * deg);
                const double scale = 1.0 / (solid_angle * cos_centre);
                const auto f = [&](int first_bin) {
                    const auto e = channel(first_bin + static_cast<int>(b));
                    return Estimate{e.value * scale, e.stderr * scale};
                };
                r.brdf_per_sr.push_back(f(channels.brdf_first_bin));
                r.btdf_per_sr.push_back(f(channels.btdf_first_bin));
            }
            r.rays = t.rays();
            r.truncated_rays = static_cast<std::uint64_t>(std::llround(t.sum(static_cast<std::size_t>(offset + channels.truncated))));
            r.converged = outcome.converged[w];
            result.wavelengths.push_back(std::move(r));
        }
        results.push_back(std::move(result));
    }
    return results;
}

}  // namespace skinspec

namespace skinspec {

std::optional<std::vector<ExitPaths>> record_biospec_paths(const LayerStack& stack, const SpectralRequest& request, const BiospecOptions& options) {
    validate(stack, request, options);
    const auto& nm = request.wavelengths.nm();
    PerWorkerSetup<BiospecWavelength> setups(
        [&](std::size_t w) { return std::make_unique<BiospecWavelength>(stack, nm[w], request.incidence_deg, request.geometry, options); });
    const std::uint64_t per_batch = request.rays_per_batch;
    const std::uint64_t batches = (request.max_rays_per_wavelength + per_batch - 1) / per_batch;
    std::vector<ExitPaths> parts(nm.size() * batches);
    std::atomic<bool> stopped{false};
    tbb::parallel_for(std::size_t{0}, parts.size(), [&](std::size_t task) {
        if (request.cancel && request.cancel->load()) {
            stopped = true;
            return;
        }
        const std::size_t w = task / batches;
        const std::uint64_t b = task % batches;
        const std::uint64_t rays = std::min(per_batch, request.max_rays_per_wavelength - b * per_batch);
        auto random = RandomStream::for_batch(request.seed, nm[w], b);
        setups.at(w).record(random, rays, parts[task]);
    });
    if (stopped) return std::nullopt;
    std::vector<ExitPaths> out(nm.size());
    for (std::size_t w = 0; w < nm.size(); ++w) {
        for (std::uint64_t b = 0; b < batches; ++b) {
            auto& part = parts[w * batches + b];
            out[w].factor = part.factor;
            out[w].append(part);
        }
    }
    return out;
}

}  // namespace skinspec
