#include "inverse/gaussian_sum/gaussian_sum_fit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <Eigen/Dense>
#include <nlopt.hpp>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

double gaussian_2d(double variance_mm2, double r_mm) {
    return std::exp(-r_mm * r_mm / (2.0 * variance_mm2)) / (2.0 * std::numbers::pi * variance_mm2);
}

std::vector<double> non_negative_least_squares(const std::vector<double>& a_values, std::size_t rows, std::size_t cols,
                                               const std::vector<double>& b_values) {
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> a(a_values.data(), rows, cols);
    const Eigen::Map<const Eigen::VectorXd> b(b_values.data(), rows);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(cols);
    std::vector<bool> passive(cols, false);
    const double tolerance = 1e-12 * std::max(1.0, (a.transpose() * b).cwiseAbs().maxCoeff());
    // Lawson & Hanson (1974) algorithm NNLS, ch. 23: move the variable with the largest gradient into the
    // passive set, solve unconstrained there, step back to feasibility when a passive variable would go negative.
    for (std::size_t outer = 0; outer < 3 * cols + 10; ++outer) {
        const Eigen::VectorXd w = a.transpose() * (b - a * x);
        std::size_t best = cols;
        for (std::size_t j = 0; j < cols; ++j) {
            if (!passive[j] && w[j] > tolerance && (best == cols || w[j] > w[best])) best = j;
        }
        if (best == cols) break;
        passive[best] = true;
        for (std::size_t inner = 0; inner < 3 * cols + 10; ++inner) {
            std::vector<Eigen::Index> set;
            for (std::size_t j = 0; j < cols; ++j) {
                if (passive[j]) set.push_back(static_cast<Eigen::Index>(j));
            }
            Eigen::MatrixXd sub(rows, set.size());
            for (std::size_t k = 0; k < set.size(); ++k) sub.col(k) = a.col(set[k]);
            const Eigen::VectorXd z_set = sub.colPivHouseholderQr().solve(b);
            Eigen::VectorXd z = Eigen::VectorXd::Zero(cols);
            for (std::size_t k = 0; k < set.size(); ++k) z[set[k]] = z_set[k];
            bool feasible = true;
            for (const auto j : set) feasible = feasible && z[j] > 0.0;
            if (feasible) {
                x = z;
                break;
            }
            double alpha = 1.0;
            for (const auto j : set) {
                if (z[j] <= 0.0) alpha = std::min(alpha, x[j] / (x[j] - z[j]));
            }
            x += alpha * (z - x);
            for (const auto j : set) {
                if (x[j] <= tolerance * 1e-6) {
                    x[j] = 0.0;
                    passive[static_cast<std::size_t>(j)] = false;
                }
            }
        }
    }
    return {x.data(), x.data() + cols};
}

void check_gaussian_count(std::size_t gaussians) {
    if (gaussians < 1 || gaussians > 12) throw InputError("--gaussians " + std::to_string(gaussians) + " is outside [1, 12]");
}

