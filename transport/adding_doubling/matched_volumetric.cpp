#include "transport/adding_doubling/matched_volumetric.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "materials/measured_profile.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"

namespace skinspec {
namespace {

bool is_dermal(CrossingScattering c) { return c == CrossingScattering::rayleigh_cosine || c == CrossingScattering::cosine; }

// The dermal factor's search: ln(scale) on a grid of factors 1/64 .. 64, then bisection of the bracket to 1e-7 in R.
constexpr int grid_lowest = -6, grid_highest = 6;  // powers of 2, stepped by 2
constexpr double reflectance_tolerance = 1e-7;
constexpr int max_refinements = 60;
constexpr int golden_steps = 30;
// The thin layers' mu_s d may move from 1 by up to a factor 4 where the dermis alone cannot match, located to 2^-10 in ln.
constexpr double max_log_thin_change = 2.0 * std::numbers::ln2;
constexpr int thin_refinements = 10;

struct DermalMatch {
    double log_scale = 0.0;
    double miss = 0.0;  // 0 where a factor reaches the target, else R_d - target at the closest factor
};

// The largest grid interval where R_d crosses the target upward (R_d grows with the dermal scattering there; below it,
// thinning the dermis can also brighten: more light reaches the reflector), refined by bisection; without one, the
// factor that comes closest (golden section about the closest grid point), stopped early if it reaches the target.
// A root of `miss` between `a` and `b`, where it has opposite signs, by bisection to reflectance_tolerance.
template <class Miss>
double bisect(const Miss& miss, double a, double b) {
    const bool rising = miss(b) > miss(a);
    double mid = 0.5 * (a + b);
    for (int i = 0; i < max_refinements; ++i) {
        mid = 0.5 * (a + b);
        const double m = miss(mid);
        if (std::abs(m) < reflectance_tolerance) break;
        ((m < 0.0) == rising ? a : b) = mid;
    }
    return mid;
}

// The largest grid interval where R_d crosses the target upward (R_d grows with the dermal scattering there; below it,
// thinning the dermis can also brighten: more light reaches the reflector), refined by bisection; without one, the
// factor that comes closest (golden section about the closest grid point; a crossing found on the way is refined).
template <class Miss>
DermalMatch match_dermis(const Miss& miss) {
    DermalMatch best{grid_lowest * std::numbers::ln2, miss(grid_lowest * std::numbers::ln2)};
    double previous_log = best.log_scale, previous = best.miss;
    std::optional<std::pair<double, double>> bracket;
    for (int k = grid_lowest + 2; k <= grid_highest; k += 2) {
        const double log_scale = k * std::numbers::ln2, m = miss(log_scale);
        if (previous < 0.0 && m >= 0.0) bracket = {previous_log, log_scale};
        if (std::abs(m) < std::abs(best.miss)) best = {log_scale, m};
        previous_log = log_scale;
        previous = m;
    }
    if (bracket) return {bisect(miss, bracket->first, bracket->second), 0.0};
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    const double closest = best.log_scale;
    const bool above = best.miss > 0.0;
    double a = closest - 2.0 * std::numbers::ln2, b = closest + 2.0 * std::numbers::ln2;
    for (int i = 0; i < golden_steps; ++i) {
        const double c = b - phi * (b - a), d = a + phi * (b - a);
        const double fc = miss(c), fd = miss(d);
        if ((fc > 0.0) != above) return {bisect(miss, closest, c), 0.0};
        if ((fd > 0.0) != above) return {bisect(miss, closest, d), 0.0};
        for (const auto& [x, f] : {std::pair{c, fc}, std::pair{d, fd}}) {
            if (std::abs(f) < std::abs(best.miss)) best = {x, f};
        }
        if (std::abs(fc) < std::abs(fd)) b = d;
        else a = c;
    }
    return best;
}

}  // namespace

MatchedVolumetric match_volumetric_to_biospec(const LayerStack& stack, const RteStack& tables, double wavelength_nm) {
    MatchedVolumetric out{tables, 1.0, 0.0};
    std::vector<std::size_t> dermal;
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        const auto crossing = crossing_in_effect(stack.layers[k], stack.model);
        auto& layer = out.stack.layers[k];
        if (is_dermal(crossing)) {
            dermal.push_back(k);
            continue;
        }
        // One deflection per normal crossing by the crossing's own redistribution (biospec-model.md, step 2).
        layer.mu_s_per_cm = 1.0 / layer.thickness_cm;
        if (crossing == CrossingScattering::henyey_greenstein) {
            layer.phase = PhaseFunction::henyey_greenstein(stack.layers[k].hg_g);
        } else {
            const auto& profile = crossing == CrossingScattering::measured_stratum_corneum ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis();
            const auto table = profile.shared_inverse_table(wavelength_nm);
            layer.phase = PhaseFunction{PhaseFunction::Kind::tabulated, table->mean_cos(), 0.0, 1.0, table};
        }
    }
    if (dermal.empty()) {
        throw InputError("model.volumetric_matched_to_biospec = true needs a dermal layer (scattering = rayleigh_cosine or cosine) to match; '" +
                         stack.name + "' has none");
    }
    AdCache cache;
    const AdOptions ad{matched_volumetric_channels, false};
    double target = 0.0;
    try {
        target = solve_biospec_adding_doubling(stack, wavelength_nm, 0.0, BiospecAdOptions{ad, FoldIntoSkin::drop, std::nullopt}, &cache).totals.diffuse_reflectance;
    } catch (const InputError& e) {
        throw InputError(std::string("model.volumetric_matched_to_biospec = true matches biospec-adding-doubling, which refuses this material: ") + e.what());
    }
    const auto derived = [&](double log_thin, double log_dermal) {
        auto s = out.stack;
        for (std::size_t k = 0; k < s.layers.size(); ++k) {
            const bool is_thin = std::find(dermal.begin(), dermal.end(), k) == dermal.end();
            s.layers[k].mu_s_per_cm = is_thin ? s.layers[k].mu_s_per_cm * std::exp(log_thin) : tables.layers[k].mu_s_per_cm * std::exp(log_dermal);
        }
        return s;
    };
    const auto miss = [&](double log_thin, double log_dermal) {
        return solve_adding_doubling(derived(log_thin, log_dermal), AdIncidence{}, ad, &cache).diffuse_reflectance - target;
    };
    auto best = match_dermis([&](double log_dermal) { return miss(0.0, log_dermal); });
    double log_thin = 0.0;
    if (best.miss != 0.0) {
        // No dermal factor reaches R: the thin layers scatter more (R too high: longer paths through the melanin) or
        // less, by the least change that lets one (bisection on ln u; continuous where the match starts to need it).
        const double far = (best.miss > 0.0 ? 1.0 : -1.0) * max_log_thin_change;
        auto at_far = match_dermis([&](double log_dermal) { return miss(far, log_dermal); });
        if (at_far.miss != 0.0) {
            log_thin = far;
            best = at_far;
        } else {
            double reached = far, not_reached = 0.0;
            for (int i = 0; i < thin_refinements; ++i) {
                const double mid = 0.5 * (reached + not_reached);
                const auto m = match_dermis([&](double log_dermal) { return miss(mid, log_dermal); });
                if (m.miss == 0.0) {
                    reached = mid;
                    at_far = m;
                } else {
                    not_reached = mid;
                }
            }
            log_thin = reached;
            best = at_far;
        }
    }
    out.stack = derived(log_thin, best.log_scale);
    out.thin_scale = std::exp(log_thin);
    out.dermal_scale = std::exp(best.log_scale);
    out.residual = std::abs(best.miss);
    return out;
}

}  // namespace skinspec
