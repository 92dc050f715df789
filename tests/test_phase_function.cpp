#include <catch2/catch.hpp>

#include "transport/phase_function.hpp"

using namespace skinspec;

TEST_CASE("each phase function kind samples with its mean cosine", "[phase_function]") {
    const auto mean_cos = [](const PhaseFunction& p) {
        auto random = RandomStream::for_batch(2, 600.0, 0);
        double m = 0.0;
        for (int i = 0; i < 100000; ++i) m += p.sample_cos(random) / 1e5;
        return m;
    };
    CHECK(mean_cos(PhaseFunction::henyey_greenstein(0.8)) == Approx(0.8).margin(0.01));
    CHECK(mean_cos(PhaseFunction::isotropic()) == Approx(0.0).margin(0.01));
    CHECK(mean_cos(PhaseFunction{PhaseFunction::Kind::rayleigh, 0, 0, 1, nullptr}) == Approx(0.0).margin(0.01));
    CHECK(mean_cos(PhaseFunction{PhaseFunction::Kind::two_term_hg, 0.9, -0.3, 0.5, nullptr}) == Approx(0.3).margin(0.01));
    const auto table = std::make_shared<const InverseCdfTable>(MeasuredProfile::epidermis().inverse_table(546.0));
    const double m = mean_cos(PhaseFunction{PhaseFunction::Kind::tabulated, 0, 0, 1, table});
    CHECK(m > 0.8);
    CHECK(m < 0.95);
    CHECK(PhaseFunction::isotropic().describe() == "isotropic");
}
