#include "transport/diffusion/multipole.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "transport/diffusion/point_source.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

void check(bool ok, const char* field, double value, const char* range) {
    if (!ok) throw InputError(std::string("diffusion slab: ") + field + " = " + format_number(value) + " is outside " + range);
}

// sum_{i >= m} [exp(-s (2 i P + a)) - exp(-s (2 i P + b))] in closed form (a geometric series; requires
// 2 m P + a > 0 and 2 m P + b > 0); its s -> 0 limit is (b - a) / (2 P).
double pair_tail(double s, double a, double b, double period, int m) {
    if (s == 0.0) return (b - a) / (2.0 * period);
    // exp(-x) - exp(-y) = sgn(y - x) exp(-min(x, y)) (1 - exp(-|y - x|)), free of overflow and cancellation.
    const double x = s * (2.0 * m * period + a), y = s * (2.0 * m * period + b);
    const double difference = std::copysign(std::exp(-std::min(x, y)) * -std::expm1(-std::abs(y - x)), y - x);
    return difference / -std::expm1(-2.0 * s * period);
}

}  // namespace

Multipole::Multipole(const DiffusionSlab& slab, double relative_tolerance) : slab_(slab), tolerance_(relative_tolerance) {
    check(std::isfinite(slab.reduced_scattering) && slab.reduced_scattering >= 0.0, "reduced scattering", slab.reduced_scattering, "[0, inf)");
    check(std::isfinite(slab.absorption) && slab.absorption >= 0.0, "absorption", slab.absorption, "[0, inf)");
    check(slab.reduced_scattering + slab.absorption > 0.0, "sigma_t'", slab.reduced_scattering + slab.absorption, "(0, inf)");
    check(slab.thickness > 0.0 && !std::isnan(slab.thickness), "thickness", slab.thickness, "(0, inf]");
    check(slab.top_internal_reflectance >= 0.0 && slab.top_internal_reflectance < 1.0, "top internal reflectance",
          slab.top_internal_reflectance, "[0, 1)");
    check(slab.bottom_internal_reflectance >= 0.0 && slab.bottom_internal_reflectance < 1.0, "bottom internal reflectance",
          slab.bottom_internal_reflectance, "[0, 1)");
    const double sigma_t = slab.reduced_scattering + slab.absorption;
    alpha_prime_ = slab.reduced_scattering / sigma_t;
    sigma_tr_ = std::sqrt(3.0 * slab.absorption * sigma_t);
    l_ = 1.0 / sigma_t;
    // Seed 002 Eq. 7 and Sec. 2: A = (1 + F) / (1 - F), extrapolation distance z_b = 2 A D with D = 1 / (3 sigma_t').
    const double diffusion_constant = 1.0 / (3.0 * sigma_t);
    const auto extrapolation = [&](double f) { return 2.0 * (1.0 + f) / (1.0 - f) * diffusion_constant; };
    zb_top_ = extrapolation(slab.top_internal_reflectance);
    zb_bottom_ = extrapolation(slab.bottom_internal_reflectance);
    finite_ = std::isfinite(slab.thickness);
    const double d = finite_ ? slab.thickness : 0.0;
    z_s_ = finite_ ? std::min(l_, 0.5 * d) : l_;
    period_ = d + zb_top_ + zb_bottom_;  // Eq. 16: the pattern repeats every 2 (d + z_b(0) + z_b(d))
    explicit_pairs_ = finite_ ? static_cast<int>(std::floor((z_s_ + 2.0 * zb_top_ + d) / (2.0 * period_))) + 1 : 1;
}

