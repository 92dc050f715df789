#include "spectral/ciede2000.hpp"

#include <cmath>
#include <numbers>

namespace skinspec {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

// Hue angle in degrees in [0, 360); 0 for a neutral colour (Sharma Eq. 4).
double hue_deg(double b, double a) {
    if (a == 0.0 && b == 0.0) return 0.0;
    const double h = std::atan2(b, a) / deg;
    return h < 0.0 ? h + 360.0 : h;
}

}  // namespace

double ciede2000(const Lab& lab1, const Lab& lab2, const Ciede2000Factors& k) {
    // Sharma Eq. 2-7: a' rescaled by G, then C', h'.
    const double c1 = std::hypot(lab1.a, lab1.b);
    const double c2 = std::hypot(lab2.a, lab2.b);
    const double c_mean = 0.5 * (c1 + c2);
    const double c7 = std::pow(c_mean, 7.0);
    const double g = 0.5 * (1.0 - std::sqrt(c7 / (c7 + std::pow(25.0, 7.0))));
    const double a1p = (1.0 + g) * lab1.a;
    const double a2p = (1.0 + g) * lab2.a;
    const double c1p = std::hypot(a1p, lab1.b);
    const double c2p = std::hypot(a2p, lab2.b);
    const double h1p = hue_deg(lab1.b, a1p);
    const double h2p = hue_deg(lab2.b, a2p);

    // Eq. 8-11: differences.
    const double dLp = lab2.L - lab1.L;
    const double dCp = c2p - c1p;
    double dhp = 0.0;
    if (c1p * c2p != 0.0) {
        dhp = h2p - h1p;
        if (dhp > 180.0) dhp -= 360.0;
        else if (dhp < -180.0) dhp += 360.0;
    }
    const double dHp = 2.0 * std::sqrt(c1p * c2p) * std::sin(0.5 * dhp * deg);

    // Eq. 12-22: means, weighting functions and the rotation term.
    const double lp_mean = 0.5 * (lab1.L + lab2.L);
    const double cp_mean = 0.5 * (c1p + c2p);
    double hp_mean = h1p + h2p;
    if (c1p * c2p != 0.0) {
        if (std::abs(h1p - h2p) <= 180.0) hp_mean *= 0.5;
        else if (h1p + h2p < 360.0) hp_mean = 0.5 * (h1p + h2p + 360.0);
        else hp_mean = 0.5 * (h1p + h2p - 360.0);
    }
    const double t = 1.0 - 0.17 * std::cos((hp_mean - 30.0) * deg) + 0.24 * std::cos(2.0 * hp_mean * deg) +
                     0.32 * std::cos((3.0 * hp_mean + 6.0) * deg) - 0.20 * std::cos((4.0 * hp_mean - 63.0) * deg);
    const double d_theta = 30.0 * std::exp(-std::pow((hp_mean - 275.0) / 25.0, 2.0));
    const double cp7 = std::pow(cp_mean, 7.0);
    const double rc = 2.0 * std::sqrt(cp7 / (cp7 + std::pow(25.0, 7.0)));
    const double l50 = (lp_mean - 50.0) * (lp_mean - 50.0);
    const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
    const double sc = 1.0 + 0.045 * cp_mean;
    const double sh = 1.0 + 0.015 * cp_mean * t;
    const double rt = -std::sin(2.0 * d_theta * deg) * rc;

    const double tl = dLp / (k.kL * sl);
    const double tc = dCp / (k.kC * sc);
    const double th = dHp / (k.kH * sh);
    return std::sqrt(tl * tl + tc * tc + th * th + rt * tc * th);
}

}  // namespace skinspec
