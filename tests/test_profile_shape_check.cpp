#include <catch2/catch.hpp>

#include <cmath>

#include "materials/material_file.hpp"
#include "solvers/profile_shape_check.hpp"

using namespace skinspec;

TEST_CASE("the shape is checked at the wavelengths nearest 450, 550 and 650 nm, each once", "[profile_shape_check]") {
    CHECK(profile_shape_wavelengths(WavelengthGrid::range(400.0, 700.0, 10.0)) == std::vector<double>{450.0, 550.0, 650.0});
    CHECK(profile_shape_wavelengths(WavelengthGrid::range(380.0, 780.0, 25.0)) == std::vector<double>{455.0, 555.0, 655.0});
    CHECK(profile_shape_wavelengths(WavelengthGrid::list({550.0})) == std::vector<double>{550.0});
    CHECK(profile_shape_wavelengths(WavelengthGrid::list({460.0, 900.0})) == std::vector<double>{460.0});
}

TEST_CASE("only a deterministic solver's profiles of a layered material are checked", "[profile_shape_check]") {
    const auto skin = load_material("biospec-moderately");
    const auto bands = load_material("jensen2001-skin1");
    CHECK(profile_shape_checked(find_solver("multipole"), skin));
    CHECK(profile_shape_checked(find_solver("matched-multipole"), skin));
    CHECK_FALSE(profile_shape_checked(find_solver("rte"), skin));      // the reference itself
    CHECK_FALSE(profile_shape_checked(find_solver("biospec"), skin));  // no profiles
    CHECK_FALSE(profile_shape_checked(find_solver("multipole"), bands));
}

TEST_CASE("where diffusion holds, the check finds the walk's shape: a thick, weakly absorbing dermis at 650 nm", "[profile_shape_check]") {
    // One 1 cm dermis (the thin layers 10 nm), its volumetric mu_s from the same reduced scattering the diffusion
    // solvers read (mu_s' ~ 20 /cm against mu_a ~ 0.35 /cm: reduced albedo 0.98, 20 transport mean free paths deep).
    // Diffusion is then accurate beyond about a transport mean free path (Farrell, Patterson & Wilson 1992, Med Phys
    // 19:879, Fig. 3) and misplaces only the light within it: the shares of R within a radius differ by about 0.1
    // (0.08-0.14 at 550 and 650 nm with g 0.8 or 0, either sign); with the thin layers of skin by 0.3-0.6.
    const auto slab = load_material("biospec-moderately", {{"stratum_corneum.thickness_cm", "1e-6"},
                                                           {"epidermis.thickness_cm", "1e-6"},
                                                           {"papillary_dermis.thickness_cm", "1e-6"},
                                                           {"reticular_dermis.thickness_cm", "1"},
                                                           {"dermis.volumetric_scattering", "from_reduced_scattering"},
                                                           {"model.volumetric_matched_to_biospec", "false"}});
    const auto check = check_profile_shape(find_solver("multipole"), slab, WavelengthGrid::list({650.0}), {}, 100'000);
    REQUIRE(check.errors.size() == 1);
    const auto& e = check.errors.front();
    INFO("largest share difference " << e.largest_share_difference << " at " << e.at_radius_mm << " mm");
    CHECK(std::abs(e.largest_share_difference) < 0.15);
    CHECK(e.walk_share_stderr > 0.0);
    CHECK(e.walk_share_stderr < 0.01);
    CHECK_FALSE(check.stopped);

    const auto skin = check_profile_shape(find_solver("multipole"), load_material("biospec-moderately"), WavelengthGrid::list({650.0}), {}, 100'000);
    CHECK(std::abs(skin.errors.front().largest_share_difference) > 0.3);
    // The shares are of one whole: within 0.1 mm and beyond 1 mm never add to more than 1.
    CHECK(skin.errors.front().walk_share_within_0_1_mm + skin.errors.front().walk_share_beyond_1_mm <= 1.0);
}
