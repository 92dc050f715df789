#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <hwy/targets.h>

#include "forced_target.hpp"

#include "transport/fresnel.hpp"
#include "transport/rte/rte_model.hpp"
#include "transport/rte/rte_packet.hpp"

using namespace skinspec;

namespace {

using testing::ForcedTarget;

// One layer between `n_above` and `n_below`, free paths with coefficient mu (1/cm), HG g.
RtePacketModel one_layer(float mu, float g, float thickness_cm, float n, float n_above, float n_below, bool split) {
    RtePacketModel m;
    m.layers = 1;
    m.phase = {static_cast<std::int32_t>(mu > 0.0f ? PacketPhase::henyey_greenstein : PacketPhase::none)};
    m.mu_per_cm = {mu};
    m.top_cm = {0.0f};
    m.bottom_cm = {thickness_cm};
    m.g = {g};
    m.g2 = {0.0f};
    m.first_term_weight = {1.0f};
    m.table_offset = {0};
    m.table_size = {1};
    m.eta_down = {n / n_below};
    m.inverse_eta_down = {n_below / n};
    m.eta_up = {n / n_above};
    m.inverse_eta_up = {n_above / n};
    m.split = split;
    m.max_steps = 1000;
    m.pad();
    return m;
}

RteRequest slab(std::uint64_t photons) {
    RteRequest r;
    r.stack.layers = {{1.4, 1.0, 100.0, 0.1, PhaseFunction::henyey_greenstein(0.9)}};
    r.photons = photons;
    r.grid = RteGrid{0.01, 0.01, 10, 10, 3};
    return r;
}

}  // namespace

