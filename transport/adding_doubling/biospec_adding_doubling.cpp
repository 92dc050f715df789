#include "transport/adding_doubling/biospec_adding_doubling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "spectral/input_error.hpp"
#include "transport/adding_doubling/ad_elements.hpp"
#include "transport/adding_doubling/adding_doubling_spectrum.hpp"
#include "transport/adding_doubling/hypodermis_reflectance.hpp"
#include "transport/adding_doubling/phase_moments.hpp"
#include "transport/biospec/biospec_packet.hpp"
#include "transport/skin_fold.hpp"

namespace skinspec {

struct AdCache::TableMoments {
    std::shared_ptr<const InverseCdfTable> table;
    std::vector<double> moments;
};

namespace {

// int_0^d exp(-a z) exp(-b (d - z)) dz = d exp(-min) (1 - exp(-|x - y|)) / |x - y| with x = a d, y = b d (no
// cancellation when a and b are close).
double depth_integral(double a, double b, double d) {
    const double x = a * d, y = b * d, gap = std::abs(x - y);
    const double common = d * std::exp(-std::min(x, y));
    return gap < 1e-12 ? common : common * -std::expm1(-gap) / gap;
}

// The channels that propagate in a medium of index n: cosine, flux weight (share of a cosine-distributed flux).
struct Live {
    std::vector<Eigen::Index> index;
    std::vector<double> mu, weight;
};
Live live_channels(const AdChannels& c, double n) {
    Live l;
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (c.s[k] >= n) continue;
        l.index.push_back(static_cast<Eigen::Index>(k));
        l.mu.push_back(c.cosine(k, n));
        l.weight.push_back(c.weight(k, n));
    }
    return l;
}

AdElement empty_layer(const AdChannels& c) {
    const auto size = static_cast<Eigen::Index>(c.size());
    return AdElement{AdElement::Kind::layer, {}, {}, {}, AdMatrix::Zero(size, size), AdMatrix::Zero(size, size), {}, {}};
}

// Step 2 (SC, epidermis; docs/BIOSPEC.md "One ray"): deflected by the redistribution `e` within the travel hemisphere (the walk
// re-draws reversals), then exp(-mu_a d / cos). The same both ways.
AdElement perturbing_layer(const AdChannels& c, const LayerOptics& o, const AdCache::Entry& e) {
    auto out = empty_layer(c);
    const auto m = static_cast<Eigen::Index>(e.live.size());
    for (Eigen::Index j = 0; j < m; ++j) {
        // The delta-M forward part f stays in its channel; the rest follows H(mu_i | mu_j) w_i (clipped at 0 where the
        // truncated series dips, then renormalised over the hemisphere).
        std::vector<double> share(static_cast<std::size_t>(m));
        double sum = 0.0;
        for (Eigen::Index i = 0; i < m; ++i) {
            const double p = (i == j ? e.f : 0.0) + (1.0 - e.f) * std::max(0.0, e.same(i, j)) * e.w(i);
            share[static_cast<std::size_t>(i)] = p;
            sum += p;
        }
        for (Eigen::Index i = 0; i < m; ++i) {
            const auto a = static_cast<Eigen::Index>(e.live[static_cast<std::size_t>(i)]);
            const auto b = static_cast<Eigen::Index>(e.live[static_cast<std::size_t>(j)]);
            out.t(a, b) = share[static_cast<std::size_t>(i)] / sum * std::exp(-o.mu_a_per_cm * o.thickness_cm / e.mu(i));
        }
    }
    return out;
}

// Step 3 (dermal layers) with step 4's absorption; the Rayleigh turn as the model's RayleighTurn reads it.
AdElement dermal_layer(const AdChannels& c, const LayerOptics& o, RayleighTurn turn) {
    const auto l = live_channels(c, o.refractive_index);
    const std::size_t m = l.index.size();
    const double d = o.thickness_cm, mu_a = o.mu_a_per_cm, beta = o.turn_per_cm();
    auto out = empty_layer(c);
    out.r_up = AdMatrix::Zero(out.r.rows(), out.r.cols());
    out.t_up = AdMatrix::Zero(out.r.rows(), out.r.cols());
    std::vector<double> through(m);  // a cosine-distributed direction, then the crossing's absorption
    for (std::size_t i = 0; i < m; ++i) through[i] = l.weight[i] * std::exp(-mu_a * d / l.mu[i]);
    // The Rayleigh phase (1 + cos^2) averaged over azimuth, as a density in mu (either hemisphere):
    // 1/2 + P2(mu) P2(mu') / 4 (Legendre moments 1 and chi_2 = 1/10; e.g. Chandrasekhar 1960, Radiative Transfer, ch. I).
    const auto p2 = [](double x) { return 0.5 * (3.0 * x * x - 1.0); };
    for (std::size_t j = 0; j < m; ++j) {
        const double unscattered = std::exp(-beta * d / l.mu[j]);
        std::vector<double> h(m);
        double norm = 0.0;
        for (std::size_t i = 0; i < m; ++i) {
            h[i] = (0.5 + 0.25 * p2(l.mu[i]) * p2(l.mu[j])) * l.weight[i] / (2.0 * l.mu[i]);  // times the dmu weight
            norm += 2.0 * h[i];
        }
        const double a_j = (beta + mu_a) / l.mu[j];
        for (std::size_t i = 0; i < m; ++i) {
            const double share = h[i] / norm;  // into channel i, per hemisphere, per turn
            double back = 0.0, on = 0.0;
            if (beta > 0.0) {
                switch (turn) {
                    case RayleighTurn::sampled_depth:
                        back = share * beta / l.mu[j] * depth_integral(a_j + mu_a / l.mu[i], 0.0, d);
                        on = share * beta / l.mu[j] * depth_integral(a_j, mu_a / l.mu[i], d);
                        break;
                    case RayleighTurn::whole_crossing:
                        back = share * (1.0 - unscattered) * std::exp(-mu_a * d / l.mu[i]);
                        on = back;
                        break;
                    case RayleighTurn::no_absorption:
                        back = share * (1.0 - unscattered);
                        on = share * (1.0 - unscattered) * std::exp(-mu_a * d / l.mu[i]);
                        break;
                }
            }
            out.r(l.index[i], l.index[j]) = back;
            out.t(l.index[i], l.index[j]) = unscattered * through[i] + on;
            out.t_up(l.index[i], l.index[j]) = through[i];
        }
    }
    return out;
}

// The share of a fold-perturbed surface reflection that points out of the skin, for a beam at incidence theta: about
// the mirror direction at polar angle t (cosine c from the fold's distribution) and uniform azimuth phi, the ray
// leaves when cos(theta) c > sin(theta) sqrt(1 - c^2) cos(phi), i.e. for the share 1 - acos(x) / pi of azimuths,
// x = cos(theta) c / (sin(theta) sqrt(1 - c^2)). Midpoint rule over the sampling variable u. It depends on no
// wavelength: the last value is kept (per thread), so a spectrum at oblique incidence computes it once.
double fold_exit_share(double sigma, FoldFormula formula, double incidence_deg) {
    const double theta = incidence_deg * std::numbers::pi / 180.0;
    if (theta == 0.0) return 1.0;
    struct Last {
        double sigma = -1.0, incidence_deg = -1.0;
        FoldFormula formula = FoldFormula::biospec_2004;
        double share = 0.0;
    };
    thread_local Last last;
    if (last.sigma == sigma && last.formula == formula && last.incidence_deg == incidence_deg) return last.share;
    constexpr int points = 4096;
    double sum = 0.0;
    for (int k = 0; k < points; ++k) {
        const double u = (k + 0.5) / points;
        const double c = formula == FoldFormula::biospec_2004 ? skin_fold_sample_cos(sigma, u) : skin_fold_authors_sample_cos(sigma, u);
        const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
        const double denominator = std::sin(theta) * s;
        const double x = denominator > 0.0 ? std::cos(theta) * c / denominator : 2.0;
        sum += 1.0 - std::acos(std::clamp(x, -1.0, 1.0)) / std::numbers::pi;
    }
    last = {sigma, incidence_deg, formula, sum / points};
    return last.share;
}

// The Legendre moments of a measured profile at a wavelength: the walk samples it as the mixture of the two tabulated
// profiles around the wavelength (MeasuredProfile::mixture), whose moments are the mixture of theirs; each tabulated
// profile's are computed once per count.
std::vector<double> profile_moments(const MeasuredProfile& profile, double wavelength_nm, std::size_t count, AdCache& cache) {
    const auto tabulated = [&](std::size_t index) -> const std::vector<double>& {
        const auto table = profile.tabulated_inverse_table(index);
        for (const auto& m : cache.table_moments) {
            if (m->table == table && m->moments.size() == count) return m->moments;
        }
        const PhaseFunction phase{PhaseFunction::Kind::tabulated, table->mean_cos(), 0.0, 1.0, table};
        cache.table_moments.push_back(std::make_shared<const AdCache::TableMoments>(AdCache::TableMoments{table, legendre_moments(phase, count)}));
        return cache.table_moments.back()->moments;
    };
    const auto mixture = profile.mixture(wavelength_nm);
    auto moments = tabulated(mixture.lower);
    if (mixture.upper_weight > 0.0) {
        const auto& upper = tabulated(mixture.upper);
        for (std::size_t l = 0; l < count; ++l) moments[l] = (1.0 - mixture.upper_weight) * moments[l] + mixture.upper_weight * upper[l];
    }
    return moments;
}

void check_model(const ModelOptions& model) {
    if (model.swapped_upward_indices) {
        throw InputError("biospec-adding-doubling does not model model.swapped_upward_indices = true (the authors' code's upward interfaces); "
                         "the biospec walk does");
    }
    if (!model.redraw_reversals_in_stratum_corneum) {
        throw InputError("biospec-adding-doubling does not model model.redraw_reversals_in_stratum_corneum = false (the authors' code's "
                         "reversing SC crossings); the biospec walk does");
    }
}

}  // namespace

