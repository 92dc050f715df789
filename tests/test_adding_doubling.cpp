#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "formats/adding_doubling_reference.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/gauss_quadrature.hpp"
#include "transport/adding_doubling/phase_moments.hpp"
#include "transport/rte/rte_model.hpp"
#include "exponential_integral.hpp"

using namespace skinspec;

TEST_CASE("Gauss-Legendre and Gauss-Radau rules match their closed forms", "[adding_doubling]") {
    // 3-point Radau on [-1, 1] with -1 fixed (Abramowitz & Stegun 25.4.31): nodes -1, (1 -+ sqrt 6) / 5.
    const auto radau = gauss_radau(3, -1.0, 1.0, -1.0);
    CHECK(radau.nodes[0] == -1.0);
    CHECK(radau.nodes[1] == Approx((1.0 - std::sqrt(6.0)) / 5.0).epsilon(1e-12));
    CHECK(radau.nodes[2] == Approx((1.0 + std::sqrt(6.0)) / 5.0).epsilon(1e-12));
    CHECK(radau.weights[0] == Approx(2.0 / 9.0).epsilon(1e-12));
    CHECK(radau.weights[1] == Approx((16.0 + std::sqrt(6.0)) / 18.0).epsilon(1e-12));
    const auto right = gauss_radau(4, 0.0, 1.0, 1.0);
    CHECK(right.nodes.back() == 1.0);
    // Exactness: n-point Gauss integrates x^(2n-1), Radau x^(2n-2).
    const auto gauss = gauss_legendre(5, 0.0, 2.0);
    double g = 0.0, r = 0.0;
    for (std::size_t i = 0; i < 5; ++i) g += gauss.weights[i] * std::pow(gauss.nodes[i], 9);
    for (std::size_t i = 0; i < 4; ++i) r += right.weights[i] * std::pow(right.nodes[i], 6);
    CHECK(g == Approx(std::pow(2.0, 10) / 10.0).epsilon(1e-12));
    CHECK(r == Approx(1.0 / 7.0).epsilon(1e-12));
}

TEST_CASE("Legendre moments of the phase functions", "[adding_doubling]") {
    const auto hg = legendre_moments(PhaseFunction::henyey_greenstein(0.8), 4);
    CHECK(hg[3] == Approx(0.512));
    PhaseFunction rayleigh;
    rayleigh.kind = PhaseFunction::Kind::rayleigh;
    const auto ray = legendre_moments(rayleigh, 4);
    CHECK(ray[1] == 0.0);
    CHECK(ray[2] == Approx(0.1));  // <P_2> of 3/8 (1 + mu^2)
    // A tabulated profile: the moments are the means of P_l over the table's entries (closed forms of P_2, P_3).
    const auto table = std::make_shared<const InverseCdfTable>(MeasuredProfile::stratum_corneum().inverse_table(450.0));
    const auto chi = legendre_moments(PhaseFunction{PhaseFunction::Kind::tabulated, 0.0, 0.0, 1.0, table}, 4);
    double p1 = 0.0, p2 = 0.0, p3 = 0.0;
    for (std::size_t i = 0; i < table->size(); ++i) {
        const double x = table->cos_theta(i);
        p1 += x;
        p2 += (3.0 * x * x - 1.0) / 2.0;
        p3 += (5.0 * x * x * x - 3.0 * x) / 2.0;
    }
    const double count = static_cast<double>(table->size());
    CHECK(chi[0] == Approx(1.0).epsilon(1e-14));
    CHECK(chi[1] == Approx(p1 / count).epsilon(1e-12));
    CHECK(chi[2] == Approx(p2 / count).epsilon(1e-12));
    CHECK(chi[3] == Approx(p3 / count).epsilon(1e-12));
}

