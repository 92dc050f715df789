#include "studies/phase_study/hg_fit.hpp"

#include <cmath>
#include <numbers>

#include <nlopt.hpp>

#include "transport/henyey_greenstein.hpp"

namespace skinspec {
namespace {

// P(theta < t) for HG: 1 - CDF(cos t).
double hg_within(double g, double theta_deg) { return 1.0 - hg_cdf_cos(g, std::cos(theta_deg * std::numbers::pi / 180.0)); }

}  // namespace

std::vector<double> measured_bin_fractions(std::span<const double> c) {
    std::vector<double> f;
    for (std::size_t i = 1; i < c.size(); ++i) f.push_back(c[i] - c[i - 1]);
    return f;
}

std::vector<double> hg_bin_fractions(double g, std::span<const double> edges) {
    const double total = hg_within(g, edges.back());
    std::vector<double> f;
    for (std::size_t i = 1; i < edges.size(); ++i) f.push_back((hg_within(g, edges[i]) - hg_within(g, edges[i - 1])) / total);
    return f;
}

double rms_error(std::span<const double> measured, std::span<const double> model) {
    double sum = 0.0;
    for (std::size_t i = 0; i < measured.size(); ++i) sum += (measured[i] - model[i]) * (measured[i] - model[i]);
    return std::sqrt(sum / static_cast<double>(measured.size()));
}

HgFit fit_hg_rms(std::span<const double> cumulative, std::span<const double> edges) {
    const auto measured = measured_bin_fractions(cumulative);
    struct Context {
        std::vector<double> measured;
        std::vector<double> edges;
        int evaluations = 0;
    } context{measured, {edges.begin(), edges.end()}, 0};
    nlopt::opt optimiser(nlopt::LN_NELDERMEAD, 1);
    optimiser.set_lower_bounds(-0.999999);
    optimiser.set_upper_bounds(0.999999);
    optimiser.set_xtol_abs(1e-9);
    optimiser.set_initial_step(0.1);
    optimiser.set_min_objective(
        [](unsigned, const double* x, double*, void* data) {
            auto* c = static_cast<Context*>(data);
            ++c->evaluations;
            return rms_error(c->measured, hg_bin_fractions(x[0], c->edges));
        },
        &context);
    std::vector<double> x{0.5};
    double best = 0.0;
    optimiser.optimize(x, best);
    return {x[0], best, context.evaluations};
}

}  // namespace skinspec
