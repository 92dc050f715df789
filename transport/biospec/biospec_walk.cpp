#include "transport/biospec/biospec_walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "transport/cosine_hemisphere.hpp"
#include "transport/fresnel.hpp"
#include "transport/henyey_greenstein.hpp"
#include "transport/rayleigh_phase.hpp"
#include "transport/skin_fold.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr int max_redraws = 1000;          // same-hemisphere re-draws before keeping the unperturbed direction
constexpr double roulette_weight = 1e-4;   // weighted estimator: Russian roulette below this weight
constexpr double roulette_survival = 0.1;
const double roulette_depth = -std::log(roulette_weight);     // tau - ln(boost) beyond which a set plays roulette
const double boost_log = -std::log(roulette_survival);
constexpr double dead_limit = std::numeric_limits<double>::infinity();  // the limit of a set that lost the roulette
constexpr std::uint32_t roulette_every = 8;  // crossings between two roulette looks at the sets' weights

}  // namespace

std::string biospec_path_difference(const LayerStack& a, const LayerStack& b) {
    if (a.layers.size() != b.layers.size()) return "the number of layers";
    if (a.above_refractive_index != b.above_refractive_index || a.below_refractive_index != b.below_refractive_index) return "the surrounding indices";
    if (a.bottom != b.bottom) return "the bottom boundary";
    if (a.fold_aspect_ratio != b.fold_aspect_ratio) return "the fold aspect ratio";
    if (a.model.dermal_rayleigh != b.model.dermal_rayleigh) return "model.dermal_rayleigh";
    if (a.model.rayleigh_turn != b.model.rayleigh_turn) return "model.rayleigh_turn";
    if (a.model.swapped_upward_indices != b.model.swapped_upward_indices) return "model.swapped_upward_indices";
    if (a.model.bottom_exit_fresnel != b.model.bottom_exit_fresnel) return "model.bottom_exit_fresnel";
    if (a.model.redraw_reversals_in_stratum_corneum != b.model.redraw_reversals_in_stratum_corneum) {
        return "model.redraw_reversals_in_stratum_corneum";
    }
    if (a.model.fold_formula != b.model.fold_formula) return "model.fold_formula";
    for (std::size_t k = 0; k < a.layers.size(); ++k) {
        const auto& x = a.layers[k];
        const auto& y = b.layers[k];
        if (x.thickness_cm != y.thickness_cm || x.refractive_index != y.refractive_index || x.crossing != y.crossing || x.hg_g != y.hg_g ||
            x.collagen_fibre_fraction != y.collagen_fibre_fraction || x.collagen_fibre_radius_nm != y.collagen_fibre_radius_nm ||
            x.collagen_fibre_index != y.collagen_fibre_index) {
            return "layer '" + x.name + "' geometry or scattering";
        }
    }
    return {};
}


BiospecChannels::BiospecChannels(const Quantities& q, std::size_t layers, std::size_t bins) {
    int next = 0;
    if (q.reflectance) {
        reflectance = next++;
        specular = next++;
    }
    if (q.transmittance) transmittance = next++;
    if (q.absorptance) {
        absorptance_surface = next++;
        absorptance_first_layer = next;
        next += static_cast<int>(layers);
    }
    if (q.angular) {
        brdf_first_bin = next;
        next += static_cast<int>(bins);
        btdf_first_bin = next;
        next += static_cast<int>(bins);
    }
    truncated = next++;
    count = static_cast<std::size_t>(next);
}

// Per-ray state of the absorption sets, reused from ray to ray, in dense arrays so that the per-crossing update
// of every set vectorises: optical depth tau, log of the roulette boosts, and the depth beyond which the set
// plays roulette (+inf once it has lost: its weight exp(boost - tau) is then 0 and it is skipped).
struct BiospecWavelength::RayState {
    std::vector<double> tau, boost_log, limit;
    std::size_t alive = 0;
};

BiospecWavelength::BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                                     const BiospecOptions& options)
    : BiospecWavelength(stack, wavelength_nm, incidence_deg, geometry, options, BiospecChannels(Quantities{}, stack.layers.size(), 0), {}) {
    if (options.estimator != AbsorptionEstimator::weighted) throw InputError("path recording needs the weighted estimator");
    // One indicator "absorption set" per layer: set s's optical depth is the ray's path length in layer s.
    sets_ = layers_.size();
    mu_a_per_cm_.assign(sets_ * sets_, 0.0);
    for (std::size_t k = 0; k < sets_; ++k) mu_a_per_cm_[k * sets_ + k] = 1.0;
    recording_ = true;
}

