#include "transport/adding_doubling/gauss_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <Eigen/Dense>

namespace skinspec {
namespace {

// Legendre recurrence on [-1, 1]: alpha_k = 0, beta_k = k / sqrt(4 k^2 - 1).
double legendre_beta(std::size_t k) {
    const double kk = static_cast<double>(k);
    return kk / std::sqrt(4.0 * kk * kk - 1.0);
}

QuadratureRule from_jacobi(const Eigen::MatrixXd& jacobi, double a, double b) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
    const auto n = static_cast<std::size_t>(jacobi.rows());
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return solver.eigenvalues()(static_cast<Eigen::Index>(i)) < solver.eigenvalues()(static_cast<Eigen::Index>(j)); });
    QuadratureRule rule;
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    for (const auto i : order) {
        const auto ii = static_cast<Eigen::Index>(i);
        const double v0 = solver.eigenvectors()(0, ii);
        rule.nodes.push_back(mid + half * solver.eigenvalues()(ii));
        rule.weights.push_back(2.0 * v0 * v0 * half);
    }
    return rule;
}

Eigen::MatrixXd legendre_jacobi(std::size_t n) {
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (std::size_t k = 1; k < n; ++k) {
        const auto kk = static_cast<Eigen::Index>(k);
        j(kk, kk - 1) = j(kk - 1, kk) = legendre_beta(k);
    }
    return j;
}

}  // namespace

QuadratureRule gauss_legendre(std::size_t n, double a, double b) {
    if (n == 0) throw std::invalid_argument("gauss_legendre: no points");
    return from_jacobi(legendre_jacobi(n), a, b);
}

QuadratureRule gauss_radau(std::size_t n, double a, double b, double fixed) {
    if (n < 2) throw std::invalid_argument("gauss_radau: needs at least 2 points");
    const double end = fixed == a ? -1.0 : 1.0;  // the fixed node on [-1, 1]
    auto j = legendre_jacobi(n);
    // Golub 1973: solve (J_{n-1} - end I) d = beta_{n-1}^2 e_{n-1}; the new last diagonal entry is end + d_{n-1}.
    const auto m = static_cast<Eigen::Index>(n - 1);
    const Eigen::MatrixXd shifted = j.topLeftCorner(m, m) - end * Eigen::MatrixXd::Identity(m, m);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
    const double beta = legendre_beta(n - 1);
    rhs(m - 1) = beta * beta;
    const Eigen::VectorXd d = shifted.partialPivLu().solve(rhs);
    j(m, m) = end + d(m - 1);
    auto rule = from_jacobi(j, a, b);
    // The fixed node exactly (the eigenvalue carries rounding).
    if (end < 0.0) rule.nodes.front() = a;
    else rule.nodes.back() = b;
    return rule;
}

}  // namespace skinspec