TEST_CASE("every instruction set the machine has walks the same photons to single-precision rounding", "[rte_packet]") {
    // A photon's path depends only on its key (its own lane stream); the instruction sets differ only in the rounding
    // of their vector mathematics, so their results agree far inside the Monte Carlo error, and energy is conserved.
    const auto targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    std::vector<RteResult> results;
    for (const auto target : targets) {
        ForcedTarget forced(target);
        CHECK(std::string(rte_packet_target()) == hwy::TargetName(target));
        results.push_back(solve_rte(slab(20'000)));
    }
    for (std::size_t t = 0; t < results.size(); ++t) {
        INFO(hwy::TargetName(targets[t]) << " against " << hwy::TargetName(targets.front()));
        const auto& a = results.front();
        const auto& b = results[t];
        CHECK(std::abs(a.diffuse_reflectance.value - b.diffuse_reflectance.value) < 0.1 * a.diffuse_reflectance.stderr);
        CHECK(std::abs(a.transmittance.value - b.transmittance.value) < 0.1 * a.transmittance.stderr);
        CHECK(b.specular_reflectance.value + b.diffuse_reflectance.value + b.transmittance.value + b.absorbed.value == Approx(1.0).margin(1e-12));
    }
}

TEST_CASE("free paths are exponential with mean 1 / mu (Wang, Jacques & Zheng 1995 Eq. 3.7)", "[rte_packet]") {
    // An isotropic medium far thicker than a free path: every segment ends in an interaction; the segment lengths of
    // an exponential distribution have mean 1/mu and standard deviation 1/mu.
    const float mu = 10.0f;
    const auto model = one_layer(mu, 0.0f, 1e6f, 1.0f, 1.0f, 1.0f, false);
    RtePacket packet;
    for (std::size_t lane = 0; lane < RtePacket::lanes; ++lane) {
        packet.launch(lane, lane + 1, 0.0f, 0.0f, 1.0f);
        packet.z[lane] = 5e5f;  // deep inside
    }
    double sum = 0.0, sum_sq = 0.0;
    std::size_t count = 0;
    for (int step = 0; step < 300; ++step) {
        step_rte_packet(model, packet);
        for (std::size_t lane = 0; lane < RtePacket::lanes; ++lane) {
            REQUIRE(packet.event_bits[lane] == rte_interaction);
            sum += packet.segment_cm[lane];
            sum_sq += packet.segment_cm[lane] * packet.segment_cm[lane];
            ++count;
        }
    }
    const double mean = sum / count;
    const double sd = std::sqrt(sum_sq / count - mean * mean);
    CHECK(std::abs(mean - 1.0 / mu) < 4.0 * (1.0 / mu) / std::sqrt(count));
    CHECK(sd == Approx(1.0 / mu).epsilon(0.03));
}

TEST_CASE("a boundary reflects and refracts by Fresnel and Snell, split boundaries keep the reflected part", "[rte_packet]") {
    // Without scattering a photon runs straight to the boundary: at normal incidence from n = 1.5 into air a split
    // boundary keeps R = ((n - 1) / (n + 1))^2 and the escaping ray leaves along the normal; at 60 degrees (beyond
    // the critical angle, 41.8 degrees) it is totally reflected and nothing escapes.
    const auto model = one_layer(0.0f, 0.0f, 0.1f, 1.5f, 1.0f, 1.0f, true);
    RtePacket packet;
    const float s60 = std::sin(60.0f * 3.14159265f / 180.0f), c60 = std::cos(60.0f * 3.14159265f / 180.0f);
    packet.launch(0, 1, 0.0f, 0.0f, 1.0f);
    packet.launch(1, 2, s60, 0.0f, c60);
    const std::uint64_t flags = step_rte_packet(model, packet);
    CHECK(flags == 1u);
    CHECK(packet.event_bits[0] == rte_left_bottom);
    CHECK(packet.segment_cm[0] == Approx(0.1));
    CHECK(packet.kept[0] == Approx(fresnel_reflectance(1.0, 1.5, 1.0)).epsilon(1e-6));
    CHECK(packet.kept[0] == Approx(0.04).epsilon(1e-6));
    CHECK(packet.exit_cos[0] == Approx(1.0));
    CHECK(packet.dz[0] == -1.0f);  // the kept part goes back up
    CHECK(packet.event_bits[1] == 0);
    CHECK(packet.dz[1] == Approx(-c60));
    CHECK(packet.segment_cm[1] == Approx(0.1 / c60));
    // A random boundary at 30 degrees from n = 1.5 into n = 1.2: Snell's cos of the refracted ray in the next layer.
    RtePacketModel two = one_layer(0.0f, 0.0f, 0.1f, 1.5f, 1.0f, 1.2f, false);
    RtePacket many;
    const double c30 = std::cos(30.0 * 3.14159265358979 / 180.0), s30 = std::sin(30.0 * 3.14159265358979 / 180.0);
    std::size_t escaped = 0;
    for (std::size_t lane = 0; lane < RtePacket::lanes; ++lane) many.launch(lane, 100 + lane, static_cast<float>(s30), 0.0f, static_cast<float>(c30));
    step_rte_packet(two, many);
    const double cos_t = std::sqrt(1.0 - 1.5 * 1.5 / (1.2 * 1.2) * s30 * s30);
    for (std::size_t lane = 0; lane < RtePacket::lanes; ++lane) {
        if (many.event_bits[lane] == rte_left_bottom) {
            ++escaped;
            CHECK(many.exit_cos[lane] == Approx(cos_t).epsilon(1e-6));
            CHECK(many.kept[lane] == 0.0f);
        } else {
            CHECK(many.dz[lane] == Approx(-c30).epsilon(1e-6));
        }
    }
    // R(30 deg, 1.5 -> 1.2) = 0.0127: nearly every one of the 64 escapes.
    CHECK(escaped >= 60);
}

TEST_CASE("the step limit and its range", "[rte_packet]") {
    auto r = slab(10);
    r.max_steps_per_photon = 3'000'000'000ULL;
    CHECK_THROWS_WITH(solve_rte(r), "maximum steps per photon 3000000000 is outside [1, 2147483647]");
    r.max_steps_per_photon = 0;
    CHECK_THROWS_WITH(solve_rte(r), "maximum steps per photon 0 is outside [1, 2147483647]");
}