BiospecWavelength::BiospecWavelength(const std::vector<const LayerStack*>& sets, double wavelength_nm, double incidence_deg,
                                     MeasurementGeometry geometry, const BiospecOptions& options, const BiospecChannels& channels,
                                     std::vector<double> edges_deg)
    : BiospecWavelength(*sets.front(), wavelength_nm, incidence_deg, geometry, options, channels, std::move(edges_deg)) {
    sets_ = sets.size();
    if (sets_ > 1 && options.estimator != AbsorptionEstimator::weighted) {
        throw InputError("absorption replay needs the weighted estimator (the random test makes paths depend on absorption)");
    }
    mu_a_per_cm_.assign(layers_.size() * sets_, 0.0);
    for (std::size_t s = 0; s < sets_; ++s) {
        if (const auto why = biospec_path_difference(*sets.front(), *sets[s]); !why.empty()) {
            throw InputError("absorption sets '" + sets.front()->name + "' and '" + sets[s]->name + "' differ in " + why +
                             ", which changes paths (trace them separately)");
        }
        for (std::size_t k = 0; k < layers_.size(); ++k) {
            mu_a_per_cm_[k * sets_ + s] = absorption_per_cm(sets[s]->layers[k], wavelength_nm, sets[s]->model);
        }
    }
}


BiospecWavelength::BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                                     const BiospecOptions& options, const BiospecChannels& channels,
                                     std::vector<double> edges_deg)
    : n_above_(stack.above_refractive_index),
      n_below_(stack.below_refractive_index),
      reflector_(stack.bottom == BottomBoundary::diffuse_reflector),
      fold_sigma_(stack.fold_aspect_ratio),
      model_(stack.model),
      geometry_(geometry),
      incident_(std::sin(incidence_deg * deg), 0.0, std::cos(incidence_deg * deg)),
      options_(options),
      channels_(channels) {
    for (const double e : edges_deg) bin_edges_cos_.push_back(std::cos(e * deg));
    if (geometry == MeasurementGeometry::zero_45) {
        if (incidence_deg != 0.0) throw InputError("geometry 0-45 needs normal incidence (incidence " + std::to_string(incidence_deg) + " deg given)");
        band_cos_lo_ = std::cos(zero_45_band_hi_deg * deg);
        band_cos_hi_ = std::cos(zero_45_band_lo_deg * deg);
        // A perfect diffuser sends sin^2 hi - sin^2 lo = cos^2 lo - cos^2 hi of its light into the band.
        band_factor_ = 1.0 / (band_cos_hi_ * band_cos_hi_ - band_cos_lo_ * band_cos_lo_);
    }
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        auto o = stack.optics(k, wavelength_nm, OpticsScope{false, false});
        if (options.thin_layer_hg && o.crossing == CrossingScattering::measured_stratum_corneum) {
            o.crossing = CrossingScattering::henyey_greenstein;
            o.hg_g = options.thin_layer_hg->stratum_corneum_g(wavelength_nm);
        } else if (options.thin_layer_hg && o.crossing == CrossingScattering::measured_epidermis) {
            o.crossing = CrossingScattering::henyey_greenstein;
            o.hg_g = options.thin_layer_hg->epidermis_g(wavelength_nm);
        }
        const InverseCdfTable* profile = nullptr;
        if (o.crossing == CrossingScattering::measured_stratum_corneum) {
            if (!stratum_corneum_table_) {
                stratum_corneum_table_ = MeasuredProfile::stratum_corneum().shared_inverse_table(wavelength_nm, options.profile_table_entries);
            }
            profile = stratum_corneum_table_.get();
        } else if (o.crossing == CrossingScattering::measured_epidermis) {
            if (!epidermis_table_) {
                epidermis_table_ = MeasuredProfile::epidermis().shared_inverse_table(wavelength_nm, options.profile_table_entries);
            }
            profile = epidermis_table_.get();
        }
        layers_.push_back({o.thickness_cm, o.refractive_index, o.rayleigh_per_cm, o.hg_g, o.crossing, profile});
        mu_a_per_cm_.push_back(o.mu_a_per_cm);
    }
}

