#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <hwy/targets.h>

#include "forced_target.hpp"

#include "transport/biospec/biospec_packet.hpp"
#include "transport/biospec/biospec_solver.hpp"
#include "materials/material_file.hpp"

using namespace skinspec;

namespace {

using testing::ForcedTarget;

SpectralRequest request(std::uint64_t rays) {
    SpectralRequest r;
    r.wavelengths = WavelengthGrid::list({450.0, 550.0, 650.0});
    r.quantities = Quantities{true, true, true, false};
    r.max_rays_per_wavelength = rays;
    return r;
}

}  // namespace

TEST_CASE("every instruction set the machine has walks the same rays to single-precision rounding", "[biospec_packet]") {
    // A ray's path depends only on its key (its own lane stream); the instruction sets differ only in the rounding
    // of their vector mathematics, so their results agree far inside the Monte Carlo error, and energy is conserved.
    auto stack = std::get<LayerStack>(load_material("biospec-moderately"));
    const auto targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    std::vector<SpectralResult> results;
    for (const auto target : targets) {
        ForcedTarget forced(target);
        INFO("instruction set " << hwy::TargetName(target));
        CHECK(std::string(biospec_packet_target()) == hwy::TargetName(target));
        results.push_back(solve_biospec(stack, request(20'000)));
    }
    for (std::size_t t = 1; t < results.size(); ++t) {
        INFO(hwy::TargetName(targets[t]) << " against " << hwy::TargetName(targets.front()));
        for (std::size_t w = 0; w < results[t].wavelengths.size(); ++w) {
            const auto& a = results.front().wavelengths[w];
            const auto& b = results[t].wavelengths[w];
            CHECK(std::abs(a.reflectance.value - b.reflectance.value) < 0.1 * a.reflectance.stderr);
            CHECK(std::abs(a.transmittance.value - b.transmittance.value) < 0.1 * a.reflectance.stderr + 1e-12);
            double sum = b.reflectance.value + b.transmittance.value + b.absorptance_surface.value;
            for (const auto& layer : b.absorptance_layers) sum += layer.value;
            CHECK(sum == Approx(1.0).margin(1e-12));
        }
    }
}

TEST_CASE("a lane's stream is seeded from its ray key alone and never all zero", "[biospec_packet]") {
    BiospecPacket a(1), b(1);
    a.seed_lane(3, 42);
    b.seed_lane(17, 42);
    for (std::size_t i = 0; i < 4; ++i) CHECK(a.rng[i][3] == b.rng[i][17]);
    a.seed_lane(4, 43);
    CHECK((a.rng[0][3] != a.rng[0][4] || a.rng[1][3] != a.rng[1][4]));
    for (std::uint64_t key = 0; key < 1000; ++key) {
        a.seed_lane(0, key);
        CHECK((a.rng[0][0] | a.rng[1][0] | a.rng[2][0] | a.rng[3][0]) != 0u);
    }
}