namespace {

RteStack one_layer(double n, double mu_a, double mu_s, double g, double d) {
    RteStack s;
    s.layers.push_back({n, mu_a, mu_s, d, PhaseFunction::henyey_greenstein(g)});
    return s;
}

// A stress case (no accuracy check): every value finite and in [0, 1], R + T + A = 1 to 1e-8.
AdResult solve_stressed(const RteStack& stack, double angle_deg) {
    AdOptions o;
    o.accuracy_check = false;
    const auto r = solve_adding_doubling(stack, {false, angle_deg}, o);
    for (const double v : {r.specular_reflectance, r.diffuse_reflectance, r.transmittance, r.absorbed_layers[0]}) {
        CHECK(std::isfinite(v));
        CHECK(v >= -1e-9);
        CHECK(v <= 1.0 + 1e-9);
    }
    CHECK(r.specular_reflectance + r.diffuse_reflectance + r.transmittance + r.absorbed_layers[0] == Approx(1.0).margin(1e-8));
    return r;
}

}  // namespace

TEST_CASE("adding-doubling reproduces Prahl's slabs within 1e-4", "[adding_doubling]") {
    for (const auto& slab : adding_doubling_slabs()) {
        INFO("a " << slab.albedo << " b " << slab.optical_thickness << " g " << slab.g << " n " << slab.refractive_index);
        const auto r = solve_adding_doubling(slab.stack(), {});
        CHECK(r.diffuse_reflectance == Approx(slab.diffuse_reflectance).margin(1e-4));
        CHECK(r.transmittance == Approx(slab.total_transmittance).margin(1e-4));
        CHECK(r.specular_reflectance + r.diffuse_reflectance + r.transmittance + r.absorbed_layers[0] == Approx(1.0).margin(1e-9));
        // The stated accuracy (twice the change with every segment's channels doubled) covers the error against the reference.
        CHECK(std::abs(r.diffuse_reflectance - slab.diffuse_reflectance) <= r.accuracy + 5e-6);
        CHECK(std::abs(r.transmittance - slab.total_transmittance) <= r.accuracy + 5e-6);
        CHECK(r.accuracy < 2e-4);
    }
}

TEST_CASE("adding-doubling analytic limits", "[adding_doubling]") {
    // A pure absorber between matched media: Beer-Lambert at normal incidence.
    const auto clear = solve_adding_doubling(one_layer(1.0, 2.0, 0.0, 0.0, 0.5), {});
    CHECK(clear.transmittance == Approx(std::exp(-1.0)).epsilon(3e-6));  // the diamond start's (1 - h/mu)/(1 + h/mu)
    // With n 1.5 in air: T = (1 - F)^2 e^-tau / (1 - F^2 e^-2 tau), F = (0.5 / 2.5)^2 (Born & Wolf, incoherent slab).
    const double f = 0.04, e = std::exp(-1.0);
    const auto glass = solve_adding_doubling(one_layer(1.5, 2.0, 0.0, 0.0, 0.5), {});
    CHECK(glass.transmittance == Approx((1 - f) * (1 - f) * e / (1 - f * f * e * e)).epsilon(3e-6));
    CHECK(glass.specular_reflectance == Approx(f).epsilon(1e-12));
    // A clear matched layer over the Lambertian reflector returns everything.
    auto white = one_layer(1.0, 0.0, 0.0, 0.0, 0.1);
    white.bottom_reflector = true;
    CHECK(solve_adding_doubling(white, {}).diffuse_reflectance == Approx(1.0).epsilon(1e-9));
    // Conservative scattering: nothing absorbed, at any incidence and for diffuse light.
    for (const AdIncidence inc : {AdIncidence{false, 0.0}, AdIncidence{false, 60.0}, AdIncidence{true, 0.0}}) {
        const auto r = solve_adding_doubling(one_layer(1.4, 0.0, 100.0, 0.9, 0.05), inc);
        CHECK(r.absorbed_layers[0] == Approx(0.0).margin(1e-9));
        CHECK(r.specular_reflectance + r.diffuse_reflectance + r.transmittance == Approx(1.0).margin(1e-9));
    }
}

