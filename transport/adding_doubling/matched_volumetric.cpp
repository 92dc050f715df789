#include "transport/adding_doubling/matched_volumetric.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "materials/measured_profile.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"

namespace skinspec {
namespace {

// The dermal factor's search: ln(scale) on a grid of factors 1/64 .. 64, then the bracket refined to 1e-7 in R.
constexpr int grid_lowest = -6, grid_highest = 6;  // powers of 2, stepped by 2
constexpr double reflectance_tolerance = 1e-7;
constexpr int max_refinements = 60;
// Golden-section steps where no factor reaches (the bracket shrinks to 0.618^15 = 2e-3 of its 4 ln 2: R_d is flat at
// its minimum, so the closest R_d is found to ~1e-6; 30 steps changed R by at most 5e-6 and took 1.6-1.9x the time).
constexpr int golden_steps = 15;
// The thin layers' mu_s d may move from 1 by up to a factor 4 where the dermis alone cannot match, located to 2 ln 2 / 2^8 in ln.
constexpr double max_log_thin_change = 2.0 * std::numbers::ln2;
constexpr int thin_refinements = 8;

struct DermalMatch {
    double log_scale = 0.0;
    double miss = 0.0;  // 0 where a factor reaches the target, else R_d - target at the closest factor
};

// A root of `miss` between `a` and `b`, where it has the opposite signs `fa` and `fb`, to reflectance_tolerance: the
// Illinois variant of regula falsi (Dowell & Jarratt 1971, BIT 11:168), superlinear and never leaving the bracket.
template <class Miss>
double refine_root(const Miss& miss, double a, double fa, double b, double fb) {
    int kept = 0;  // the end kept by the last two steps: -1 a, +1 b (its value is halved when kept twice)
    double c = a;
    for (int i = 0; i < max_refinements && b - a != 0.0; ++i) {
        c = (a * fb - b * fa) / (fb - fa);
        const double fc = miss(c);
        if (std::abs(fc) < reflectance_tolerance) break;
        if ((fc > 0.0) == (fb > 0.0)) {
            b = c;
            fb = fc;
            if (kept == -1) fa *= 0.5;
            kept = -1;
        } else {
            a = c;
            fa = fc;
            if (kept == 1) fb *= 0.5;
            kept = 1;
        }
    }
    return c;
}

// The largest grid interval where R_d crosses the target upward (R_d grows with the dermal scattering there; below it,
// thinning the dermis can also brighten: more light reaches the reflector), refined; without one, the
// factor that comes closest (golden section about the closest grid point; a crossing found on the way is refined).
template <class Miss>
DermalMatch match_dermis(const Miss& miss) {
    // The grid from the top down: the first upward crossing met is the largest, and the points below it are not needed.
    DermalMatch best{grid_highest * std::numbers::ln2, miss(grid_highest * std::numbers::ln2)};
    double upper_log = best.log_scale, upper = best.miss;
    for (int k = grid_highest - 2; k >= grid_lowest; k -= 2) {
        const double log_scale = k * std::numbers::ln2, m = miss(log_scale);
        if (m < 0.0 && upper >= 0.0) return {refine_root(miss, log_scale, m, upper_log, upper), 0.0};
        if (std::abs(m) <= std::abs(best.miss)) best = {log_scale, m};  // on a tie the lower factor, as found going up
        upper_log = log_scale;
        upper = m;
    }
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    const auto closest = best;
    const bool above = best.miss > 0.0;
    // Golden section (one new point per step) for the smallest |miss|; a point on the other side ends it with a root.
    DermalMatch crossed;
    const auto probe = [&](double x) -> std::optional<double> {
        const double f = miss(x);
        if ((f > 0.0) != above) {
            crossed = {x, f};
            return std::nullopt;
        }
        if (std::abs(f) < std::abs(best.miss)) best = {x, f};
        return std::abs(f);
    };
    double a = closest.log_scale - 2.0 * std::numbers::ln2, b = closest.log_scale + 2.0 * std::numbers::ln2;
    double c = b - phi * (b - a), d = a + phi * (b - a);
    auto fc = probe(c), fd = fc ? probe(d) : std::nullopt;
    for (int i = 0; i < golden_steps && fc && fd; ++i) {
        if (*fc < *fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - phi * (b - a);
            fc = probe(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + phi * (b - a);
            fd = probe(d);
        }
    }
    if (!fc || !fd) return {refine_root(miss, closest.log_scale, closest.miss, crossed.log_scale, crossed.miss), 0.0};
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
                         stack.name + "' has none (--set model.volumetric_matched_to_biospec=false solves the layers' own volumetric description)");
    }
    AdCache cache;
    const AdOptions ad{matched_volumetric_channels, false};
    double target = 0.0;
    try {
        target = solve_biospec_adding_doubling(stack, wavelength_nm, 0.0, BiospecAdOptions{ad, FoldIntoSkin::drop, std::nullopt}, &cache).totals.diffuse_reflectance;
    } catch (const InputError& e) {
        throw InputError(std::string("model.volumetric_matched_to_biospec = true matches biospec-adding-doubling, which refuses this material: ") + e.what() +
                         " (--set model.volumetric_matched_to_biospec=false solves the layers' own volumetric description)");
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
    // Where no dermal factor reaches R, the thin layers scatter more (R too high: longer paths through the melanin) or
    // less, by the least change that lets one: bisection on ln u toward `far` (continuous where the match starts to
    // need it). Returns the change and its match (miss != 0 where even `far` does not reach).
    const auto move_thin = [&](double far) -> std::pair<double, DermalMatch> {
        auto at_far = match_dermis([&](double log_dermal) { return miss(far, log_dermal); });
        if (at_far.miss != 0.0) return {far, at_far};
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
        return {reached, at_far};
    };
    if (best.miss != 0.0) {
        // The expected direction first; the other where it does not reach (very heavily pigmented skin, where more
        // thin-layer scattering missed by more); else the closest of the three.
        const double expected = (best.miss > 0.0 ? 1.0 : -1.0) * max_log_thin_change;
        for (const double far : {expected, -expected}) {
            const auto [moved, match] = move_thin(far);
            if (std::abs(match.miss) < std::abs(best.miss)) {
                log_thin = moved;
                best = match;
            }
            if (best.miss == 0.0) break;
        }
    }
    out.stack = derived(log_thin, best.log_scale);
    out.thin_scale = std::exp(log_thin);
    out.dermal_scale = std::exp(best.log_scale);
    out.residual = std::abs(best.miss);
    return out;
}

double derived_description_miss(const LayerStack& stack, const AdResult& derived, double wavelength_nm, double incidence_deg, bool specular,
                                const AdOptions& options, AdCache* cache) {
    const BiospecAdOptions exact{AdOptions{options.channels, false, options.cancel}, FoldIntoSkin::drop, std::nullopt};
    const auto biospec = solve_biospec_adding_doubling(stack, wavelength_nm, incidence_deg, exact, cache).totals;
    return derived.diffuse_reflectance - biospec.diffuse_reflectance + (specular ? derived.specular_reflectance - biospec.specular_reflectance : 0.0);
}

}  // namespace skinspec
