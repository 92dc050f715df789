#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "materials/measured_profile.hpp"
#include "transport/random_stream.hpp"

using namespace skinspec;

namespace {

// Table 1 of Baranoski et al. 2005 (Bruls & van der Leun 1984), cumulative percent at 0, 2.5, 7.5, ..., 62.5 deg.
const std::vector<double> sc_436{0, 17.6, 55.2, 70.9, 79.1, 84.1, 87.6, 90.3, 92.5, 94.4, 96.1, 97.6, 99.0, 100};
const std::vector<double> ep_546{0, 4.0, 22.5, 39.7, 52.5, 62.4, 70.2, 76.7, 82.4, 87.2, 91.4, 94.9, 97.9, 100};

}  // namespace

TEST_CASE("the profiles hold the published cumulative data", "[measured_profile]") {
    const auto sc = MeasuredProfile::stratum_corneum().cumulative(436.0);
    const auto ep = MeasuredProfile::epidermis().cumulative(546.0);
    REQUIRE(sc.size() == sc_436.size());
    for (std::size_t i = 0; i < sc.size(); ++i) {
        CHECK(sc[i] * 100.0 == Approx(sc_436[i]).margin(1e-9));
        CHECK(ep[i] * 100.0 == Approx(ep_546[i]).margin(1e-9));
    }
}

TEST_CASE("profiles interpolate linearly in wavelength and clamp outside", "[measured_profile]") {
    const auto& p = MeasuredProfile::stratum_corneum();
    // Halfway between 436 and 546 nm at 2.5 deg: (17.6 + 20.6) / 2 = 19.1 %.
    CHECK(p.cumulative(491.0)[1] * 100.0 == Approx(19.1).margin(1e-9));
    CHECK(p.cumulative(700.0) == p.cumulative(546.0));
    CHECK(p.cumulative(200.0) == p.cumulative(254.0));
    CHECK(MeasuredProfile::epidermis().cumulative(254.0) == MeasuredProfile::epidermis().cumulative(302.0));
}

TEST_CASE("the 1000-entry inverse table reproduces the cumulative data", "[measured_profile]") {
    for (const auto* profile : {&MeasuredProfile::stratum_corneum(), &MeasuredProfile::epidermis()}) {
        for (const double nm : {436.0, 546.0}) {
            const auto table = profile->inverse_table(nm, 1000);
            const auto c = profile->cumulative(nm);
            const auto angles = profile->angles_deg();
            // Fraction of entries within each tabulated angle: within half an entry (0.05 %) of the data.
            for (std::size_t a = 0; a < angles.size(); ++a) {
                std::size_t within = 0;
                for (std::size_t j = 0; j < table.size(); ++j) within += table.theta_deg(j) <= angles[a] + 1e-12;
                CHECK(static_cast<double>(within) / 1000.0 == Approx(c[a]).margin(0.0005 + 1e-12));
            }
        }
    }
}

TEST_CASE("randomized table look-up samples match the measured fractions", "[measured_profile]") {
    const auto& profile = MeasuredProfile::epidermis();
    const auto table = profile.inverse_table(436.0);
    auto random = RandomStream::for_batch(1, 436.0, 0);
    const int n = 200000;
    std::vector<int> counts(profile.angles_deg().size(), 0);
    for (int i = 0; i < n; ++i) {
        const double theta = table.theta_deg(table.index(random.uniform()));
        for (std::size_t a = 0; a < counts.size(); ++a) counts[a] += theta <= profile.angles_deg()[a] + 1e-12;
    }
    const auto c = profile.cumulative(436.0);
    for (std::size_t a = 1; a < counts.size(); ++a) {
        const double p = c[a];
        const double sigma = std::sqrt(p * (1 - p) / n) + 1e-12;
        CHECK(std::abs(counts[a] / static_cast<double>(n) - p) < 4.0 * sigma + 0.0005);
    }
    // The density integrates to 1 over 0-62.5 deg.
    double integral = 0.0;
    for (int i = 0; i < 6250; ++i) integral += profile.pdf_theta(436.0, (i + 0.5) * 0.01) * 0.01;
    CHECK(integral == Approx(1.0).epsilon(1e-9));
    CHECK(profile.cdf(436.0, 5.0) == Approx((0.026 + 0.161) / 2.0));
}

TEST_CASE("a profile between tabulated wavelengths is the mixture of its two neighbours", "[measured_profile]") {
    // The cumulative fractions are linear in wavelength between tabulated profiles, so C(lambda) is exactly
    // (1 - w) C(lower) + w C(upper) with w the fractional position; at and beyond the ends w = 0.
    for (const auto* profile : {&MeasuredProfile::stratum_corneum(), &MeasuredProfile::epidermis()}) {
        const auto nm = profile->wavelengths_nm();
        for (const double wavelength : {nm.front() - 50.0, nm.front(), 0.5 * (nm[1] + nm[2]), nm[2] + 0.1, nm.back(), 700.0}) {
            INFO(wavelength << " nm");
            const auto m = profile->mixture(wavelength);
            REQUIRE(m.lower <= m.upper);
            REQUIRE(m.upper < nm.size());
            CHECK(m.upper_weight >= 0.0);
            CHECK(m.upper_weight < 1.0);
            const auto c = profile->cumulative(wavelength);
            const auto lower = profile->cumulative(nm[m.lower]);
            const auto upper = profile->cumulative(nm[m.upper]);
            for (std::size_t i = 0; i < c.size(); ++i) CHECK(c[i] == Approx((1.0 - m.upper_weight) * lower[i] + m.upper_weight * upper[i]).margin(1e-12));
        }
        CHECK(profile->mixture(0.5 * (nm[1] + nm[2])).upper_weight == Approx(0.5));
        CHECK(profile->tabulated_inverse_table(1) == profile->tabulated_inverse_table(1));  // built once, shared
    }
}