TEST_CASE("a reflector of reflectance rho under a clear absorber: R = rho e^-tau 2 E_3(tau), T = (1 - rho) e^-tau", "[adding_doubling]") {
    // Matched media: the beam reaches the reflector as e^-tau, rho of it returns as Lambertian light, which crosses
    // the layer with 2 E_3(tau) and leaves; what the reflector keeps is T (the hypodermis' share).
    for (const double rho : {0.0, 0.35, 0.9}) {
        auto stack = one_layer(1.0, 4.0, 0.0, 0.0, 0.1);
        stack.bottom_reflector = true;
        stack.bottom_reflectance = rho;
        AdOptions options;
        options.channels = 32;
        const auto r = solve_adding_doubling(stack, {}, options);
        INFO("rho " << rho);
        CHECK(r.diffuse_reflectance == Approx(rho * std::exp(-0.4) * 2.0 * skinspec::testing::exponential_integral_3(0.4)).epsilon(1e-4).margin(1e-12));
        CHECK(r.transmittance == Approx((1.0 - rho) * std::exp(-0.4)).epsilon(1e-5));
        CHECK(r.diffuse_reflectance + r.transmittance + r.absorbed_layers[0] == Approx(1.0).margin(1e-9));
    }
}

TEST_CASE("a forward delta scatters nothing, and strongly forward layers keep their depth (similarity)", "[adding_doubling]") {
    // HG with g = 1 is a delta forward: the layer is the same layer without scattering, exactly.
    for (const bool reflector : {false, true}) {
        auto delta = one_layer(1.4, 0.5, 1000.0, 1.0, 0.1), clear = one_layer(1.4, 0.5, 0.0, 0.0, 0.1);
        delta.bottom_reflector = clear.bottom_reflector = reflector;
        const auto a = solve_adding_doubling(delta, {}), b = solve_adding_doubling(clear, {});
        CHECK(a.diffuse_reflectance == Approx(b.diffuse_reflectance).margin(1e-12));
        CHECK(a.transmittance == Approx(b.transmittance).margin(1e-12));
        CHECK(a.absorbed_layers[0] == Approx(b.absorbed_layers[0]).margin(1e-12));
    }
    // The similarity relation (van de Hulst; Wyman, Patterson & Wilson 1989): as g -> 1 at fixed mu_s (1 - g), R
    // and T converge. mu_s' 20 /cm over 1.8 mm with g 0.999999 is 3.6e6 optical depths before delta-M, 173 after;
    // limiting the depth to 1e6 before the scaling made the layer 3.6x thinner (R 0.66 where g 0.9999 gives 0.56).
    const auto reduced = [](double g) {
        auto s = one_layer(1.38, 0.05, 20.0 / (1.0 - g), g, 0.18);
        s.bottom_reflector = true;
        return solve_adding_doubling(s, {}).diffuse_reflectance;
    };
    CHECK(reduced(0.999999) == Approx(reduced(0.9999)).margin(1e-3));
    CHECK(reduced(0.9999) == Approx(reduced(0.99)).margin(3e-3));
}

