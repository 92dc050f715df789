#include "spectral/rgb_uplift.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "spectral/cie.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double first_nm = 360.0, span_nm = 470.0;  // the 360-830 nm the fit is made over (Jakob & Hanika Sec. 4)

// The sigmoid of Jakob & Hanika Eq. 3, S(x) = 1/2 + x / (2 sqrt(1 + x^2)), and its derivative.
double sigmoid(double x) { return std::isinf(x) ? (x > 0.0 ? 1.0 : 0.0) : 0.5 + x / (2.0 * std::sqrt(1.0 + x * x)); }
double sigmoid_slope(double x) { return 0.5 / std::pow(1.0 + x * x, 1.5); }

// Per 1 nm sample: t and its weights in linear sRGB, so that sRGB(f) = sum_i f(lambda_i) weight_i (D65, CIE 1931,
// the perfect reflector at Y = 1).
struct FitSamples {
    std::vector<double> t;
    std::vector<std::array<double, 3>> weight;
};

const FitSamples& fit_samples() {
    static const FitSamples samples = [] {
        std::vector<double> nm;
        for (int i = 0; i <= static_cast<int>(span_nm); ++i) nm.push_back(first_nm + i);
        const TristimulusWeights w(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
        FitSamples s;
        for (std::size_t i = 0; i < nm.size(); ++i) {
            const auto [x, y, z] = w.weights(i);
            s.t.push_back((nm[i] - first_nm) / span_nm);
            s.weight.push_back(linear_srgb(XYZ{x, y, z}));
        }
        return s;
    }();
    return samples;
}

using Vector3 = Eigen::Vector3d;

// The sigmoid polynomial's sRGB minus the target, and its Jacobian in (c0, c1, c2).
Vector3 residual(const Vector3& c, const Vector3& target, Eigen::Matrix3d* jacobian) {
    const auto& s = fit_samples();
    Vector3 rgb = Vector3::Zero();
    if (jacobian) jacobian->setZero();
    for (std::size_t i = 0; i < s.t.size(); ++i) {
        const double t = s.t[i];
        const double x = (c[0] * t + c[1]) * t + c[2];
        const Vector3 w(s.weight[i][0], s.weight[i][1], s.weight[i][2]);
        rgb += sigmoid(x) * w;
        if (jacobian) *jacobian += sigmoid_slope(x) * w * Eigen::RowVector3d(t * t, t, 1.0);
    }
    return rgb - target;
}

// Damped Newton from `c` towards the target; the best coefficients found.
Vector3 newton(Vector3 c, const Vector3& target) {
    Eigen::Matrix3d jacobian;
    Vector3 r = residual(c, target, &jacobian);
    for (int iteration = 0; iteration < 50 && r.norm() > 1e-12; ++iteration) {
        const Vector3 step = jacobian.colPivHouseholderQr().solve(-r);
        if (!step.allFinite()) break;
        double damping = 1.0;
        bool improved = false;
        for (int halving = 0; halving < 30; ++halving, damping *= 0.5) {
            Eigen::Matrix3d next_jacobian;
            const Vector3 next = c + damping * step;
            const Vector3 next_r = residual(next, target, &next_jacobian);
            if (next_r.norm() < r.norm()) {
                c = next;
                r = next_r;
                jacobian = next_jacobian;
                improved = true;
                break;
            }
        }
        if (!improved) break;
    }
    return c;
}

}  // namespace

std::array<double, 3> linear_srgb(const XYZ& xyz) {
    // IEC 61966-2-1:1999, the XYZ to linear sRGB matrix.
    return {3.2406 * xyz.X - 1.5372 * xyz.Y - 0.4986 * xyz.Z, -0.9689 * xyz.X + 1.8758 * xyz.Y + 0.0415 * xyz.Z,
            0.0557 * xyz.X - 0.2040 * xyz.Y + 1.0570 * xyz.Z};
}

UpliftedSpectrum::UpliftedSpectrum(const std::array<double, 3>& rgb) {
    for (const double v : rgb) {
        if (!std::isfinite(v) || v < 0.0) {
            throw InputError("RGB coefficient " + format_number(v) + " cannot become a spectrum (allowed: finite, >= 0)");
        }
    }
    scale_ = 2.0 * std::max({rgb[0], rgb[1], rgb[2]});
    if (scale_ == 0.0) return;
    const Vector3 target = Vector3(rgb[0], rgb[1], rgb[2]) / scale_;
    // From the grey of the target's mean, S(c2) = mean (S^-1(v) = u / sqrt(1 - u^2), u = 2v - 1), along the straight
    // path to the target in steps, each solved from the last (saturated targets are far from any start).
    const double grey = target.mean();
    const double u = 2.0 * grey - 1.0;
    Vector3 c(0.0, 0.0, u / std::sqrt(1.0 - u * u));
    constexpr int steps = 8;
    for (int k = 1; k <= steps; ++k) {
        const double f = static_cast<double>(k) / steps;
        c = newton(c, (1.0 - f) * Vector3::Constant(grey) + f * target);
    }
    c_ = {c[0], c[1], c[2]};
}

double UpliftedSpectrum::operator()(double wavelength_nm) const {
    if (scale_ == 0.0) return 0.0;
    const double t = (wavelength_nm - first_nm) / span_nm;
    return scale_ * sigmoid((c_[0] * t + c_[1]) * t + c_[2]);
}

}  // namespace skinspec