void BiospecWavelength::trace(RandomStream& random, std::uint64_t rays, RayTally& tally) const {
    if (recording_) throw InputError("a path-recording walk records paths (BiospecWavelength::record)");
    RayState state{std::vector<double>(sets_), std::vector<double>(sets_), std::vector<double>(sets_), 0};
    RayScore score(channels_.count * sets_);
    for (std::uint64_t i = 0; i < rays; ++i) {
        trace_one(random.bits64(), score, tally, state, nullptr);
        tally.add_ray(score);
    }
}

void BiospecWavelength::record(RandomStream& random, std::uint64_t rays, ExitPaths& paths) const {
    if (!recording_) throw InputError("only a path-recording walk records paths");
    RayState state{std::vector<double>(sets_), std::vector<double>(sets_), std::vector<double>(sets_), 0};
    RayScore score(channels_.count * sets_);
    RayTally unused(channels_.count * sets_);
    paths.resize_layers(layers_.size());
    paths.factor = geometry_ == MeasurementGeometry::zero_45 ? band_factor_ : 1.0;
    for (std::uint64_t i = 0; i < rays; ++i) trace_one(random.bits64(), score, unused, state, &paths);
    paths.rays += rays;
}

double BiospecWavelength::geometry_factor(double cos_exit, bool first_surface) const {
    switch (geometry_) {
        case MeasurementGeometry::sci: return 1.0;
        case MeasurementGeometry::sce: return first_surface ? 0.0 : 1.0;
        case MeasurementGeometry::zero_45: return cos_exit >= band_cos_lo_ && cos_exit <= band_cos_hi_ ? band_factor_ : 0.0;
    }
    return 0.0;
}

std::size_t BiospecWavelength::exit_bin(double cos_exit) const {
    // Edges are stored as decreasing cosines; find the bin whose [cos_hi, cos_lo] holds cos_exit.
    const auto it = std::upper_bound(bin_edges_cos_.begin(), bin_edges_cos_.end(), cos_exit, std::greater<>());
    const auto upper = static_cast<std::size_t>(it - bin_edges_cos_.begin());
    return upper == 0 ? 0 : std::min(upper - 1, bin_edges_cos_.size() - 2);
}

// Step 2/3 of the specification: the direction change on one crossing of `layer`, and the path it is charged.
BiospecWavelength::Crossing BiospecWavelength::scatter(const Layer& layer, const Direction& d, RandomStream& random) const {
    const bool down = d.z > 0.0;
    const auto whole = [&](const Direction& out) { return Crossing{out, layer.thickness_cm / std::max(std::abs(out.z), 1e-12), false}; };
    const bool redraw = layer.crossing != CrossingScattering::measured_stratum_corneum || model_.redraw_reversals_in_stratum_corneum;
    const auto same_hemisphere = [&](auto&& draw_cos_sin) {
        for (int attempt = 0; attempt < max_redraws; ++attempt) {
            const auto [cos_t, sin_t] = draw_cos_sin();
            const Direction out = deflect(d, cos_t, sin_t, sample_azimuth(random));
            if ((out.z > 0.0) == down && out.z != 0.0) return whole(out);
            // Authors' behaviour 4: the SC keeps a reversing perturbation (the caller handles the reversal).
            if (!redraw && out.z != 0.0) return Crossing{out, 0.0, true};
        }
        return whole(d);
    };
    switch (layer.crossing) {
        case CrossingScattering::measured_stratum_corneum:
        case CrossingScattering::measured_epidermis:
            return same_hemisphere([&] {
                const auto i = layer.profile->index(random.uniform());
                return std::pair{layer.profile->cos_theta(i), layer.profile->sin_theta(i)};
            });
        case CrossingScattering::henyey_greenstein:
            return same_hemisphere([&] {
                const double c = hg_sample_cos(layer.hg_g, random.uniform());
                return std::pair{c, std::sqrt(std::max(0.0, 1.0 - c * c))};
            });
        case CrossingScattering::rayleigh_cosine:
            if (down) {
                const double cos_in = std::max(std::abs(d.z), 1e-12);
                const double u = random.uniform();
                const double beta = layer.rayleigh_per_cm;
                if (u < -std::expm1(-beta * layer.thickness_cm / cos_in)) {
                    const double c = rayleigh_sample_cos(random.uniform());
                    const Direction out = deflect(d, c, std::sqrt(std::max(0.0, 1.0 - c * c)), sample_azimuth(random));
                    const double cos_out = std::max(std::abs(out.z), 1e-12);
                    switch (model_.rayleigh_turn) {
                        case RayleighTurn::sampled_depth: {
                            // Shared spec 2026-12: free path s ~ Exp(beta) (the same u decides whether it falls inside
                            // the layer), turn at depth z = s cos_in, then on to the top or the bottom.
                            const double s_cm = -std::log1p(-u) / beta;
                            const double z_cm = std::min(s_cm * cos_in, layer.thickness_cm);
                            const double rest_cm = out.z < 0.0 ? z_cm : layer.thickness_cm - z_cm;
                            return Crossing{out, s_cm + rest_cm / cos_out, false};
                        }
                        case RayleighTurn::whole_crossing: return whole(out);
                        case RayleighTurn::no_absorption: return out.z < 0.0 ? Crossing{out, 0.0, false} : whole(out);
                    }
                }
            }
            [[fallthrough]];
        case CrossingScattering::cosine: {
            const double u = random.uniform();
            return whole(sample_cosine_hemisphere(u, sample_azimuth(random), down));
        }
    }
    return whole(d);
}