TEST_CASE("transparent layers (glass slides) are exact: no NaN from the channels they trap", "[adding_doubling]") {
    // A clear slide of 1.5 in air: incoherent plate, R = 2F / (1 + F), T = (1 - F) / (1 + F), F = 0.04 (Stokes). The
    // channels between s = 1 and 1.5 are totally reflected on both faces: adding them as a layer divided by zero.
    const double f = 0.04;
    for (const AdIncidence inc : {AdIncidence{false, 0.0}, AdIncidence{true, 0.0}}) {
        const auto plate = solve_adding_doubling(one_layer(1.5, 0.0, 0.0, 0.0, 0.1), inc);
        if (!inc.diffuse) {
            CHECK(plate.specular_reflectance + plate.diffuse_reflectance == Approx(2.0 * f / (1.0 + f)).epsilon(1e-12));
            CHECK(plate.transmittance == Approx((1.0 - f) / (1.0 + f)).epsilon(1e-12));
        }
        CHECK(plate.specular_reflectance + plate.diffuse_reflectance + plate.transmittance == Approx(1.0).epsilon(1e-12));
    }
    // Slides on both faces of a pure absorber of index 1.4 (b = 1): the closed form of the incoherent stack. Faces:
    // air|glass|sample, r = r1 + t1^2 r2 / (1 - r1 r2), t = t1 t2 / (1 - r1 r2); through the sample R = r + t^2 r e^-2b
    // / (1 - r^2 e^-2b), T = t^2 e^-b / (1 - r^2 e^-2b).
    const double r1 = 0.04, r2 = (0.1 / 2.9) * (0.1 / 2.9);
    const double r = r1 + (1 - r1) * (1 - r1) * r2 / (1 - r1 * r2), t = (1 - r1) * (1 - r2) / (1 - r1 * r2), e = std::exp(-1.0);
    auto slid = one_layer(1.4, 2.0, 0.0, 0.0, 0.5);
    const RteLayer slide{1.5, 0.0, 0.0, 0.1, PhaseFunction::isotropic()};
    slid.layers = {slide, slid.layers.front(), slide};
    const auto stack = solve_adding_doubling(slid, {});
    CHECK(stack.specular_reflectance + stack.diffuse_reflectance == Approx(r + t * t * r * e * e / (1 - r * r * e * e)).epsilon(1e-5));
    CHECK(stack.transmittance == Approx(t * t * e / (1 - r * r * e * e)).epsilon(3e-6));
    CHECK(stack.absorbed_layers[0] == 0.0);
    CHECK(stack.absorbed_layers[2] == 0.0);
}

TEST_CASE("adding-doubling stress: extreme layers stay finite, in [0, 1] and energy-conserving", "[adding_doubling]") {
    for (const double g : {0.0, 0.9, 0.99}) {
        for (const double albedo : {0.0, 0.5, 1.0}) {
            for (const double mfp : {1e-6, 1e-2, 1.0, 100.0, 1e3}) {
                for (const double n : {1.0, 1.4, 2.0}) {
                    for (const double angle : {0.0, 60.0, 89.9}) {
                        INFO("g " << g << " albedo " << albedo << " mfp " << mfp << " n " << n << " angle " << angle);
                        const double mu_t = 100.0;
                        auto stack = one_layer(n, mu_t * (1.0 - albedo), mu_t * albedo, g, mfp / mu_t);
                        const auto r = solve_stressed(stack, angle);
                    }
                }
            }
        }
    }
}

TEST_CASE("adding-doubling stress: the measured forward peaks as tabulated phase functions", "[adding_doubling]") {
    // The stratum corneum and epidermis profiles (g 0.95 and 0.88, a forward peak within 2.5 deg) at 302 and 546 nm.
    for (const auto* profile : {&MeasuredProfile::stratum_corneum(), &MeasuredProfile::epidermis()}) {
        for (const double nm : {302.0, 546.0}) {
            const auto table = std::make_shared<const InverseCdfTable>(profile->inverse_table(nm));
            const PhaseFunction phase{PhaseFunction::Kind::tabulated, table->mean_cos(), 0.0, 1.0, table};
            for (const double albedo : {0.0, 0.5, 1.0}) {
                for (const double mfp : {1e-6, 1e-2, 1.0, 100.0, 1e3}) {
                    for (const double angle : {0.0, 89.9}) {
                        INFO("nm " << nm << " albedo " << albedo << " mfp " << mfp << " angle " << angle);
                        RteStack stack;
                        stack.layers.push_back({1.5, 100.0 * (1.0 - albedo), 100.0 * albedo, mfp / 100.0, phase});
                        const auto r = solve_stressed(stack, angle);
                        if (albedo == 1.0) CHECK(r.absorbed_layers[0] == Approx(0.0).margin(1e-8));
                    }
                }
            }
        }
    }
}

