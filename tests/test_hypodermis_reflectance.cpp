#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/gauss_quadrature.hpp"
#include "transport/adding_doubling/hypodermis_reflectance.hpp"

using namespace skinspec;

namespace {

// Chandrasekhar's H-function of isotropic scattering with albedo w (Radiative Transfer 1960, ch. V, Eq. 5.(11) in the
// form 1 / H(mu) = sqrt(1 - w) + (w / 2) int_0^1 mu' H(mu') / (mu + mu') dmu', iterated to convergence), and the
// diffuse (Lambertian-incidence) reflectance of the semi-infinite medium it gives: 1 - 2 sqrt(1 - w) int_0^1 H mu dmu.
double isotropic_diffuse_reflectance(double w) {
    const auto rule = gauss_legendre(96, 0.0, 1.0);
    const auto& mu = rule.nodes;
    std::vector<double> h(mu.size(), 1.0);
    for (int iteration = 0; iteration < 2000; ++iteration) {
        std::vector<double> next(mu.size());
        for (std::size_t i = 0; i < mu.size(); ++i) {
            double integral = 0.0;
            for (std::size_t j = 0; j < mu.size(); ++j) integral += rule.weights[j] * mu[j] * h[j] / (mu[i] + mu[j]);
            next[i] = 1.0 / (std::sqrt(1.0 - w) + 0.5 * w * integral);
        }
        h = next;
    }
    double first_moment = 0.0;
    for (std::size_t i = 0; i < mu.size(); ++i) first_moment += rule.weights[i] * h[i] * mu[i];
    return 1.0 - 2.0 * std::sqrt(1.0 - w) * first_moment;
}

}  // namespace

TEST_CASE("the semi-infinite diffuse reflectance of isotropic scatterers is Chandrasekhar's, from his H-function", "[hypodermis_reflectance]") {
    for (const double w : {0.3, 0.9, 0.99}) {
        INFO("albedo " << w);
        CHECK(semi_infinite_diffuse_reflectance(1.0 - w, w, 0.0) == Approx(isotropic_diffuse_reflectance(w)).margin(2e-4));
    }
    // Without absorption everything returns.
    CHECK(semi_infinite_diffuse_reflectance(0.0, 10.0, 0.8) == Approx(1.0).margin(1e-4));
}

TEST_CASE("the measured hypodermis reflects part of the light, over its measured range only", "[hypodermis_reflectance]") {
    for (double nm = 380.0; nm <= 1600.0; nm += 20.0) {
        const double rho = hypodermis_reflectance(nm);
        INFO(nm << " nm: " << rho);
        CHECK(rho > 0.2);
        CHECK(rho < 0.7);
    }
    // The lipid and water bands pull it down (Salomatina's mu_a: 1200 and 1450 nm).
    CHECK(hypodermis_reflectance(1200.0) < hypodermis_reflectance(1100.0) - 0.05);
    CHECK(hypodermis_reflectance(1450.0) < hypodermis_reflectance(1300.0) - 0.1);
    for (const double nm : {370.0, 1610.0, 2000.0}) {
        CHECK_THROWS_WITH(hypodermis_reflectance(nm), Catch::Contains("bottom.boundary = hypodermis") && Catch::Contains("covers 373.7") &&
                                                          Catch::Contains("use diffuse_reflector or exit"));
    }
    auto stack = std::get<LayerStack>(load_material("biospec-lightly"));
    CHECK(bottom_reflectance(stack, 550.0) == 1.0);
    stack.bottom = BottomBoundary::exit;
    CHECK(bottom_reflectance(stack, 550.0) == 0.0);
    stack.bottom = BottomBoundary::hypodermis;
    CHECK(bottom_reflectance(stack, 550.0) == hypodermis_reflectance(550.0));
}
