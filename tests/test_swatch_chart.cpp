#include <catch2/catch.hpp>

#include "appearance/swatch_chart.hpp"
#include "solvers/color_precision.hpp"
#include "spectral/ciede2000.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/text_fields.hpp"
#include "thread_work_share.hpp"

#include <cmath>
#include "spectral/input_error.hpp"

using namespace skinspec;

TEST_CASE("sweeps parse and space their values evenly", "[swatch_chart]") {
    const auto s = parse_sweep("epidermis.melanosome_fraction=0.01:0.42:8");
    CHECK(s.field == "epidermis.melanosome_fraction");
    const auto v = s.values();
    REQUIRE(v.size() == 8);
    CHECK(v.front() == 0.01);
    CHECK(v.back() == Approx(0.42));
    CHECK(parse_sweep("dermis.blood_fraction=0.02:0.02:1").values() == std::vector<double>{0.02});
}

TEST_CASE("bad sweeps are input errors", "[swatch_chart]") {
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.1:5"), Catch::Contains("empty range"));
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.2:-3"), Catch::Contains("STEPS must be a whole number in [1, 1000]"));
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.2:2.5"), Catch::Contains("STEPS must be a whole number"));
    CHECK_THROWS_WITH(parse_sweep("epidermis.melanosome_fraction=0.1:0.2"), Catch::Contains("FIELD=FIRST:LAST:STEPS"));
    CHECK_THROWS_WITH(parse_sweep("0.1:0.2:3"), Catch::Contains("FIELD=FIRST:LAST:STEPS"));
    CHECK_THROWS_WITH(parse_sweep("x=a:0.2:3"), Catch::Contains("finite numbers"));
    SwatchRequest r;
    r.sweeps = {parse_sweep("epidermis.melanin=0.1:0.2:2")};
    CHECK_THROWS_WITH(compute_swatch(r), Catch::Contains("unknown key 'epidermis.melanin'"));
    r.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.5:1.5:2")};
    CHECK_THROWS_WITH(compute_swatch(r), Catch::Contains("= 1.5 is outside [0, 1]"));
}

TEST_CASE("the colour wavelengths follow the stated rule", "[swatch_chart]") {
    CHECK(swatch_wavelengths(0.3).size() == 81);
    CHECK(swatch_wavelengths(2.0).size() == 41);
    CHECK(swatch_wavelengths(0.3).front() == 380.0);
    CHECK(swatch_wavelengths(0.3).back() == 780.0);
}

TEST_CASE("a perfect white reflector is exactly the illuminant's white", "[swatch_chart]") {
    SwatchRequest r;
    r.material = SKINSPEC_TEST_INPUT_DIR "/white_reflector.toml";
    const auto chart = compute_swatch(r);
    REQUIRE(chart.patches.size() == 1);
    const auto& p = chart.patches[0];
    CHECK(p.xyz.X == Approx(chart.white.X).epsilon(1e-12));
    CHECK(p.xyz.Y == Approx(1.0).epsilon(1e-12));
    CHECK(p.lab.L == Approx(100.0).epsilon(1e-10));
    CHECK(p.uncertainty.delta_e2000 == 0.0);
}

TEST_CASE("patches meet the colour tolerance and order by pigmentation", "[swatch_chart]") {
    SwatchRequest r;
    r.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.02:0.3:3")};
    r.delta_e = 1.0;
    const auto chart = compute_swatch(r);
    REQUIRE(chart.patches.size() == 3);
    CHECK(chart.columns == 3);
    CHECK(chart.rows == 1);
    for (const auto& p : chart.patches) {
        CHECK(p.uncertainty.delta_e2000 <= 1.0 * 1.15);  // the allocation aims at the tolerance from estimated variances
        CHECK(p.converged);
    }
    CHECK(chart.patches[0].lab.L > chart.patches[1].lab.L + 3.0);
    CHECK(chart.patches[1].lab.L > chart.patches[2].lab.L + 3.0);
}

TEST_CASE("a chart shared among processes equals the one-process chart bit for bit", "[swatch_chart]") {
    SwatchRequest r;
    r.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.01:0.4:5:log"), parse_sweep("dermis.blood_fraction=0.002:0.05:3")};
    r.delta_e = 2.0;
    r.patches_per_sweep = 4;  // 15 patches in 4 chunks
    const auto one = compute_swatch(r);
    for (const std::size_t ranks : {2u, 3u}) {
        const auto shared = testing::run_shared<SwatchChart>(ranks, [&](const WorkShare& share) {
            auto request = r;
            request.work_share = &share;
            return compute_swatch(request);
        });
        REQUIRE(shared.patches.size() == one.patches.size());
        for (std::size_t i = 0; i < one.patches.size(); ++i) {
            CHECK(shared.patches[i].reflectance == one.patches[i].reflectance);
            CHECK(shared.patches[i].reflectance_stderr == one.patches[i].reflectance_stderr);
            CHECK(shared.patches[i].rays == one.patches[i].rays);
            CHECK(shared.patches[i].xyz.Y == one.patches[i].xyz.Y);
        }
        CHECK(shared.settings == one.settings);
        CHECK_FALSE(shared.partial);
    }
}

TEST_CASE("a look-up texel has the colour of its material's own spectrum, within the uncertainties", "[swatch_chart]") {
    // The texel at the preset's melanin, dermal blood set to one value (the texture's blood axis sets both layers).
    SwatchRequest r;
    r.overrides = {{"dermis.blood_fraction", "0.012"}};
    r.sweeps = {parse_sweep("epidermis.melanosome_fraction=0.042:0.062:3"), parse_sweep("dermis.blood_fraction=0.011:0.013:3")};
    r.geometry = MeasurementGeometry::sce;
    r.delta_e = 0.5;
    const auto chart = compute_swatch(r);
    const auto& texel = chart.patches[4];  // column 1, row 1: 0.052, 0.012
    REQUIRE(texel.parameters[0] == Approx(0.052));
    REQUIRE(texel.parameters[1] == Approx(0.012));
    // The same material through solve_spectrum, on its own random streams, to a tighter colour target.
    SolverRequest request;
    request.spectral.wavelengths = chart.wavelengths;
    request.spectral.geometry = MeasurementGeometry::sce;
    request.spectral.seed = 7;
    const TristimulusWeights weights(chart.wavelengths.nm(), IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
    request.spectral.stderr_targets = color_stderr_targets(weights, 0.2);
    request.spectral.max_rays_per_wavelength = 1'000'000;
    const auto direct = solve_spectrum(find_solver("biospec"), load_material("biospec-moderately", {{"epidermis.melanosome_fraction", format_number(texel.parameters[0])},
                                                                                         {"dermis.blood_fraction", format_number(texel.parameters[1])}}),
                                       request);
    std::vector<double> rd, sd;
    for (const auto& w : direct.wavelengths) {
        rd.push_back(w.reflectance.value);
        sd.push_back(w.reflectance.stderr);
    }
    const auto lab = xyz_to_lab(weights.integrate(rd), weights.white());
    const double combined = std::hypot(texel.uncertainty.delta_e2000, ciede2000_uncertainty(weights, rd, sd));
    CHECK(ciede2000(texel.lab, lab) < 3.0 * combined);
}