BiospecAdResult solve_biospec_adding_doubling(const LayerStack& stack, double wavelength_nm, double incidence_deg, const BiospecAdOptions& options,
                                              AdCache* cache) {
    check_incidence_deg(incidence_deg);
    check_model(stack.model);
    if (options.ad.channels < 4 || options.ad.channels > 256) {
        throw InputError("adding-doubling channels " + std::to_string(options.ad.channels) + " is outside [4, 256]");
    }
    if (stack.layers.empty()) throw InputError("material '" + stack.name + "' has no layers");
    AdCache own;
    auto& phases = cache ? *cache : own;
    const auto optics = stack.optics(wavelength_nm, OpticsScope{false, false});
    const bool reflector = has_reflector(stack.bottom);
    // Authors' behaviour 3 off: light leaves the bottom with no Fresnel test (an index-matched exit).
    const double below = reflector || stack.model.bottom_exit_fresnel ? stack.below_refractive_index : optics.back().refractive_index;
    AdStackShape shape{stack.above_refractive_index, {}, {}, reflector, below, {}};
    shape.bottom_reflectance = bottom_reflectance(stack, wavelength_nm);
    for (const auto& o : optics) {
        shape.layer_indices.push_back(o.refractive_index);
        shape.absorbing.push_back(o.mu_a_per_cm != 0.0);
    }
    const auto make_layer = [&](const AdChannels& channels, std::size_t k, double) {
        const auto& o = optics[k];
        switch (o.crossing) {
            case CrossingScattering::measured_stratum_corneum:
            case CrossingScattering::measured_epidermis: {
                const bool sc = o.crossing == CrossingScattering::measured_stratum_corneum;
                const double n = o.refractive_index;
                if (options.thin_layer_hg) {
                    const double g = sc ? options.thin_layer_hg->stratum_corneum_g(wavelength_nm) : options.thin_layer_hg->epidermis_g(wavelength_nm);
                    return perturbing_layer(channels, o, *cached_redistribution(channels, n, PhaseFunction::henyey_greenstein(g), phases));
                }
                const auto& profile = sc ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis();
                const auto moments = profile_moments(profile, wavelength_nm, redistribution_moment_count(channels, n), phases);
                return perturbing_layer(channels, o, *cached_redistribution(channels, n, moments, phases));
            }
            case CrossingScattering::henyey_greenstein:
                return perturbing_layer(channels, o, *cached_redistribution(channels, o.refractive_index, PhaseFunction::henyey_greenstein(o.hg_g), phases));
            case CrossingScattering::rayleigh_cosine:
            case CrossingScattering::cosine: return dermal_layer(channels, o, stack.model.rayleigh_turn);
        }
        return empty_layer(channels);
    };
    BiospecAdResult out{solve_stack(shape, AdIncidence{false, incidence_deg}, options.ad, make_layer), 0.0};
    // Step 1: the skin fold. Drop: one draw, lost when it points into the skin; resample: up to max_redraws draws.
    const double exits = fold_exit_share(stack.fold_aspect_ratio, stack.model.fold_formula, incidence_deg);
    const double kept = options.fold_into_skin == FoldIntoSkin::drop ? exits : 1.0 - std::pow(1.0 - exits, max_redraws);
    out.surface_absorbed = out.totals.specular_reflectance * (1.0 - kept);
    out.totals.specular_reflectance *= kept;
    return out;
}

SpectralResult solve_biospec_adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const BiospecAdOptions& options) {
    AdCache phases;
    auto result = adding_doubling_spectrum(stack, request, options.ad, "biospec-adding-doubling", [&](double nm, const AdOptions& ad) {
        auto o = options;
        o.ad = ad;
        const auto r = solve_biospec_adding_doubling(stack, nm, request.incidence_deg, o, &phases);
        return AdWavelength{r.totals, r.surface_absorbed};
    });
    result.settings["fold_into_skin"] = std::string(to_string(options.fold_into_skin));
    result.settings["fold_aspect_ratio"] = stack.fold_aspect_ratio;
    result.settings["thin_layer_phase"] = options.thin_layer_hg ? "henyey_greenstein (" + options.thin_layer_hg->source + ")" : std::string("measured");
    return result;
}

}  // namespace skinspec
