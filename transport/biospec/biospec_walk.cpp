#include "transport/biospec/biospec_walk.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/cosine_hemisphere.hpp"
#include "transport/fresnel.hpp"
#include "transport/henyey_greenstein.hpp"
#include "transport/rayleigh_phase.hpp"
#include "transport/skin_fold.hpp"

namespace skinspec {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr int max_redraws = 1000;          // same-hemisphere re-draws before keeping the unperturbed direction
constexpr double roulette_weight = 1e-4;   // weighted estimator: Russian roulette below this weight
constexpr double roulette_survival = 0.1;

}  // namespace

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
    count = static_cast<std::size_t>(next);
}

BiospecWavelength::BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg,
                                     const BiospecOptions& options, const BiospecChannels& channels,
                                     std::vector<double> edges_deg)
    : n_above_(stack.above_refractive_index),
      n_below_(stack.below_refractive_index),
      reflector_(stack.bottom == BottomBoundary::diffuse_reflector),
      fold_sigma_(stack.fold_aspect_ratio),
      incident_(std::sin(incidence_deg * deg), 0.0, std::cos(incidence_deg * deg)),
      options_(options),
      channels_(channels) {
    for (const double e : edges_deg) bin_edges_cos_.push_back(std::cos(e * deg));
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
                stratum_corneum_table_ = MeasuredProfile::stratum_corneum().inverse_table(wavelength_nm, options.profile_table_entries);
            }
            profile = &*stratum_corneum_table_;
        } else if (o.crossing == CrossingScattering::measured_epidermis) {
            if (!epidermis_table_) {
                epidermis_table_ = MeasuredProfile::epidermis().inverse_table(wavelength_nm, options.profile_table_entries);
            }
            profile = &*epidermis_table_;
        }
        layers_.push_back({o.thickness_cm, o.refractive_index, o.mu_a_per_cm, o.rayleigh_per_cm, o.hg_g, o.crossing, profile});
    }
}

void BiospecWavelength::trace(RandomStream& random, std::uint64_t rays, RayTally& tally) const {
    trace_rays(channels_.count, rays, tally, [&](RayScore& score, std::uint64_t& truncated) { trace_one(random, score, truncated); });
}

void BiospecWavelength::exit_into_bin(int first_bin, double cos_exit, double weight, RayScore& score) const {
    if (first_bin < 0) return;
    // Edges are stored as decreasing cosines; find the bin whose [cos_hi, cos_lo] holds cos_exit.
    const auto it = std::upper_bound(bin_edges_cos_.begin(), bin_edges_cos_.end(), cos_exit, std::greater<>());
    const auto upper = static_cast<std::size_t>(it - bin_edges_cos_.begin());
    const std::size_t bin = upper == 0 ? 0 : std::min(upper - 1, bin_edges_cos_.size() - 2);
    score.add(static_cast<std::size_t>(first_bin) + bin, weight);
}

// Step 2/3 of the specification: the direction change on one crossing of `layer`.
Direction BiospecWavelength::scatter(const Layer& layer, const Direction& d, RandomStream& random) const {
    const bool down = d.z > 0.0;
    const auto same_hemisphere = [&](auto&& draw_cos_sin) {
        for (int attempt = 0; attempt < max_redraws; ++attempt) {
            const auto [cos_t, sin_t] = draw_cos_sin();
            const Direction out = deflect(d, cos_t, sin_t, sample_azimuth(random));
            if ((out.z > 0.0) == down && out.z != 0.0) return out;
        }
        return d;
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
                const double cos_t = std::max(std::abs(d.z), 1e-12);
                if (random.uniform() < -std::expm1(-layer.rayleigh_per_cm * layer.thickness_cm / cos_t)) {
                    const double c = rayleigh_sample_cos(random.uniform());
                    return deflect(d, c, std::sqrt(std::max(0.0, 1.0 - c * c)), sample_azimuth(random));
                }
            }
            [[fallthrough]];
        case CrossingScattering::cosine: {
            const double u = random.uniform();
            return sample_cosine_hemisphere(u, sample_azimuth(random), down);
        }
    }
    return d;
}

void BiospecWavelength::trace_one(RandomStream& random, RayScore& score, std::uint64_t& truncated) const {
    const auto add = [&](int channel, double value) {
        if (channel >= 0) score.add(static_cast<std::size_t>(channel), value);
    };
    const auto absorb = [&](std::size_t layer, double value) {
        if (channels_.absorptance_first_layer >= 0) add(channels_.absorptance_first_layer + static_cast<int>(layer), value);
    };

    // Step 1: air -> stratum corneum. Reflection is perturbed by the skin-fold distribution.
    const double n_top = layers_.front().n;
    if (random.uniform() < fresnel_reflectance(incident_.z, n_above_, n_top)) {
        for (int attempt = 0; attempt < max_redraws; ++attempt) {
            const double c = skin_fold_sample_cos(fold_sigma_, random.uniform());
            const Direction out = deflect(mirror(incident_), c, std::sqrt(std::max(0.0, 1.0 - c * c)), sample_azimuth(random));
            if (out.z < 0.0) {
                add(channels_.reflectance, 1.0);
                add(channels_.specular, 1.0);
                exit_into_bin(channels_.brdf_first_bin, -out.z, 1.0, score);
                return;
            }
            if (options_.fold_into_skin == FoldIntoSkin::drop) break;
        }
        add(channels_.absorptance_surface, 1.0);
        return;
    }
    Direction d = *refract(incident_, n_above_, n_top);  // Fresnel was below 1, so the refracted ray exists
    std::size_t k = 0;
    double weight = 1.0;
    const std::size_t last = layers_.size() - 1;

    for (std::uint32_t event = 0;; ++event) {
        const Layer& layer = layers_[k];
        if (event >= options_.max_events_per_ray) {
            absorb(k, weight);
            ++truncated;
            return;
        }
        // Steps 2-3: direction change on this crossing; step 4: absorption along it.
        d = scatter(layer, d, random);
        const double survival =
            layer.mu_a_per_cm > 0.0 ? std::exp(-layer.mu_a_per_cm * layer.thickness_cm / std::max(std::abs(d.z), 1e-12)) : 1.0;
        if (options_.estimator == AbsorptionEstimator::weighted) {
            const double kept = weight * survival;
            absorb(k, weight - kept);
            weight = kept;
            if (weight < roulette_weight) {
                // Russian roulette that conserves each ray's energy exactly: a survivor's added weight is
                // taken back from this layer's absorption, a loser's weight is absorbed; both unbiased.
                if (random.uniform() < roulette_survival) {
                    const double boosted = weight / roulette_survival;
                    absorb(k, weight - boosted);
                    weight = boosted;
                } else {
                    absorb(k, weight);
                    return;
                }
            }
        } else if (random.uniform() >= survival) {
            absorb(k, weight);
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
        const double reflect = fresnel_reflectance(d.z, layer.n, n_next);
        const auto transmitted = refract(d, layer.n, n_next);
        if (!transmitted || (reflect > 0.0 && random.uniform() < reflect)) {
            d = mirror(d);
            continue;
        }
        d = *transmitted;
        if (down) {
            if (k == last) {
                add(channels_.transmittance, weight);
                exit_into_bin(channels_.btdf_first_bin, d.z, weight, score);
                return;
            }
            ++k;
        } else {
            if (k == 0) {
                add(channels_.reflectance, weight);
                exit_into_bin(channels_.brdf_first_bin, -d.z, weight, score);
                return;
            }
            --k;
        }
    }
}

}  // namespace skinspec
