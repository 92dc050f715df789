#include <catch2/catch.hpp>

#include <cmath>

#include "materials/chromophore.hpp"
#include "materials/tissue_layer.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

TissueLayer blood_only() {
    TissueLayer l;
    l.name = "blood";
    l.thickness_cm = 0.1;
    l.refractive_index = 1.4;
    l.blood_fraction = 1.0;
    l.oxygen_saturation = 1.0;
    l.bilirubin_g_per_l = 0.0;
    return l;
}

}  // namespace

TEST_CASE("whole oxygenated blood reproduces the hand-computed mu_a", "[tissue_layer]") {
    ModelOptions prahl;
    prahl.hemoglobin_molar_mass_g_per_mol = 64500.0;
    CHECK(absorption_per_cm(blood_only(), 576.0, prahl) == Approx(297.408).margin(1e-3));
}

TEST_CASE("the layer mixture weights each compartment by its volume fraction", "[tissue_layer]") {
    const ModelOptions model;
    TissueLayer epidermis;
    epidermis.name = "epidermis";
    epidermis.thickness_cm = 0.01;
    epidermis.refractive_index = 1.4;
    epidermis.melanosome_fraction = 0.1;
    epidermis.pheomelanin_mg_per_ml = 0.0;
    epidermis.carotene_g_per_l = 0.0;
    // 0.1 * 3.28 * 80 (eumelanin at 642.77 nm, no ln 10) + 0.9 * baseline(642.77).
    const double baseline = 0.244 + 85.3 * std::exp(-(642.77 - 154.0) / 66.2);
    CHECK(absorption_per_cm(epidermis, 642.77, model) == Approx(0.1 * 3.28 * 80.0 + 0.9 * baseline).epsilon(1e-4));
    // Without baseline and melanin the layer is transparent.
    ModelOptions bare = model;
    bare.baseline_absorption = false;
    epidermis.melanosome_fraction = 0.0;
    CHECK(absorption_per_cm(epidermis, 500.0, bare) == 0.0);
}

TEST_CASE("more melanin and more blood absorb more at every visible wavelength", "[tissue_layer]") {
    const ModelOptions model;
    TissueLayer l;
    l.name = "l";
    l.thickness_cm = 0.01;
    l.refractive_index = 1.4;
    l.carotene_g_per_l = 2.1e-4;
    for (double nm = 400.0; nm <= 700.0; nm += 5.0) {
        INFO(nm << " nm");
        double previous = -1.0;
        for (const double v : {0.0, 0.019, 0.052, 0.12, 0.42}) {
            l.melanosome_fraction = v;
            const double mu = absorption_per_cm(l, nm, model);
            CHECK(mu > previous);
            previous = mu;
        }
        l.melanosome_fraction = 0.0;
        previous = -1.0;
        for (const double v : {0.0, 0.002, 0.0091, 0.012, 0.05}) {
            l.blood_fraction = v;
            const double mu = absorption_per_cm(l, nm, model);
            CHECK(mu > previous);
            previous = mu;
        }
        l.blood_fraction = 0.0;
    }
}

TEST_CASE("absent chromophores are not evaluated, present ones keep their range", "[tissue_layer]") {
    TissueLayer l = blood_only();
    l.blood_fraction = 0.0;
    l.melanosome_fraction = 0.0;
    ModelOptions bare;
    bare.baseline_absorption = false;
    CHECK(absorption_per_cm(l, 2000.0, bare) == 0.0);
    l.melanosome_fraction = 0.1;
    CHECK_THROWS_WITH(absorption_per_cm(l, 2600.0, bare), Catch::Contains("eumelanin: wavelength 2600 nm"));
}

TEST_CASE("collagen Rayleigh coefficient matches the hand computation", "[tissue_layer]") {
    // Papillary dermis n = 1.36, fibres n = 1.5, f = 0.21, r = 25 nm, lambda = 500 nm:
    // beta = 8 pi^3 (eta^2 - 1)^2 / (3 N lambda^4) = 193.22 /cm (computed by hand from the spec formula).
    TissueLayer l;
    l.refractive_index = 1.36;
    CHECK(rayleigh_coefficient_per_cm(l, 500.0) == Approx(193.2236).epsilon(1e-6));
    // lambda^-4 law.
    CHECK(rayleigh_coefficient_per_cm(l, 1000.0) == Approx(193.2236 / 16.0).epsilon(1e-6));
    l.collagen_fibre_fraction = 0.0;
    CHECK(rayleigh_coefficient_per_cm(l, 500.0) == 0.0);
}

TEST_CASE("scattering names parse and print", "[tissue_layer]") {
    CHECK(parse_crossing_scattering("rayleigh_cosine", "x") == CrossingScattering::rayleigh_cosine);
    CHECK_THROWS_WITH(parse_crossing_scattering("mie", "scattering"), Catch::Contains("allowed: measured_stratum_corneum"));
    CHECK(parse_phase_function("isotropic", "x") == PhaseFunctionKind::isotropic);
    CHECK_THROWS_AS(parse_phase_function("hg2", "x"), InputError);
}

