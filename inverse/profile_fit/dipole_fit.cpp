#include "inverse/profile_fit/dipole_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlopt.hpp>

#include "transport/diffusion/dipole.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

std::vector<double> values_of(const ParameterGrid& g, const char* name) {
    if (!(std::isfinite(g.first) && std::isfinite(g.last) && g.last >= g.first && g.step > 0.0 && g.first >= 0.0)) {
        throw InputError(fmt::format("{} grid {:g}:{:g}:{:g} is not a range FIRST:LAST:STEP with 0 <= FIRST <= LAST and STEP > 0",
                                     name, g.first, g.last, g.step));
    }
    // The count first (a tiny STEP must not run away); values never pass LAST (the refinement box ends there).
    const double intervals = std::floor((g.last - g.first) / g.step * (1.0 + 1e-12));
    if (!(intervals < 1'000'000.0)) throw InputError(fmt::format("{} grid {:g}:{:g}:{:g} has more than 1,000,000 values", name, g.first, g.last, g.step));
    std::vector<double> out;
    for (int i = 0; i <= static_cast<int>(intervals); ++i) out.push_back(std::min(g.first + i * g.step, g.last));
    return out;
}

}  // namespace

double absorption_ratio_for_total(double total, double eta) {
    const auto rd = [eta](double albedo) { return Dipole({albedo, 1.0 - albedo, eta}).total_reflectance(); };
    const double top = rd(1.0);
    if (!(total > 0.0 && total < top)) {
        throw InputError(fmt::format("total diffuse reflectance = {} is outside (0, {:.6g}) (the dipole's range at eta = {:g})",
                                     format_number(total), top, eta));
    }
    double lo = 0.0, hi = 1.0;  // R_d increases with the reduced albedo
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        (rd(mid) < total ? lo : hi) = mid;
    }
    const double albedo = 0.5 * (lo + hi);
    return (1.0 - albedo) / albedo;
}

