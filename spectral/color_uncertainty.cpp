#include "spectral/color_uncertainty.hpp"

#include <array>
#include <cmath>

#include "spectral/ciede2000.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// d Lab / d XYZ (CIE 015:2018 Eq. 8.1-8.3): f'(t) = t^(-2/3) / 3 above (6/29)^3, 1 / (3 (6/29)^2) below.
Matrix3 lab_jacobian(const XYZ& xyz, const XYZ& white) {
    constexpr double delta = 6.0 / 29.0;
    const auto df = [](double t) {
        return t > delta * delta * delta ? 1.0 / (3.0 * std::cbrt(t * t)) : 1.0 / (3.0 * delta * delta);
    };
    const double fx = df(xyz.X / white.X) / white.X;
    const double fy = df(xyz.Y / white.Y) / white.Y;
    const double fz = df(xyz.Z / white.Z) / white.Z;
    return {{{0.0, 116.0 * fy, 0.0}, {500.0 * fx, -500.0 * fy, 0.0}, {0.0, 200.0 * fy, -200.0 * fz}}};
}

// G with dE00^2(lab, lab + d) ~ d^T G d: half the Hessian at d = 0, by central differences (step h in Lab).
Matrix3 ciede2000_metric(const Lab& lab) {
    constexpr double h = 1e-3;
    const auto f = [&](const std::array<double, 3>& d) {
        const double e = ciede2000(lab, Lab{lab.L + d[0], lab.a + d[1], lab.b + d[2]});
        return e * e;
    };
    Matrix3 g{};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            std::array<double, 3> pp{}, pm{}, mp{}, mm{};
            pp[i] += h; pp[j] += h;
            pm[i] += h; pm[j] -= h;
            mp[i] -= h; mp[j] += h;
            mm[i] -= h; mm[j] -= h;
            g[i][j] = (f(pp) - f(pm) - f(mp) + f(mm)) / (8.0 * h * h);
        }
    }
    return g;
}

}  // namespace

std::vector<double> ciede2000_sensitivities(const TristimulusWeights& weights, std::span<const double> samples) {
    const XYZ xyz = weights.integrate(samples);
    const Matrix3 j = lab_jacobian(xyz, weights.white());
    const Matrix3 g = ciede2000_metric(xyz_to_lab(xyz, weights.white()));
    // M = J^T G J (3x3 in XYZ), then a_i = w_i^T M w_i.
    Matrix3 gj{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) gj[r][c] += g[r][k] * j[k][c];
    Matrix3 m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) m[r][c] += j[k][r] * gj[k][c];
    std::vector<double> a(weights.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto w = weights.weights(i);
        double v = 0.0;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) v += w[r] * m[r][c] * w[c];
        a[i] = std::max(v, 0.0);
    }
    return a;
}

double ciede2000_uncertainty(const TristimulusWeights& weights, std::span<const double> samples,
                             std::span<const double> standard_errors) {
    if (standard_errors.size() != samples.size()) {
        throw InputError("colour uncertainty: " + std::to_string(standard_errors.size()) + " standard errors for " +
                         std::to_string(samples.size()) + " samples");
    }
    const auto a = ciede2000_sensitivities(weights, samples);
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += a[i] * standard_errors[i] * standard_errors[i];
    return std::sqrt(sum);
}

}  // namespace skinspec
