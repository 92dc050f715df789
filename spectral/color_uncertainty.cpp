#include "spectral/color_uncertainty.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "spectral/ciede2000.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

// A B and A^T (3x3).
Matrix3 product(const Matrix3& a, const Matrix3& b) {
    Matrix3 out{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) out[r][c] += a[r][k] * b[k][c];
    return out;
}

Matrix3 transposed(const Matrix3& a) {
    Matrix3 out{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out[r][c] = a[c][r];
    return out;
}

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
    const Matrix3 m = product(transposed(j), product(g, j));
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

ColorUncertainty color_uncertainty(const TristimulusWeights& weights, std::span<const double> samples,
                                   std::span<const double> standard_errors, double stated_error) {
    if (standard_errors.size() != samples.size()) {
        throw InputError("colour uncertainty: " + std::to_string(standard_errors.size()) + " standard errors for " +
                         std::to_string(samples.size()) + " samples");
    }
    for (const double s : standard_errors) {
        if (!std::isfinite(s) || s < 0.0) throw InputError("colour uncertainty: a standard error of " + std::to_string(s) + " is outside [0, inf)");
    }
    if (!std::isfinite(stated_error) || stated_error < 0.0) {
        throw InputError("colour uncertainty: a stated error of " + std::to_string(stated_error) + " is outside [0, inf)");
    }
    ColorUncertainty out;
    std::array<double, 3> common{};
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const auto w = weights.weights(i);
        const double v = standard_errors[i] * standard_errors[i];
        for (int r = 0; r < 3; ++r) {
            common[r] += w[r];
            for (int c = 0; c < 3; ++c) out.xyz_covariance[r][c] += v * w[r] * w[c];
        }
    }
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out.xyz_covariance[r][c] += stated_error * stated_error * common[r] * common[c];
    const XYZ xyz = weights.integrate(samples);
    const Matrix3 j = lab_jacobian(xyz, weights.white());
    const Matrix3 lab_covariance = product(j, product(out.xyz_covariance, transposed(j)));
    // A variance that is 0 exactly (a grey spectrum shifted by a common error keeps a* = b* = 0) can round below it.
    out.lab = {std::sqrt(std::max(lab_covariance[0][0], 0.0)), std::sqrt(std::max(lab_covariance[1][1], 0.0)), std::sqrt(std::max(lab_covariance[2][2], 0.0))};
    // E[d^T G d] = trace(G Cov(Lab)).
    const Matrix3 g = ciede2000_metric(xyz_to_lab(xyz, weights.white()));
    double expected = 0.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) expected += g[r][c] * lab_covariance[c][r];
    out.delta_e2000 = std::sqrt(std::max(expected, 0.0));
    return out;
}

std::array<double, 3> rgb_uncertainty(const XYZ& xyz, const XYZ& white, const Matrix3& xyz_covariance, std::string_view space) {
    const auto& cm = ColorManagement::builtin();
    constexpr double h = 1e-3;
    Matrix3 j{};
    for (int k = 0; k < 3; ++k) {
        XYZ up = xyz, down = xyz;
        (k == 0 ? up.X : k == 1 ? up.Y : up.Z) += h;
        (k == 0 ? down.X : k == 1 ? down.Y : down.Z) -= h;
        const auto a = cm.from_xyz(up, white, space);
        const auto b = cm.from_xyz(down, white, space);
        for (int c = 0; c < 3; ++c) j[c][k] = (a[c] - b[c]) / (2.0 * h);
    }
    const Matrix3 covariance = product(j, product(xyz_covariance, transposed(j)));
    return {std::sqrt(std::max(covariance[0][0], 0.0)), std::sqrt(std::max(covariance[1][1], 0.0)), std::sqrt(std::max(covariance[2][2], 0.0))};
}

double ciede2000_uncertainty(const TristimulusWeights& weights, std::span<const double> samples,
                             std::span<const double> standard_errors) {
    return color_uncertainty(weights, samples, standard_errors).delta_e2000;
}

}  // namespace skinspec