namespace {

// Gauss-Newton standard errors of a least-squares fit (Press et al., Numerical Recipes, 3rd ed., Sec. 15.5):
// Cov = s^2 (J^T J)^-1, s^2 = residual / (n - p), J by central differences of the dipole's R(d) at the result.
void state_standard_errors(DipoleFitResult& result, const std::vector<double>& d, double eta, std::optional<double> ratio) {
    const std::size_t p = ratio ? 1 : 2;
    if (d.size() <= p) return;
    const auto model = [&](double sigma_s, double sigma_a, double distance) { return Dipole({sigma_s, sigma_a, eta}).radial_reflectance(distance); };
    const double s = result.reduced_scattering_per_mm, a = result.absorption_per_mm;
    const double hs = 1e-4 * std::max(s, 1e-6), ha = 1e-4 * std::max(a, 1e-6);
    double jss = 0.0, jsa = 0.0, jaa = 0.0;
    for (const double distance : d) {
        const double ds = ratio ? (model(s + hs, *ratio * (s + hs), distance) - model(s - hs, *ratio * (s - hs), distance)) / (2.0 * hs)
                                : (model(s + hs, a, distance) - model(s - hs, a, distance)) / (2.0 * hs);
        const double da = ratio ? 0.0 : (model(s, a + ha, distance) - model(s, std::max(0.0, a - ha), distance)) / (a >= ha ? 2.0 * ha : ha + a);
        jss += ds * ds;
        jsa += ds * da;
        jaa += da * da;
    }
    const double scatter = result.residual / static_cast<double>(d.size() - p);
    if (ratio) {
        if (!(jss > 0.0)) return;
        result.reduced_scattering_stderr_per_mm = std::sqrt(scatter / jss);
        result.absorption_stderr_per_mm = *ratio * result.reduced_scattering_stderr_per_mm;
        return;
    }
    const double det = jss * jaa - jsa * jsa;
    if (!(det > 1e-12 * jss * jaa)) return;  // singular: the bins do not tell the two apart
    result.reduced_scattering_stderr_per_mm = std::sqrt(scatter * jaa / det);
    result.absorption_stderr_per_mm = std::sqrt(scatter * jss / det);
}

DipoleFitResult fit_on_grid_and_refine(std::span<const double> distances_mm, std::span<const double> profile, std::span<const char> use,
                           const DipoleFitOptions& options) {
    if (distances_mm.size() != profile.size() || use.size() != profile.size()) throw InputError("dipole fit: distances and profile differ in size");
    std::vector<double> d, target;
    for (std::size_t i = 0; i < profile.size(); ++i) {
        if (!use[i]) continue;
        if (!std::isfinite(distances_mm[i]) || !std::isfinite(profile[i])) {
            throw InputError(fmt::format("dipole fit: bin {} (d = {} mm) is not a finite number", i, format_number(distances_mm[i])));
        }
        d.push_back(distances_mm[i]);
        target.push_back(profile[i]);
    }
    if (d.empty()) throw InputError("dipole fit: no usable profile sample");
    if (!(options.eta > 0.2 && options.eta < 5.0)) throw InputError("eta = " + format_number(options.eta) + " is outside (0.2, 5)");
    const auto ratio = options.total_diffuse_reflectance ? std::optional(absorption_ratio_for_total(*options.total_diffuse_reflectance, options.eta))
                                                         : std::nullopt;
    DipoleFitResult result;
    // Eq. 25.
    const auto residual = [&](double sigma_s, double sigma_a) {
        ++result.evaluations;
        if (sigma_s + sigma_a <= 0.0) return std::numeric_limits<double>::max();
        const Dipole dipole({sigma_s, sigma_a, options.eta});
        double sum = 0.0;
        for (std::size_t i = 0; i < d.size(); ++i) {
            const double e = target[i] - dipole.radial_reflectance(d[i]);
            sum += e * e;
        }
        return sum;
    };
    const auto absorption_of = [&](double sigma_s, double sigma_a) { return ratio ? *ratio * sigma_s : sigma_a; };
    const auto s_values = values_of(options.reduced_scattering_per_mm, "sigma_s'");
    const auto a_values = ratio ? std::vector<double>{0.0} : values_of(options.absorption_per_mm, "sigma_a");
    double best = std::numeric_limits<double>::max();
    for (const double s : s_values) {
        for (const double a : a_values) {
            const double e = residual(s, absorption_of(s, a));
            if (e < best) {
                best = e;
                result.grid_reduced_scattering_per_mm = s;
                result.grid_absorption_per_mm = absorption_of(s, a);
            }
        }
    }
    result.grid_residual = best;
    result.reduced_scattering_per_mm = result.grid_reduced_scattering_per_mm;
    result.absorption_per_mm = result.grid_absorption_per_mm;
    result.residual = best;
    if (!options.refine) {
        state_standard_errors(result, d, options.eta, ratio);
        return result;
    }

    // Local refinement in the grid's box, scaled so both parameters move on comparable steps.
    const auto& gs = options.reduced_scattering_per_mm;
    const auto& ga = options.absorption_per_mm;
    const unsigned dims = ratio ? 1u : 2u;
    nlopt::opt opt(nlopt::LN_BOBYQA, dims);
    std::vector<double> lower{std::max(gs.first, 1e-9)}, upper{gs.last}, x{result.reduced_scattering_per_mm}, step{gs.step};
    if (!ratio) {
        lower.push_back(ga.first);
        upper.push_back(ga.last);
        x.push_back(result.absorption_per_mm);
        step.push_back(ga.step);
    }
    if (upper[0] <= lower[0] || (!ratio && upper[1] <= lower[1])) {
        state_standard_errors(result, d, options.eta, ratio);
        return result;
    }
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_initial_step(step);
    opt.set_xtol_rel(1e-12);
    opt.set_ftol_rel(1e-15);
    opt.set_maxeval(20000);
    struct Data {
        decltype(residual)* f;
        decltype(absorption_of)* a;
    } data{&residual, &absorption_of};
    opt.set_min_objective(
        [](const std::vector<double>& v, std::vector<double>&, void* p) {
            const auto& dd = *static_cast<Data*>(p);
            return (*dd.f)(v[0], (*dd.a)(v[0], v.size() > 1 ? v[1] : 0.0));
        },
        &data);
    double value = 0.0;
    try {
        opt.optimize(x, value);
    } catch (const nlopt::roundoff_limited&) {
        value = residual(x[0], absorption_of(x[0], x.size() > 1 ? x[1] : 0.0));
    }
    if (value < result.residual) {
        result.reduced_scattering_per_mm = x[0];
        result.absorption_per_mm = absorption_of(x[0], x.size() > 1 ? x[1] : 0.0);
        result.residual = value;
    }
    state_standard_errors(result, d, options.eta, ratio);
    return result;
}

}  // namespace

DipoleFitResult fit_dipole(std::span<const double> distances_mm, std::span<const double> profile_per_mm2, std::span<const char> use,
                           const DipoleFitOptions& options) {
    auto result = fit_on_grid_and_refine(distances_mm, profile_per_mm2, use, options);
    constexpr std::string_view beyond = ": the best fit may lie beyond it (widen the search grid: --grid-scattering, --grid-absorption or their keywords), or the profile does not constrain it";
    const auto edge = [&](const char* name, double value, const ParameterGrid& grid) {
        const double tolerance = 1e-6 * std::max(grid.step, 1e-12);
        if (std::abs(value - grid.first) <= tolerance && grid.first == 0.0) {
            // Nothing below 0: a coefficient there is the physical bound, not a search range to widen.
            result.at_bounds.push_back(fmt::format("{} = 0 /mm, the physical lower bound (the profile shows no {} the fit can resolve)", name,
                                                   std::string_view(name) == "sigma_a" ? "absorption" : "scattering"));
        } else if (std::abs(value - grid.first) <= tolerance) {
            result.at_bounds.push_back(fmt::format("{} = {} /mm, the search's lower bound{}", name, format_number(value), beyond));
        }
        else if (std::abs(value - grid.last) <= tolerance) result.at_bounds.push_back(fmt::format("{} = {} /mm, the search's upper bound{}", name, format_number(value), beyond));
    };
    edge("sigma_s'", result.reduced_scattering_per_mm, options.reduced_scattering_per_mm);
    if (!options.total_diffuse_reflectance) edge("sigma_a", result.absorption_per_mm, options.absorption_per_mm);
    return result;
}

}  // namespace skinspec
