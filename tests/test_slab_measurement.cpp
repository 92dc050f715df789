#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "inverse/iad/inverse_adding_doubling.hpp"
#include "inverse/iad/slab_measurement.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("the setup table: one key and one iad letter per field, its defaults in range", "[iad]") {
    std::set<std::string> keys;
    std::set<char> letters;
    for (const auto& f : setup_fields()) {
        CHECK(keys.insert(std::string(f.key)).second);
        if (f.rxt_letter) CHECK(letters.insert(f.rxt_letter).second);
        CHECK(f.range.contains(SlabSetup{}.*(f.member)));
    }
    CHECK(setup_field_by_letter('n')->member == &SlabSetup::sample_index);
    CHECK(setup_field_by_letter('r') == nullptr);  // a measurement, not a setup field
    CHECK_NOTHROW(validate(SlabSetup{}, "here"));
}

TEST_CASE("port areas are (d_port / (2 d_sphere))^2 of the sphere", "[iad]") {
    SlabSetup s;
    s.r_sphere_mm = 100.0;
    s.r_sample_port_mm = 20.0;
    s.r_entrance_port_mm = 10.0;
    s.r_detector_port_mm = 0.0;
    const auto p = s.r_ports();
    CHECK(p.sample == Approx(0.01));
    CHECK(p.third == Approx(0.0025));
    CHECK(p.wall == Approx(1.0 - 0.0125));
}

TEST_CASE("a setup outside its ranges is refused naming the field, value and range", "[iad]") {
    SlabSetup s;
    s.sample_index = 0.5;
    CHECK_THROWS_WITH(validate(s, "f.rxt:3"), Catch::Contains("f.rxt:3: sample_index = 0.5 is outside [1, 4]"));
    s = {};
    s.spheres = 1.5;
    CHECK_THROWS_WITH(validate(s, "x"), Catch::Contains("spheres = 1.5 is not one of 0, 1, 2"));
    s = {};
    s.r_baffle = 0.5;
    CHECK_THROWS_WITH(validate(s, "x"), Catch::Contains("r_baffle = 0.5 is not one of 0, 1"));
    s = {};
    s.spheres = 1.0;
    s.r_sample_port_mm = 2.0 * s.r_sphere_mm;
    CHECK_THROWS_WITH(validate(s, "x"), Catch::Contains("the reflection sphere's ports cover"));
    s = {};
    s.r_standard = 0.0;
    CHECK_THROWS_WITH(validate(s, "x"), Catch::Contains("r_standard = 0 is outside (0, 1]"));
}

TEST_CASE("every setup field and result field is documented in docs/IAD.md", "[iad]") {
    std::ifstream in(std::string(SKINSPEC_TEST_REFERENCE_DIR) + "/../../docs/IAD.md");
    const std::string doc{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    REQUIRE_FALSE(doc.empty());
    for (const auto& f : setup_fields()) CHECK(doc.find(std::string(f.key)) != std::string::npos);
    for (const auto& f : iad_result_fields()) CHECK(doc.find(std::string(f.key)) != std::string::npos);
}