TEST_CASE("vessel packaging: Svaasand's factor, its limits, and the blood term it scales", "[tissue_layer]") {
    // C = (1 - exp(-2 mu R)) / (2 mu R) (Svaasand et al. 1995; Verkruysse et al. 1997 Eq. 6).
    CHECK(vessel_packaging_factor(100.0, 0.0) == 1.0);
    CHECK(vessel_packaging_factor(1e-6, 10.0) == Approx(1.0).epsilon(1e-8));  // optically thin vessels: no change
    // 2 mu R = 2 * 200 /cm * 25e-4 cm = 1: C = 1 - 1/e.
    CHECK(vessel_packaging_factor(200.0, 25.0) == Approx(1.0 - std::exp(-1.0)).epsilon(1e-12));
    // Optically thick vessels: C -> 1 / (2 mu R).
    CHECK(vessel_packaging_factor(3000.0, 100.0) == Approx(1.0 / 60.0).epsilon(1e-12));
    const ModelOptions model;
    auto dermis = blood_only();
    dermis.blood_fraction = 0.02;
    dermis.carotene_g_per_l = 7e-5;
    auto packaged = dermis;
    packaged.vessel_radius_um = 15.0;
    auto no_blood = dermis;
    no_blood.blood_fraction = 0.0;
    for (const double nm : {420.0, 542.0, 650.0}) {
        INFO(nm << " nm");
        const double mu_blood = absorption_per_cm(blood_only(), nm, model);
        const double background = absorption_per_cm(no_blood, nm, model) * (1.0 - 0.02);
        CHECK(absorption_per_cm(dermis, nm, model) == Approx(background + 0.02 * mu_blood).epsilon(1e-12));
        CHECK(absorption_per_cm(packaged, nm, model) ==
              Approx(background + 0.02 * vessel_packaging_factor(mu_blood, 15.0) * mu_blood).epsilon(1e-12));
    }
    // Packaging flattens the Soret band more than the red.
    const auto ratio = [&](double nm) { return absorption_per_cm(packaged, nm, model) / absorption_per_cm(dermis, nm, model); };
    CHECK(ratio(420.0) < ratio(650.0));
}

TEST_CASE("water and lipid absorb over the whole layer", "[tissue_layer]") {
    TissueLayer layer;
    layer.water_fraction = 0.65;
    ModelOptions bare;
    bare.baseline_absorption = false;
    // Segelstein's water at 1449 nm is 31.542 /cm (raw row): the layer absorbs 0.65 of it.
    CHECK(absorption_per_cm(layer, 1449.0, bare) == Approx(0.65 * 31.542).epsilon(1e-12));
    layer.lipid_fraction = 0.1;  // van Veen's fat at 930 nm: 13.10 /m
    CHECK(absorption_per_cm(layer, 930.0, bare) ==
          Approx(0.65 * chromophore(ChromophoreKind::water).table(930.0) + 0.1 * 0.131).epsilon(1e-12));
    CHECK_THROWS_WITH(absorption_per_cm(layer, 1200.0, bare), Catch::Contains("lipid: wavelength 1200 nm is outside"));
}

TEST_CASE("sieve effect: Duysens' sphere factor, its limits, and the melanin term it scales", "[tissue_layer]") {
    CHECK(sphere_packaging_factor(1000.0, 0.0) == 1.0);
    // Small spheres: C = 1 - 3x/8 + O(x^2) (the series of 3 Q / 2x), here x = 2 * 10 /cm * 0.5e-4 cm = 1e-3.
    CHECK(sphere_packaging_factor(10.0, 0.5) == Approx(1.0 - 0.375e-3 + 1e-7).epsilon(1e-10));
    // Both sides of the series switch (x = 0.01) agree.
    CHECK(sphere_packaging_factor(10.0, std::nextafter(5.0, 0.0)) == Approx(sphere_packaging_factor(10.0, 5.0)).epsilon(1e-11));
    // x = 1: Q = 1 - 2 (1 - 2/e) = 4/e - 1, C = 1.5 (4/e - 1).
    CHECK(sphere_packaging_factor(100.0, 50.0) == Approx(1.5 * (4.0 / std::exp(1.0) - 1.0)).epsilon(1e-12));
    // Opaque spheres absorb their cross-section: C -> 3 / (2x).
    CHECK(sphere_packaging_factor(1e5, 100.0) == Approx(1.5 / 2000.0).epsilon(1e-6));
    TissueLayer layer;
    layer.melanosome_fraction = 0.05;
    ModelOptions bare;
    bare.baseline_absorption = false;
    auto sieved = layer;
    sieved.melanin_cluster_radius_um = 1.0;
    for (const double nm : {350.0, 500.0, 700.0}) {
        const double mu_melanosomes = absorption_per_cm(layer, nm, bare) / 0.05;
        CHECK(absorption_per_cm(sieved, nm, bare) ==
              Approx(0.05 * sphere_packaging_factor(mu_melanosomes, 1.0) * mu_melanosomes).epsilon(1e-12));
    }
    // The sieve flattens the ultraviolet more than the red.
    const auto ratio = [&](double nm) { return absorption_per_cm(sieved, nm, bare) / absorption_per_cm(layer, nm, bare); };
    CHECK(ratio(350.0) < ratio(700.0));
}
