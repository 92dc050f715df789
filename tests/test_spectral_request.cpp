#include <catch2/catch.hpp>

#include "spectral/input_error.hpp"
#include "transport/spectral_request.hpp"

using namespace skinspec;

TEST_CASE("quantities parse from a comma list, an unknown one is refused naming the allowed ones", "[spectral_request]") {
    const auto q = parse_quantities("R,T,A,brdf", "--quantities");
    CHECK((q.reflectance && q.transmittance && q.absorptance && q.angular));
    const auto t = parse_quantities("T", "--quantities");
    CHECK((!t.reflectance && t.transmittance && !t.absorptance && !t.angular));
    CHECK(parse_quantities("angular", "x").angular);
    CHECK_THROWS_WITH(parse_quantities("R,X", "quantities"), "quantities: 'X' is not a quantity (allowed: R, T, A, brdf)");
    CHECK_THROWS_WITH(parse_quantities("", "--quantities"), "--quantities: '' is not a quantity (allowed: R, T, A, brdf)");
    CHECK_THROWS_WITH(parse_quantities("R,", "--quantities"), Catch::Contains("'' is not a quantity"));
}

TEST_CASE("measurement geometries parse by name", "[spectral_request]") {
    CHECK(parse_measurement_geometry("0-45", "--geometry") == MeasurementGeometry::zero_45);
    CHECK_THROWS_WITH(parse_measurement_geometry("45-0", "--geometry"), Catch::Contains("'45-0' is not a measurement geometry"));
}

TEST_CASE("a result is labelled by its material and a sweep member's swept values in --vary order", "[spectral_request]") {
    SpectralResult result;
    result.material = "biospec-lightly";
    CHECK(result_label(result) == "biospec-lightly");
    result.provenance.varied = {std::make_shared<const std::vector<std::string>>(std::vector<std::string>{"epidermis.melanosome_fraction", "papillary_dermis.blood_fraction"}),
                                {0.068, 0.002}};
    CHECK(result_label(result) == "biospec-lightly: 0.068, 0.002");
}
