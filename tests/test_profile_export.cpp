#include <catch2/catch.hpp>

#include <cmath>

#include "appearance/profile_export.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

// A member whose two channels ("a", "b": bands) are exact sums of Gaussians with the variances `v` and weights `w`.
SpectralProfiles gaussian_member(const std::vector<double>& v, const std::vector<std::vector<double>>& w) {
    SpectralProfiles p;
    p.material = "synthetic";
    p.model = "test";
    for (int i = 0; i <= 500; ++i) p.radii_mm.push_back(0.01 * i);
    for (std::size_t c = 0; c < w.size(); ++c) {
        ChannelProfile channel;
        channel.label = c == 0 ? "a" : "b";
        for (const double r : p.radii_mm) {
            double value = 0.0;
            for (std::size_t i = 0; i < v.size(); ++i) value += w[c][i] * gaussian_2d(v[i], r);
            channel.reflectance_per_mm2.push_back(value);
        }
        for (const double wi : w[c]) channel.total_reflectance += wi;
        p.channels.push_back(channel);
    }
    return p;
}

}  // namespace

TEST_CASE("a grid's corners and middle member", "[profile_export]") {
    CHECK(grid_corners_and_middle({16, 16}) == std::vector<std::size_t>{0, 15, 136, 240, 255});
    CHECK(grid_corners_and_middle({5}) == std::vector<std::size_t>{0, 2, 4});
    CHECK(grid_corners_and_middle({1}) == std::vector<std::size_t>{0});
    CHECK(grid_corners_and_middle({2, 1}) == std::vector<std::size_t>{0, 1});
}

TEST_CASE("a grid shares one set of variances: members made of them get their own weights back", "[profile_export]") {
    // Every member is an exact sum of the same three Gaussians with its own weights: the shared fit must reproduce
    // each (an analytic reference: the members' own construction).
    const std::vector<double> v{0.001, 0.02, 0.3};
    std::vector<SpectralProfiles> members;
    std::vector<std::vector<std::vector<double>>> weights;
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 3; ++i) {
            weights.push_back({{0.1 + 0.1 * i, 0.2, 0.05 + 0.1 * j}, {0.3, 0.05 * (i + 1), 0.2 - 0.05 * j}});
            members.push_back(gaussian_member(v, weights.back()));
        }
    }
    ProfileExportRequest request;
    request.gaussians = 3;
    const auto grid = fit_profile_export_grid(members, {{"x", {1, 2, 3}}, {"y", {1, 2}}}, true, request);
    REQUIRE(grid.members.size() == 6);
    CHECK(grid.variances_fitted_to == std::vector<std::size_t>{0, 2, 3, 4, 5});
    for (std::size_t m = 0; m < 6; ++m) {
        CHECK(grid.members[m].fit.variances_mm2 == grid.members.front().fit.variances_mm2);
        for (std::size_t c = 0; c < 2; ++c) {
            CHECK(grid.members[m].fit.relative_l2_error[c] < 2e-3);
            double total = 0.0;
            for (const double w : weights[m][c]) total += w;
            CHECK(grid.members[m].fit.fitted_total[c] == Approx(total).epsilon(2e-3));
        }
    }
    for (std::size_t i = 0; i < 3; ++i) CHECK(grid.members.front().fit.variances_mm2[i] == Approx(v[i]).epsilon(0.05));
    const auto json = profile_export_grid_json(grid);
    CHECK(json["members"].size() == 6);
    CHECK(json["members"][4]["values"]["x"] == 2.0);
    CHECK(json["members"][4]["values"]["y"] == 2.0);
    const auto table = profile_export_grid_table_csv(grid);
    CHECK(table.find("x,y,channel,weight_1,weight_2,weight_3,total_reflectance_fit,profile_relative_l2_error\n") != std::string::npos);
    CHECK_THROWS_WITH(fit_profile_export_grid(members, {{"x", {1, 2}}}, true, request), Catch::Contains("6 members' profiles for a grid of 2"));
}