Multipole::Sum Multipole::profile_sum(double r, bool transmit) const {
    const double d = finite_ ? slab_.thickness : 0.0;
    // Eq. 16: z_r,i = 2 i P + l and z_v,i = 2 i P - l - 2 z_b(0); Eq. 12 (R) sees a source at height z from
    // the top face, Eq. 13 (T) at d - z from the bottom face; virtual sources carry the opposite sign.
    const auto pair = [&](int i) {
        const double z_r = 2.0 * i * period_ + z_s_;
        const double z_v = 2.0 * i * period_ - z_s_ - 2.0 * zb_top_;
        const double w_r = transmit ? d - z_r : z_r;
        const double w_v = transmit ? d - z_v : z_v;
        return alpha_prime_ * (diffusion::point_source_exitance(w_r, r, sigma_tr_) - diffusion::point_source_exitance(w_v, r, sigma_tr_));
    };
    if (!finite_) return {transmit ? 0.0 : pair(0), 1, true};
    double sum = pair(0);
    const double reach = r + z_s_ + 2.0 * zb_top_ + d;  // beyond this, pairs only shrink with |i|
    for (int i = 1; static_cast<std::size_t>(2 * i + 1) <= max_pairs; ++i) {
        const double change = pair(i) + pair(-i);
        sum += change;
        if (2.0 * i * period_ > reach && std::abs(change) <= tolerance_ * std::abs(sum)) return {sum, static_cast<std::size_t>(2 * i + 1), true};
    }
    return {sum, max_pairs, false};
}

double Multipole::radial_reflectance(double r) const { return profile_sum(r, false).value; }
double Multipole::radial_transmittance(double r) const { return profile_sum(r, true).value; }

namespace {
template <typename F>
RadialProfile profile_of(std::span<const double> radii, F&& sum) {
    RadialProfile out;
    out.values.reserve(radii.size());
    for (const double r : radii) {
        const auto s = sum(r);
        out.values.push_back(s.value);
        out.max_pairs = std::max(out.max_pairs, s.pairs);
        out.converged = out.converged && s.converged;
    }
    return out;
}
}  // namespace

RadialProfile Multipole::reflectance_profile(std::span<const double> radii) const {
    return profile_of(radii, [&](double r) { return profile_sum(r, false); });
}
RadialProfile Multipole::transmittance_profile(std::span<const double> radii) const {
    return profile_of(radii, [&](double r) { return profile_sum(r, true); });
}

double Multipole::transform(double k, bool transmit) const {
    const double s = std::sqrt(sigma_tr_ * sigma_tr_ + k * k);
    if (!finite_) {
        if (transmit) return 0.0;
        return alpha_prime_ * (diffusion::point_source_transform(z_s_, s) - diffusion::point_source_transform(-z_s_ - 2.0 * zb_top_, s));
    }
    const double d = slab_.thickness;
    const double l = z_s_, zb = zb_top_, p = period_;
    const int m = explicit_pairs_;
    double sum = 0.0;
    for (int i = 1 - m; i < m; ++i) {
        const double z_r = 2.0 * i * p + l;
        const double z_v = 2.0 * i * p - l - 2.0 * zb;
        sum += transmit ? diffusion::point_source_transform(d - z_r, s) - diffusion::point_source_transform(d - z_v, s)
                        : diffusion::point_source_transform(z_r, s) - diffusion::point_source_transform(z_v, s);
    }
    // Pairs with |i| >= m all lie on one side of the face: each side is a geometric series.
    const double tails = transmit ? -pair_tail(s, l - d, -l - 2.0 * zb - d, p, m) + pair_tail(s, d - l, d + l + 2.0 * zb, p, m)
                                  : pair_tail(s, l, -l - 2.0 * zb, p, m) - pair_tail(s, -l, l + 2.0 * zb, p, m);
    return alpha_prime_ * (sum + 0.5 * tails);
}

double Multipole::reflectance_transform(double k) const { return transform(k, false); }
double Multipole::transmittance_transform(double k) const { return transform(k, true); }

Multipole Multipole::flipped() const {
    auto swapped = slab_;
    std::swap(swapped.top_internal_reflectance, swapped.bottom_internal_reflectance);
    return Multipole(swapped, tolerance_);
}

}  // namespace skinspec
