#include "transport/adding_doubling/matched_volumetric.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

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
// The thin layers' mu_s d may move from 1 by up to a factor 4 where the dermis alone cannot match.
constexpr double max_log_thin_change = 2.0 * std::numbers::ln2;
// The closest dermal factor where none reaches: bracketed by steps (in ln(scale)) growing away from a start, the
// closest grid point (a quarter of the grid's step first) or the last thin-layer change's closest factor (which moves
// little: 0.05 first), then located to 1e-3 in ln by Brent's method (R_d is flat there: its value then to ~1e-8).
constexpr double grid_bracket_step = 0.5 * std::numbers::ln2, tracking_bracket_step = 0.05;
constexpr double extremum_tolerance = 1e-3;

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

struct Extremum {
    double log_scale = 0.0;
    double value = 0.0;
};

// The least of `f` on [a, b], where `inner` lies inside and below both ends' values, located to `tolerance` (or the
// first point found at or below `enough`): Brent's method (Brent 1973, "Algorithms for Minimization without
// Derivatives", Ch. 5), successive parabolic interpolation through the three best points, a golden-section step
// wherever the parabola's step is not trusted. `f` is smooth here, so it converges superlinearly.
template <class F>
Extremum brent_minimum(const F& f, double a, double b, Extremum inner, double tolerance, double enough) {
    const double golden = 0.5 * (3.0 - std::sqrt(5.0));
    double x = inner.log_scale, w = x, v = x;
    double fx = inner.value, fw = fx, fv = fx;
    double step = 0.0, previous_step = 0.0;
    for (;;) {
        const double middle = 0.5 * (a + b);
        if (std::abs(x - middle) <= 2.0 * tolerance - 0.5 * (b - a)) break;
        bool parabolic = false;
        if (std::abs(previous_step) > tolerance) {
            const double r = (x - w) * (fx - fv);
            double q = (x - v) * (fx - fw);
            double p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if (q > 0.0) p = -p;
            q = std::abs(q);
            if (std::abs(p) < std::abs(0.5 * q * previous_step) && p > q * (a - x) && p < q * (b - x)) {
                previous_step = step;
                step = p / q;
                const double u = x + step;
                if (u - a < 2.0 * tolerance || b - u < 2.0 * tolerance) step = x < middle ? tolerance : -tolerance;
                parabolic = true;
            }
        }
        if (!parabolic) {
            previous_step = x < middle ? b - x : a - x;
            step = golden * previous_step;
        }
        const double u = x + (std::abs(step) >= tolerance ? step : (step > 0.0 ? tolerance : -tolerance));
        const double fu = f(u);
        if (fu <= enough) return {u, fu};
        if (fu <= fx) {
            (u < x ? b : a) = x;
            v = w;
            fv = fw;
            w = x;
            fw = fx;
            x = u;
            fx = fu;
        } else {
            (u < x ? a : b) = u;
            if (fu <= fw || w == x) {
                v = w;
                fv = fw;
                w = u;
                fw = fu;
            } else if (fu <= fv || v == x || v == w) {
                v = u;
                fv = fu;
            }
        }
    }
    return {x, fx};
}

// The least of `f` over ln(scale) within the dermal grid's range, starting at `start`: downhill by steps growing by
// the golden ratio until `f` rises (or the range ends, where the least is its end), then Brent's method in that bracket;
// the first point at or below `enough` ends it.
template <class F>
Extremum extremum_near(const F& f, double start, double first_step, double enough) {
    const double lowest = grid_lowest * std::numbers::ln2, highest = grid_highest * std::numbers::ln2;
    const double growth = 0.5 * (1.0 + std::sqrt(5.0));
    Extremum previous{start, f(start)};
    double step = start + first_step <= highest ? first_step : -first_step;
    Extremum current{start + step, f(start + step)};
    if (current.value <= enough) return current;
    if (current.value > previous.value) {
        std::swap(previous, current);
        step = -step;
    }
    for (;;) {
        const double next_scale = std::clamp(current.log_scale + step * growth, lowest, highest);
        if (next_scale == current.log_scale) return current;  // downhill to the range's end
        const Extremum next{next_scale, f(next_scale)};
        if (next.value <= enough) return next;
        if (next.value > current.value) {
            return brent_minimum(f, std::min(previous.log_scale, next.log_scale), std::max(previous.log_scale, next.log_scale), current, extremum_tolerance, enough);
        }
        step = next.log_scale - current.log_scale;
        previous = current;
        current = next;
    }
}

// The largest grid interval where R_d crosses the target upward (R_d grows with the dermal scattering there; below it,
// thinning the dermis can also brighten: more light reaches the reflector), refined; without one, the factor that
// comes closest, found from the closest grid point (a crossing found on the way is refined).
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
    const double side = best.miss > 0.0 ? 1.0 : -1.0;
    const auto closest = extremum_near([&](double log_scale) { return side * miss(log_scale); }, best.log_scale, grid_bracket_step, 0.0);
    if (closest.value > 0.0) return {closest.log_scale, side * closest.value};
    return {refine_root(miss, best.log_scale, best.miss, closest.log_scale, side * closest.value), 0.0};
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
        // One deflection per normal crossing by the crossing's own redistribution (Krishnaswamy & Baranoski 2004; docs/BIOSPEC.md, "One ray", step 2).
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
    const DermalMatch unmoved = best;
    const double side = unmoved.miss > 0.0 ? 1.0 : -1.0;  // R_d above the target at every dermal factor (or below)
    double log_thin = 0.0;
    // Where no dermal factor reaches R, the thin layers scatter more (R too high: longer paths through the melanin) or
    // less, by the least change that lets one. With `side` the sign of the unmoved miss, closest(t) = min over the
    // dermal factor of side (R_d - target) at thin change t is > 0 at t = 0 and <= 0 where a factor reaches; its root
    // t* (Illinois, to 1e-7 in R) is the least change, and there the closest dermal factor meets R_d exactly (the
    // tangent point): the description moves continuously with the wavelength into and through this regime. Returns
    // the change and its match (miss != 0 where even `far` does not reach).
    const auto move_thin = [&](double far) -> std::pair<double, DermalMatch> {
        const auto at_far = match_dermis([&](double log_dermal) { return miss(far, log_dermal); });
        if (at_far.miss != 0.0) return {far, at_far};
        Extremum last{unmoved.log_scale, 0.0};  // the closest dermal factor at the last change looked at
        const auto closest = [&](double log_thin_change) {
            last = extremum_near([&](double log_dermal) { return side * miss(log_thin_change, log_dermal); }, last.log_scale, tracking_bracket_step,
                                 -std::numeric_limits<double>::infinity());
            return last.value;
        };
        const double at_far_closest = closest(far);
        if (at_far_closest > 0.0) return {far, at_far};  // the root `far` reaches is on another branch of R_d
        const double change = refine_root(closest, 0.0, side * unmoved.miss, far, at_far_closest);  // its last look is at `change`
        return {change, {last.log_scale, std::abs(last.value) < reflectance_tolerance ? 0.0 : side * last.value}};
    };
    if (best.miss != 0.0) {
        // The expected direction first; the other where it does not reach (very heavily pigmented skin, where more
        // thin-layer scattering missed by more); else the closest of the three.
        const double expected = side * max_log_thin_change;
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
