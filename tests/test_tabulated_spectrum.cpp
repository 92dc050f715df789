#include <catch2/catch.hpp>

#include "spectral/input_error.hpp"
#include "spectral/tabulated_spectrum.hpp"

using namespace skinspec;

TEST_CASE("piecewise-linear inside the domain", "[tabulated_spectrum]") {
    const TabulatedSpectrum s("test", {400, 500, 600}, {0.0, 1.0, 3.0}, OutOfRangePolicy::error);
    CHECK(s(400) == 0.0);
    CHECK(s(450) == Approx(0.5));
    CHECK(s(500) == 1.0);
    CHECK(s(575) == Approx(2.5));
    CHECK(s(600) == 3.0);
}

TEST_CASE("each out-of-range policy does what it says", "[tabulated_spectrum]") {
    const std::vector<double> nm{400, 500};
    const std::vector<double> v{2.0, 4.0};
    CHECK(TabulatedSpectrum("z", nm, v, OutOfRangePolicy::zero)(399) == 0.0);
    CHECK(TabulatedSpectrum("h", nm, v, OutOfRangePolicy::hold)(300) == 2.0);
    CHECK(TabulatedSpectrum("h", nm, v, OutOfRangePolicy::hold)(900) == 4.0);
    CHECK_THROWS_WITH(TabulatedSpectrum("melanin", nm, v, OutOfRangePolicy::error)(501),
                      "melanin: wavelength 501 nm is outside the tabulated domain [400, 500] nm");
}

TEST_CASE("malformed tables are rejected", "[tabulated_spectrum]") {
    CHECK_THROWS_AS(TabulatedSpectrum("t", {400}, {1.0}, OutOfRangePolicy::zero), InputError);
    CHECK_THROWS_AS(TabulatedSpectrum("t", {400, 400}, {1.0, 1.0}, OutOfRangePolicy::zero), InputError);
    CHECK_THROWS_AS(TabulatedSpectrum("t", {400, 500}, {1.0}, OutOfRangePolicy::zero), InputError);
    CHECK_THROWS_AS(TabulatedSpectrum("t", {400, 500}, {1.0, std::nan("")}, OutOfRangePolicy::zero), InputError);
    CHECK(parse_out_of_range_policy("hold", "x") == OutOfRangePolicy::hold);
    CHECK_THROWS_WITH(parse_out_of_range_policy("clamp", "outside_domain"),
                      Catch::Contains("allowed: error, zero, hold"));
}