void BiospecWavelength::trace_one(std::uint64_t ray_key, RayScore& score, RayTally& tally, RayState& state, ExitPaths* paths) const {
    auto random = RandomStream::for_ray(ray_key);
    const auto add = [&](std::size_t set, int channel, double value) {
        if (channel >= 0) score.add(set * channels_.count + static_cast<std::size_t>(channel), value);
    };
    const bool absorptance = channels_.absorptance_first_layer >= 0;
    const auto absorb = [&](std::size_t set, std::size_t layer, double value) {
        if (absorptance) add(set, channels_.absorptance_first_layer + static_cast<int>(layer), value);
    };
    const auto weight = [&](std::size_t set) { return std::exp(state.boost_log[set] - state.tau[set]); };
    // Exits reach each channel once per ray: straight into the tally.
    const auto leave = [&](std::size_t set, int channel, double w) {
        if (channel >= 0) tally.add_single(set * channels_.count + static_cast<std::size_t>(channel), w);
    };
    const auto bin = [&](std::size_t set, int first_bin, double cos_exit, double w) {
        if (first_bin >= 0) leave(set, first_bin + static_cast<int>(exit_bin(cos_exit)), w);
    };

    // Step 1: air -> stratum corneum. Reflection is perturbed by the skin-fold distribution.
    const double n_top = layers_.front().n;
    if (random.uniform() < fresnel_reflectance(incident_.z, n_above_, n_top)) {
        for (int attempt = 0; attempt < max_redraws; ++attempt) {
            const double u = random.uniform();
            const double c = model_.fold_formula == FoldFormula::biospec_2004 ? skin_fold_sample_cos(fold_sigma_, u)
                                                                             : skin_fold_authors_sample_cos(fold_sigma_, u);
            const Direction out = deflect(mirror(incident_), c, std::sqrt(std::max(0.0, 1.0 - c * c)), sample_azimuth(random));
            if (out.z < 0.0) {
                const double f = geometry_factor(-out.z, true);
                if (paths) {
                    if (f > 0.0) ++paths->surface_exits;
                    return;
                }
                for (std::size_t s = 0; s < sets_; ++s) {
                    leave(s, channels_.reflectance, f);
                    leave(s, channels_.specular, 1.0);
                    bin(s, channels_.brdf_first_bin, -out.z, 1.0);
                }
                return;
            }
            if (options_.fold_into_skin == FoldIntoSkin::drop) break;
        }
        for (std::size_t s = 0; s < sets_; ++s) add(s, channels_.absorptance_surface, 1.0);
        return;
    }
    Direction d = *refract(incident_, n_above_, n_top);  // Fresnel was below 1, so the refracted ray exists
    std::size_t k = 0;
    const std::size_t last = layers_.size() - 1;
    std::fill(state.tau.begin(), state.tau.end(), 0.0);
    std::fill(state.boost_log.begin(), state.boost_log.end(), 0.0);
    std::fill(state.limit.begin(), state.limit.end(), roulette_depth);
    state.alive = sets_;
    const auto alive = [&](std::size_t set) { return state.limit[set] != dead_limit; };
    const bool weighted = options_.estimator == AbsorptionEstimator::weighted;
    // A ray leaving the top with |cos| = cos_exit: into R (or the recorded paths) as the geometry accepts it.
    const auto leave_top = [&](double cos_exit) {
        const double f = geometry_factor(cos_exit, false);
        if (paths) {
            if (f > 0.0) paths->add_exit(state.tau);
            return;
        }
        for (std::size_t s = 0; s < sets_; ++s) {
            if (!alive(s)) continue;
            const double w = weight(s);
            leave(s, channels_.reflectance, w * f);
            bin(s, channels_.brdf_first_bin, cos_exit, w);
        }
    };

    for (std::uint32_t event = 0;; ++event) {
        const Layer& layer = layers_[k];
        if (event >= options_.max_events_per_ray) {
            if (paths) return;
            for (std::size_t s = 0; s < sets_; ++s) {
                if (!alive(s)) continue;
                absorb(s, k, weight(s));
                add(s, channels_.truncated, 1.0);
            }
            return;
        }
        // Steps 2-3: direction change on this crossing; step 4: absorption along it, per set.
        const bool was_down = d.z > 0.0;
        const Crossing crossing = scatter(layer, d, random);
        d = crossing.d;
        if (crossing.reversed && was_down) {
            // Authors' behaviour 4: a down-going SC ray turned upward leaves as reflectance, no Fresnel, no absorption.
            leave_top(-d.z);
            return;
        }
        const double path_cm = crossing.path_cm;
        const double* mu_a = &mu_a_per_cm_[k * sets_];
        if (weighted) {
            double* __restrict tau = state.tau.data();
            if (absorptance) {
                for (std::size_t s = 0; s < sets_; ++s) {
                    const double before = tau[s];
                    tau[s] += mu_a[s] * path_cm;
                    if (alive(s) && mu_a[s] > 0.0) absorb(s, k, std::exp(state.boost_log[s] - before) - weight(s));
                }
            } else {
                for (std::size_t s = 0; s < sets_; ++s) tau[s] += mu_a[s] * path_cm;  // the hot loop of a replay
            }
            // Russian roulette, every roulette_every crossings, for the sets whose weight fell below roulette_weight,
            // conserving each ray's energy exactly: a survivor's added weight is taken back from this layer's
            // absorption, a loser's weight is absorbed; both unbiased. Recorded paths carry no absorption.
            if (!paths && event % roulette_every == roulette_every - 1) {
                for (std::size_t s = 0; s < sets_; ++s) {
                    if (!(tau[s] > state.limit[s])) continue;  // also skips the sets that lost (limit inf)
                    const double w = weight(s);
                    if (RandomStream::keyed_uniform(ray_key, event) < roulette_survival) {
                        state.boost_log[s] += boost_log;
                        state.limit[s] += boost_log;
                        absorb(s, k, w - weight(s));
                    } else {
                        absorb(s, k, w);
                        state.limit[s] = dead_limit;
                        --state.alive;
                    }
                }
                if (state.alive == 0) return;
            }
        } else if (mu_a[0] > 0.0 && random.uniform() >= std::exp(-mu_a[0] * path_cm)) {
            absorb(0, k, 1.0);
            return;
        }
        // Steps 5-6: the interface the ray now meets.
        const bool down = d.z > 0.0;
        if (down && k == last && reflector_) {
            const double u = random.uniform();
            d = sample_cosine_hemisphere(u, sample_azimuth(random), false);
            continue;
        }
        const double n_next = down ? (k == last ? n_below_ : layers_[k + 1].n) : (k == 0 ? n_above_ : layers_[k - 1].n);
        const bool bottom_exit = down && k == last;
        if (!(bottom_exit && !model_.bottom_exit_fresnel)) {
            // Authors' behaviour 1: upward crossings evaluate the interface with its indices swapped.
            const bool swap = !down && model_.swapped_upward_indices;
            const double n_from = swap ? n_next : layer.n;
            const double n_to = swap ? layer.n : n_next;
            const double reflect = fresnel_reflectance(d.z, n_from, n_to);
            const auto transmitted = refract(d, n_from, n_to);
            if (!transmitted || (reflect > 0.0 && random.uniform() < reflect)) {
                d = mirror(d);
                continue;
            }
            d = *transmitted;
        }
        if (down) {
            if (k == last) {
                if (paths) return;
                for (std::size_t s = 0; s < sets_; ++s) {
                    if (!alive(s)) continue;
                    const double w = weight(s);
                    leave(s, channels_.transmittance, w);
                    bin(s, channels_.btdf_first_bin, d.z, w);
                }
                return;
            }
            ++k;
        } else {
            if (k == 0) {
                leave_top(-d.z);
                return;
            }
            --k;
        }
    }
}

}  // namespace skinspec
