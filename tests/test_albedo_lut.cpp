#include <catch2/catch.hpp>

#include <cmath>

#include "inverse/image_fit/albedo_lut.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

// A table of f(i, j) per channel at the nodes (index coordinates).
template <class F>
AlbedoLut table_of(std::size_t nu, std::size_t nv, F f) {
    const ParameterSweep u{"epidermis.melanosome_fraction", 0.01, 0.4, nu, true}, v{"dermis.blood_fraction", 0.002, 0.05, nv, false};
    std::vector<double> values;
    for (std::size_t j = 0; j < nv; ++j) {
        for (std::size_t i = 0; i < nu; ++i) {
            for (std::size_t c = 0; c < 3; ++c) values.push_back(f(static_cast<double>(i), static_cast<double>(j), c));
        }
    }
    return AlbedoLut(u, v, {"R", "G", "B"}, values);
}

}  // namespace

TEST_CASE("the table passes through its nodes and reproduces linear functions with their derivatives", "[albedo_lut]") {
    const auto linear = [](double i, double j, std::size_t c) { return 1.0 + 0.1 * i + 0.05 * j + 0.01 * static_cast<double>(c); };
    const auto lut = table_of(7, 5, linear);
    for (const LutPoint p : {LutPoint{0, 0}, LutPoint{6, 4}, LutPoint{3, 2}, LutPoint{0.3, 3.7}, LutPoint{5.99, 0.01}, LutPoint{2.5, 4}}) {
        const auto s = lut.sample(p);
        for (std::size_t c = 0; c < 3; ++c) {
            CHECK(s.value[c] == Approx(linear(p.u, p.v, c)).epsilon(1e-12));
            CHECK(s.d_du[c] == Approx(0.1).epsilon(1e-12));
            CHECK(s.d_dv[c] == Approx(0.05).epsilon(1e-12));
        }
    }
}

TEST_CASE("away from its edges the table reproduces quadratics (Catmull-Rom is exact to second order)", "[albedo_lut]") {
    const auto quadratic = [](double i, double j, std::size_t) { return 2.0 + 0.3 * i * i - 0.2 * i * j + 0.1 * j * j; };
    const auto lut = table_of(8, 7, quadratic);
    for (const LutPoint p : {LutPoint{1.5, 1.5}, LutPoint{3.25, 4.75}, LutPoint{5.9, 2.1}}) {
        const auto s = lut.sample(p);
        CHECK(s.value[0] == Approx(quadratic(p.u, p.v, 0)).epsilon(1e-12));
        CHECK(s.d_du[0] == Approx(0.6 * p.u - 0.2 * p.v).margin(1e-12));
        CHECK(s.d_dv[0] == Approx(-0.2 * p.u + 0.2 * p.v).margin(1e-12));
    }
}

TEST_CASE("the derivatives are those of the interpolated values (finite differences)", "[albedo_lut]") {
    const auto smooth = [](double i, double j, std::size_t c) { return 0.5 * std::exp(-0.1 * i * (1.0 + static_cast<double>(c)) - 0.07 * j); };
    const auto lut = table_of(9, 6, smooth);
    const double h = 1e-6;
    for (const LutPoint p : {LutPoint{0.2, 0.4}, LutPoint{4.4, 2.6}, LutPoint{7.7, 4.9}}) {
        const auto s = lut.sample(p);
        const auto du = lut.sample({p.u + h, p.v}), dv = lut.sample({p.u, p.v + h});
        for (std::size_t c = 0; c < 3; ++c) {
            CHECK(s.d_du[c] == Approx((du.value[c] - s.value[c]) / h).epsilon(1e-4));
            CHECK(s.d_dv[c] == Approx((dv.value[c] - s.value[c]) / h).epsilon(1e-4));
        }
    }
}

TEST_CASE("index coordinates map to the sweeps' values, evenly in the logarithm for log sweeps", "[albedo_lut]") {
    const ParameterSweep log_sweep{"f", 0.01, 0.4, 9, true}, linear_sweep{"g", 0.002, 0.05, 5, false};
    CHECK(AlbedoLut::value_at(log_sweep, 0.0) == Approx(0.01));
    CHECK(AlbedoLut::value_at(log_sweep, 8.0) == Approx(0.4));
    CHECK(AlbedoLut::value_at(log_sweep, 4.0) == Approx(std::sqrt(0.01 * 0.4)));
    CHECK(AlbedoLut::value_at(linear_sweep, 2.0) == Approx(0.026));
    for (const auto* s : {&log_sweep, &linear_sweep}) {
        for (const double x : {0.0, 1.3, 3.9}) {
            CHECK(AlbedoLut::index_of(*s, AlbedoLut::value_at(*s, x)) == Approx(x).margin(1e-12));
            const double h = 1e-6;
            CHECK(AlbedoLut::value_per_index(*s, x) == Approx((AlbedoLut::value_at(*s, x + h) - AlbedoLut::value_at(*s, x)) / h).epsilon(1e-5));
        }
    }
}

TEST_CASE("a table refuses too few nodes, too many channels and values that are not positive", "[albedo_lut]") {
    const ParameterSweep one{"epidermis.melanosome_fraction", 0.1, 0.1, 1, false}, two{"dermis.blood_fraction", 0.01, 0.02, 2, false};
    CHECK_THROWS_WITH(AlbedoLut(one, two, {"R"}, {0.1, 0.1}), Catch::Contains("at least 2 values per axis"));
    CHECK_THROWS_WITH(AlbedoLut(two, two, std::vector<std::string>(17, "b"), std::vector<double>(4 * 17, 0.5)), Catch::Contains("allowed 1 to 16"));
    CHECK_THROWS_WITH(AlbedoLut(two, two, {"R"}, {0.1, -0.02, 0.3, 0.4}),
                      Catch::Contains("R is -0.02 at dermis.blood_fraction = 0.02, dermis.blood_fraction = 0.01") && Catch::Contains("gamut"));
    CHECK_THROWS_WITH(AlbedoLut(two, two, {"R"}, {0.1, 0.2, NAN, 0.4}), Catch::Contains("allowed: finite and > 0"));
}
