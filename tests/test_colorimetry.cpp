#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "spectral/cie.hpp"
#include "spectral/colorimetry.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

XYZ flat(double value, IlluminantKind illuminant, ObserverKind observer = ObserverKind::cie1931_2deg) {
    const TabulatedSpectrum s("flat", {360, 830}, {value, value}, OutOfRangePolicy::error);
    return spectrum_to_xyz(s, illuminant, observer);
}

}  // namespace

TEST_CASE("white points from the 1 nm tables match CIE 015:2018 Table T.3", "[colorimetry]") {
    // Published 2-degree chromaticities: D65 (0.3127, 0.3290), D50 (0.3457, 0.3585), A (0.4476, 0.4074).
    struct Case { IlluminantKind kind; double x, y; };
    for (const auto& c : {Case{IlluminantKind::d65, 0.3127, 0.3290}, Case{IlluminantKind::d50, 0.3457, 0.3585},
                          Case{IlluminantKind::a, 0.4476, 0.4074}, Case{IlluminantKind::e, 1.0 / 3.0, 1.0 / 3.0}}) {
        const auto xy = chromaticity(flat(1.0, c.kind));
        CHECK(xy.x == Approx(c.x).margin(0.5e-4));
        CHECK(xy.y == Approx(c.y).margin(0.5e-4));
    }
    // 10-degree D65: (0.31382, 0.33100) in CIE 015:2018 Table T.3.
    const auto xy10 = chromaticity(flat(1.0, IlluminantKind::d65, ObserverKind::cie1964_10deg));
    CHECK(xy10.x == Approx(0.31382).margin(0.5e-4));
    CHECK(xy10.y == Approx(0.33100).margin(0.5e-4));
}

TEST_CASE("the perfect reflector has Y = 1 and Lab (100, 0, 0)", "[colorimetry]") {
    for (const auto kind : all_illuminants()) {
        const auto white = flat(1.0, kind);
        CHECK(white.Y == Approx(1.0).margin(1e-12));
        const auto lab = xyz_to_lab(white, white);
        CHECK(lab.L == Approx(100.0).margin(1e-10));
        CHECK(lab.a == Approx(0.0).margin(1e-10));
        CHECK(lab.b == Approx(0.0).margin(1e-10));
    }
}

TEST_CASE("an 18 % flat grey has L* = 49.50", "[colorimetry]") {
    // CIE 015:2018 Eq. 8.1: L* = 116 * 0.18^(1/3) - 16 = 49.496.
    const auto white = flat(1.0, IlluminantKind::d65);
    const auto grey = flat(0.18, IlluminantKind::d65);
    CHECK(grey.Y == Approx(0.18).margin(1e-12));
    CHECK(xyz_to_lab(grey, white).L == Approx(49.50).margin(0.005));
    // Below (6/29)^3 the linear branch: L* = 903.3 Y (CIE 015:2018 Eq. 8.3 note).
    CHECK(xyz_to_lab(flat(0.001, IlluminantKind::d65), white).L == Approx(903.2963 * 0.001).margin(1e-6));
}

TEST_CASE("tristimulus weights are linear in the samples and hold outside the samples", "[colorimetry]") {
    const std::vector<double> nm{400, 500, 600, 700};
    const TristimulusWeights w(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    // Holding a flat spectrum outside its samples is the flat spectrum everywhere: weights sum to the white.
    const auto ones = w.integrate(std::vector<double>{1, 1, 1, 1});
    CHECK(ones.X == Approx(w.white().X).epsilon(1e-12));
    CHECK(ones.Y == Approx(1.0).epsilon(1e-12));
    const auto a = w.integrate(std::vector<double>{0.1, 0.2, 0.3, 0.4});
    const auto b = w.integrate(std::vector<double>{0.2, 0.4, 0.6, 0.8});
    CHECK(b.Z == Approx(2 * a.Z).epsilon(1e-12));
    CHECK_THROWS_AS(w.integrate(std::vector<double>{1, 2}), InputError);
    CHECK_THROWS_AS(TristimulusWeights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::error),
                    InputError);
    // Zero outside: a reflectance of 1 only on 400-700 nm sees less than the full white.
    const TristimulusWeights z(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::zero);
    CHECK(z.integrate(std::vector<double>{1, 1, 1, 1}).Y < 1.0);
}

TEST_CASE("chromaticity of black is defined", "[colorimetry]") {
    const auto xy = chromaticity(XYZ{});
    CHECK(xy.x == 0.0);
    CHECK(xy.y == 0.0);
}

TEST_CASE("colours of steps, ramps and narrow bands on 5, 10 and 20 nm grids equal the 1 nm CIE sums", "[colorimetry]") {
    // The reference is CIE 015:2018 Eq. 7.1-7.2 summed here at every 1 nm of the CIE tables (360-830 nm), with the
    // spectrum linearly interpolated between its samples by this test's own arithmetic: k = 1 / sum ybar S_illuminant,
    // X = k sum R xbar S. Flat spectra cannot tell which way a sample's weight is interpolated (t against 1 - t moved Lab by
    // ~0.2 unseen); these spectra change between every pair of samples.
    const auto& cmf = observer(ObserverKind::cie1931_2deg);
    const auto& d65 = illuminant(IlluminantKind::d65);
    const std::vector<std::pair<const char*, std::function<double(double)>>> shapes{
        {"step at 550 nm", [](double nm) { return nm < 550.0 ? 0.1 : 0.7; }},
        {"ramp", [](double nm) { return 0.05 + 0.9 * (nm - 360.0) / 470.0; }},
        {"narrow band at 575 nm", [](double nm) { return std::exp(-0.5 * std::pow((nm - 575.0) / 6.0, 2.0)); }},
        {"skin-like", [](double nm) { return 0.1 + 0.5 / (1.0 + std::exp(-(nm - 590.0) / 12.0)) - 0.05 * std::exp(-0.5 * std::pow((nm - 542.0) / 10.0, 2.0)); }},
    };
    for (const double step : {5.0, 10.0, 20.0}) {
        std::vector<double> nm;  // from at or below 360 nm up to 830 nm
        for (double w = 830.0 - step * std::ceil(470.0 / step); w <= 830.0 + 1e-9; w += step) nm.push_back(w);
        const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::error);
        for (const auto& [name, shape] : shapes) {
            std::vector<double> samples;
            for (const double w : nm) samples.push_back(shape(w));
            double x = 0.0, y = 0.0, z = 0.0, norm = 0.0;
            for (int w = 360; w <= 830; ++w) {
                const auto i = std::min(static_cast<std::size_t>((w - nm.front()) / step), nm.size() - 2);
                const double t = (w - nm[i]) / step;
                const double r = (1.0 - t) * samples[i] + t * samples[i + 1];
                const double e = d65.power(w);
                x += r * cmf.xbar(w) * e;
                y += r * cmf.ybar(w) * e;
                z += r * cmf.zbar(w) * e;
                norm += cmf.ybar(w) * e;
            }
            const auto got = weights.integrate(samples);
            INFO(name << " on a " << step << " nm grid");
            CHECK(got.X == Approx(x / norm).epsilon(1e-10));
            CHECK(got.Y == Approx(y / norm).epsilon(1e-10));
            CHECK(got.Z == Approx(z / norm).epsilon(1e-10));
        }
    }
}