namespace {

void check_request(const GaussianSumRequest& request) {
    const auto& v = request.variances_mm2;
    if (!v.empty() && v.size() != request.gaussians) {
        throw InputError("Gaussian fit: " + std::to_string(v.size()) + " variances given for " + std::to_string(request.gaussians) + " Gaussians");
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!(std::isfinite(v[i]) && v[i] > 0.0) || (i > 0 && !(v[i] > v[i - 1]))) {
            throw InputError("Gaussian fit: given variance " + format_number(v[i]) + " mm^2 is not positive, finite and above the one before");
        }
    }
    const auto& r = request.radii_mm;
    check_gaussian_count(request.gaussians);
    if (r.size() < 8) throw InputError("--radii: " + std::to_string(r.size()) + " radii are too few for a Gaussian fit (at least 8)");
    if (!(r.front() >= 0.0)) throw InputError("--radii: the first radius " + format_number(r.front()) + " mm is outside [0, inf)");
    for (std::size_t i = 1; i < r.size(); ++i) {
        if (!(r[i] > r[i - 1]) || !std::isfinite(r[i])) {
            throw InputError("--radii: radius " + format_number(r[i]) + " mm does not increase from " + format_number(r[i - 1]) + " mm");
        }
    }
    if (request.profiles_per_mm2.empty()) throw InputError("Gaussian fit: no profile to fit");
    for (std::size_t c = 0; c < request.profiles_per_mm2.size(); ++c) {
        const auto& p = request.profiles_per_mm2[c];
        if (p.size() != r.size()) {
            throw InputError("Gaussian fit: profile " + std::to_string(c + 1) + " has " + std::to_string(p.size()) + " values for " +
                             std::to_string(r.size()) + " radii");
        }
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (!std::isfinite(p[i])) throw InputError("Gaussian fit: profile " + std::to_string(c + 1) + " at " + format_number(r[i]) + " mm is not finite");
        }
        if (std::all_of(p.begin(), p.end(), [](double v) { return v == 0.0; })) {
            throw InputError("Gaussian fit: profile " + std::to_string(c + 1) + " is zero everywhere (nothing to fit)");
        }
    }
    const auto& t = request.total_reflectance;
    if (!t.empty() && t.size() != request.profiles_per_mm2.size()) {
        throw InputError("Gaussian fit: " + std::to_string(t.size()) + " totals for " + std::to_string(request.profiles_per_mm2.size()) + " profiles");
    }
    for (std::size_t c = 0; c < t.size(); ++c) {
        if (!(t[c] > 0.0) || !std::isfinite(t[c])) {
            throw InputError("Gaussian fit: total reflectance of profile " + std::to_string(c + 1) + " = " + format_number(t[c]) + " is outside (0, inf)");
        }
    }
}

struct Problem {
    const GaussianSumRequest& request;
    std::vector<double> quadrature;  // trapezoid weights of int f(r) r dr
    std::vector<double> norms;       // int R_c^2 r dr
    std::size_t evaluations = 0;

    // Weights per channel for these variances, and the relative errors.
    std::tuple<std::vector<std::vector<double>>, std::vector<double>, double> solve(const std::vector<double>& variances) const {
        const auto& r = request.radii_mm;
        const std::size_t n = r.size(), m = variances.size();
        const bool totals = !request.total_reflectance.empty();
        const std::size_t rows = n + (totals ? 1 : 0);
        std::vector<double> a(rows * m);
        for (std::size_t k = 0; k < n; ++k) {
            for (std::size_t i = 0; i < m; ++i) a[k * m + i] = std::sqrt(quadrature[k]) * gaussian_2d(variances[i], r[k]);
        }
        std::vector<std::vector<double>> weights;
        std::vector<double> errors;
        double objective = 0.0;
        for (std::size_t c = 0; c < request.profiles_per_mm2.size(); ++c) {
            std::vector<double> b(rows);
            for (std::size_t k = 0; k < n; ++k) b[k] = std::sqrt(quadrature[k]) * request.profiles_per_mm2[c][k];
            // The total as one more row: sqrt(norm) (sum_i w_i / T - 1), in the profile's relative units.
            if (totals) {
                const double row = std::sqrt(norms[c]) / request.total_reflectance[c];
                for (std::size_t i = 0; i < m; ++i) a[n * m + i] = row;
                b[n] = std::sqrt(norms[c]);
            }
            auto w = non_negative_least_squares(a, rows, m, b);
            double residual = 0.0, total = 0.0;
            for (std::size_t k = 0; k < n; ++k) {
                double fit = 0.0;
                for (std::size_t i = 0; i < m; ++i) fit += a[k * m + i] * w[i];
                residual += (b[k] - fit) * (b[k] - fit);
            }
            for (const double wi : w) total += wi;
            errors.push_back(std::sqrt(residual / norms[c]));
            objective += residual / norms[c];
            if (totals) objective += (total / request.total_reflectance[c] - 1.0) * (total / request.total_reflectance[c] - 1.0);
            weights.push_back(std::move(w));
        }
        return {weights, errors, objective};
    }
    double objective(const std::vector<double>& log_variances) {
        ++evaluations;
        std::vector<double> v;
        for (const double x : log_variances) v.push_back(std::exp(x));
        return std::get<2>(solve(v));
    }
};