// The measured profiles turn no light back; their truncated Legendre series rang into the backward directions, and
// adding-doubling took what rang above 0 as backscatter (the stratum corneum's profile alone, mu_s d = 1: R_d 0.0053 at
// 16 channels where the walk finds 0.00099). Independent reference: the volumetric walk, which samples the profile.
TEST_CASE("a forward-only tabulated phase reflects what the volumetric walk finds, at few channels too", "[adding_doubling]") {
    for (const auto* profile : {&MeasuredProfile::stratum_corneum(), &MeasuredProfile::epidermis()}) {
        const auto table = profile->shared_inverse_table(550.0);
        RteStack stack;
        stack.layers.push_back({1.0, 10.0, 100.0, 0.01, PhaseFunction{PhaseFunction::Kind::tabulated, table->mean_cos(), 0.0, 1.0, table}});
        RteRequest walk;
        walk.stack = stack;
        walk.photons = 2'000'000;
        const auto w = solve_rte(walk);
        const auto at24 = solve_adding_doubling(stack, AdIncidence{}, AdOptions{24, true});
        const auto at16 = solve_adding_doubling(stack, AdIncidence{}, AdOptions{16, false});
        INFO("g " << table->mean_cos() << ": walk " << w.diffuse_reflectance.value << " +- " << w.diffuse_reflectance.stderr << ", 24 channels "
                  << at24.diffuse_reflectance << " (accuracy " << at24.accuracy << "), 16 channels " << at16.diffuse_reflectance);
        CHECK(std::abs(at24.diffuse_reflectance - w.diffuse_reflectance.value) <= at24.accuracy + 4.5 * w.diffuse_reflectance.stderr);
        CHECK(std::abs(at16.diffuse_reflectance - w.diffuse_reflectance.value) < 1e-3);
    }
}

TEST_CASE("a cache shared across calls changes no bit (a sweep's unchanged layers are reused)", "[adding_doubling]") {
    // Two layers; the top one's mu_a varies as a melanin sweep's epidermis would. Through one cache (the bottom layer
    // doubled once, then reused) and each call with its own, the results are the same bits.
    AdCache shared;
    AdOptions o;
    o.accuracy_check = false;
    for (const double mu_a : {2.0, 5.0, 2.0, 9.0}) {
        RteStack s = one_layer(1.4, mu_a, 300.0, 0.8, 0.01);
        s.layers.push_back({1.4, 1.5, 200.0, 0.2, PhaseFunction::henyey_greenstein(0.85)});
        const auto reused = solve_adding_doubling(s, {false, 10.0}, o, &shared);
        const auto fresh = solve_adding_doubling(s, {false, 10.0}, o);
        CHECK(reused.diffuse_reflectance == fresh.diffuse_reflectance);
        CHECK(reused.transmittance == fresh.transmittance);
        CHECK(reused.absorbed_layers == fresh.absorbed_layers);
    }
    CHECK(shared.slabs.size() == 4);  // top at three absorptions, bottom once
}

TEST_CASE("adding-doubling refuses what it cannot solve", "[adding_doubling]") {
    CHECK_THROWS_WITH(solve_adding_doubling(one_layer(1.4, 1.0, 10.0, 0.9, 0.1), {false, 90.0}), "incidence angle 90 deg is outside [0, 90)");
    AdOptions few;
    few.channels = 2;
    CHECK_THROWS_WITH(solve_adding_doubling(one_layer(1.4, 1.0, 10.0, 0.9, 0.1), {}, few), "adding-doubling channels 2 is outside [4, 256]");
    CHECK_THROWS_AS(solve_adding_doubling(one_layer(1.4, -1.0, 10.0, 0.9, 0.1), {}), InputError);
    CHECK_THROWS_AS(solve_adding_doubling(RteStack{}, {}), InputError);
}
