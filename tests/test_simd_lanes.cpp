// The walks' lane samplers (transport/simd_lanes-inl.h) against their exact formulas in double precision, for every
// instruction set the machine has, at every one of the 2^24 values the lane streams draw; the weights' exponential
// against std::exp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "tests/test_simd_lanes.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "transport/simd_lanes-inl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

HWY_BEFORE_NAMESPACE();
namespace skinspec {
namespace HWY_NAMESPACE {

// Largest absolute errors over u = k 2^-24: [0] Rayleigh cos theta against the exact root of its CDF (Cardano),
// [1] cos phi and [2] sin phi against the azimuth's own phi = (f - 1/2) pi / 2 + q pi / 2 (4u = q + f), [3] the
// largest deviation of the 64 phi-bins' counts from the uniform 2^24 / 64.
std::array<double, 4> SamplerErrorsImpl() {
    const DF df;
    const std::size_t n = hn::Lanes(df);
    std::vector<float> u(n), a(n), b(n);
    std::array<double, 4> worst{};
    std::vector<long> bins(64, 0);
    for (std::size_t k = 0; k < (std::size_t{1} << 24); k += n) {
        for (std::size_t i = 0; i < n; ++i) u[i] = static_cast<float>(k + i) * 0x1.0p-24f;
        const VF vu = hn::LoadU(df, u.data());
        hn::StoreU(RayleighCos(vu), df, a.data());
        for (std::size_t i = 0; i < n; ++i) {
            // mu^3 + 3 mu = 8u - 4 (Chandrasekhar 1960 Eq. I.(26)): mu = c - 1/c, c = cbrt(y/2 + sqrt(y^2/4 + 1)).
            const double y = 8.0 * u[i] - 4.0;
            const double c = std::cbrt(y / 2.0 + std::sqrt(y * y / 4.0 + 1.0));
            worst[0] = std::max(worst[0], std::abs(a[i] - (c - 1.0 / c)));
        }
        VF cos_phi, sin_phi;
        Azimuth(vu, cos_phi, sin_phi);
        hn::StoreU(cos_phi, df, a.data());
        hn::StoreU(sin_phi, df, b.data());
        for (std::size_t i = 0; i < n; ++i) {
            const double v = 4.0 * u[i], q = std::floor(v);
            const double phi = (v - q - 0.5) * std::numbers::pi / 2.0 + q * std::numbers::pi / 2.0;
            worst[1] = std::max(worst[1], std::abs(a[i] - std::cos(phi)));
            worst[2] = std::max(worst[2], std::abs(b[i] - std::sin(phi)));
            const double angle = std::atan2(static_cast<double>(b[i]), static_cast<double>(a[i])) + std::numbers::pi;
            ++bins[std::min<std::size_t>(63, static_cast<std::size_t>(angle / (2.0 * std::numbers::pi) * 64.0))];
        }
    }
    for (const long count : bins) worst[3] = std::max(worst[3], std::abs(static_cast<double>(count) - 262144.0));
    return worst;
}

// Largest relative error of ExpOfNegativeDepth against std::exp over tau = k 2^-12 in [0, 80], each tau a float.
double ExpErrorImpl() {
    const DF df;
    const std::size_t n = hn::Lanes(df);
    std::vector<float> tau(n), w(n);
    double worst = 0.0;
    for (std::size_t k = 0; k <= (std::size_t{80} << 12); k += n) {
        for (std::size_t i = 0; i < n; ++i) tau[i] = std::min(80.0f, static_cast<float>(k + i) * 0x1.0p-12f);
        hn::StoreU(ExpOfNegativeDepth(df, hn::LoadU(df, tau.data())), df, w.data());
        for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(w[i] / std::exp(-static_cast<double>(tau[i])) - 1.0));
    }
    return worst;
}

}  // namespace HWY_NAMESPACE
}  // namespace skinspec
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <catch2/catch.hpp>

#include <hwy/targets.h>

#include "forced_target.hpp"

namespace skinspec {
HWY_EXPORT(SamplerErrorsImpl);
HWY_EXPORT(ExpErrorImpl);
}  // namespace skinspec

TEST_CASE("Rayleigh cos theta and the azimuth are their exact formulas to single-precision rounding", "[simd_lanes]") {
    for (const auto target : hwy::SupportedAndGeneratedTargets()) {
        skinspec::testing::ForcedTarget forced(target);
        INFO("instruction set " << hwy::TargetName(target));
        const auto worst = HWY_DYNAMIC_DISPATCH(skinspec::SamplerErrorsImpl)();
        // One unit in the last place of 1 is 1.19e-7: the samplers are within it.
        CHECK(worst[0] < 1.2e-7);
        CHECK(worst[1] < 1.2e-7);
        CHECK(worst[2] < 1.2e-7);
        // The 2^24 evenly spaced u fill the 64 azimuth bins equally but for rounding at the bins' edges.
        CHECK(worst[3] <= 2.0);
    }
}

TEST_CASE("a weight's exponential is std::exp to float precision over optical depths 0-80", "[simd_lanes]") {
    for (const auto target : hwy::SupportedAndGeneratedTargets()) {
        skinspec::testing::ForcedTarget forced(target);
        const double worst = HWY_DYNAMIC_DISPATCH(skinspec::ExpErrorImpl)();
        INFO("instruction set " << hwy::TargetName(target) << ": largest relative error " << worst);
        // 2.5 units in the last place of 1: the series' remainder (1.2e-7) and the rounding of its sums.
        CHECK(worst < 3e-7);
    }
}
#endif
