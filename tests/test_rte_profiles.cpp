#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "materials/material_file.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/input_error.hpp"
#include "transport/rte/rte_profiles.hpp"

using namespace skinspec;

namespace {

std::vector<double> radii(std::size_t n, double step) {
    std::vector<double> r;
    for (std::size_t i = 0; i < n; ++i) r.push_back(static_cast<double>(i) * step);
    return r;
}

}  // namespace

TEST_CASE("the walk's R(r) rings add up to its whole-plane diffuse reflectance", "[rte_profiles]") {
    // Energy conservation of the tally: sum_i R(r_i) * area of the ring centred on r_i (disc of radius h/2 at 0)
    // over radii far beyond the light's reach equals the diffuse R counted photon by photon.
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const double h = 0.05;
    const auto r = radii(401, h);  // 0-20 mm
    const auto p = solve_rte_profiles(stack, WavelengthGrid::list({650.0}), r, true, RteProfileOptions{100'000, 3});
    REQUIRE(p.channels.size() == 1);
    const auto& c = p.channels.front();
    double sum = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const double area = i == 0 ? std::numbers::pi * 0.25 * h * h : 2.0 * std::numbers::pi * r[i] * h;
        sum += area * c.reflectance_per_mm2[i];
        variance += area * area * c.reflectance_stderr_per_mm2[i] * c.reflectance_stderr_per_mm2[i];
        CHECK(c.reflectance_stderr_per_mm2[i] >= 0.0);
    }
    CHECK(std::abs(sum - c.total_reflectance) < 4.0 * std::sqrt(variance) + 1e-4);
    CHECK(c.transmittance_per_mm2.size() == r.size());
    // Monotone decrease well away from the source, as every diffusing medium's.
    CHECK(c.reflectance_per_mm2[20] > c.reflectance_per_mm2[40]);
    CHECK(c.reflectance_per_mm2[40] > c.reflectance_per_mm2[80]);
}

TEST_CASE("the walk's profiles need rings, deterministic solvers refuse ray counts", "[rte_profiles]") {
    const auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto grid = WavelengthGrid::list({550.0});
    CHECK_THROWS_WITH(solve_rte_profiles(stack, grid, std::vector<double>{0.1, 0.2, 0.3}, false, {}), Catch::Contains("must start at 0 mm with equal steps"));
    CHECK_THROWS_WITH(solve_rte_profiles(stack, grid, std::vector<double>{0.0, 0.1, 0.3}, false, {}), Catch::Contains("radius 0.3 mm is not 2 x 0.1 mm"));
    CHECK_THROWS_WITH(solve_rte_profiles(stack, grid, std::vector<double>{0.0}, false, {}), Catch::Contains("at least two radii"));
    ProfileRequest request{grid, {0.0, 0.5, 1.0}, false, {}, std::uint64_t{1000}, 1};
    CHECK_THROWS_WITH(solve_profiles(find_solver("multipole"), Material(stack), request), Catch::Contains("'multipole' is deterministic: it takes no ray count"));
    CHECK(solve_profiles(find_solver("rte"), Material(stack), request).channels.front().reflectance_stderr_per_mm2.size() == 3);
}