// The variances minimising the objective: log-variances searched by BOBYQA, the weights solved at each point.
std::vector<double> fitted_variances(Problem& problem) {
    const auto& r = problem.request.radii_mm;
    const std::size_t n = r.size(), m = problem.request.gaussians;
    // Variances between a quarter of the finest radial step and the square of the largest radius: narrower
    // Gaussians fall between the samples, wider ones are flat over the profile.
    double finest = r[1] - r[0];
    for (std::size_t k = 1; k + 1 < n; ++k) finest = std::min(finest, r[k + 1] - r[k]);
    const double lo = std::log(0.0625 * finest * finest), hi = std::log(r.back() * r.back());
    // Start: log-spaced from (2 steps)^2 to (largest radius / 3)^2, as d'Eon's skin variances spread (Table 14-1).
    const double start_lo = std::min(hi, std::log(4.0 * finest * finest)), start_hi = std::max(start_lo, std::log(r.back() * r.back() / 9.0));
    std::vector<double> x(m), lower(m, lo), upper(m, hi);
    for (std::size_t i = 0; i < m; ++i) x[i] = m == 1 ? 0.5 * (start_lo + start_hi) : start_lo + (start_hi - start_lo) * i / (m - 1.0);
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(m));
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_initial_step(std::vector<double>(m, 0.5));
    opt.set_xtol_abs(1e-6);
    opt.set_ftol_rel(1e-10);
    opt.set_maxeval(static_cast<int>(400 * m));
    opt.set_min_objective(
        [](const std::vector<double>& v, std::vector<double>&, void* p) { return static_cast<Problem*>(p)->objective(v); }, &problem);
    double value = 0.0;
    try {
        opt.optimize(x, value);
    } catch (const nlopt::roundoff_limited&) {
        // x holds the best point found.
    }
    std::sort(x.begin(), x.end());
    std::vector<double> variances;
    for (const double v : x) variances.push_back(std::exp(v));
    return variances;
}

}  // namespace

GaussianSumFit fit_gaussian_sum(const GaussianSumRequest& request) {
    check_request(request);
    const auto& r = request.radii_mm;
    const std::size_t n = r.size();
    Problem problem{request, std::vector<double>(n, 0.0), {}};
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double h = r[k + 1] - r[k];
        problem.quadrature[k] += 0.5 * h * r[k];
        problem.quadrature[k + 1] += 0.5 * h * r[k + 1];
    }
    // At r = 0 the area weight vanishes; a sliver keeps the peak in the fit (the disc of radius h/4 around it).
    problem.quadrature[0] = std::max(problem.quadrature[0], 0.03125 * (r[1] - r[0]) * (r[1] - r[0]));
    GaussianSumFit fit;
    for (const auto& p : request.profiles_per_mm2) {
        double norm = 0.0, total = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
            norm += problem.quadrature[k] * p[k] * p[k];
            total += 2.0 * std::numbers::pi * problem.quadrature[k] * p[k];
        }
        problem.norms.push_back(norm);
        fit.profile_total.push_back(total);
    }

    if (request.variances_mm2.empty()) {
        fit.variances_mm2 = fitted_variances(problem);
        fit.evaluations = problem.evaluations;
    } else {
        fit.variances_mm2 = request.variances_mm2;
    }
    auto solved = problem.solve(fit.variances_mm2);
    fit.weights = std::move(std::get<0>(solved));
    fit.relative_l2_error = std::move(std::get<1>(solved));
    for (const auto& w : fit.weights) {
        double total = 0.0;
        for (const double wi : w) total += wi;
        fit.fitted_total.push_back(total);
    }
    return fit;
}

}  // namespace skinspec
