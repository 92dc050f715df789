#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "transport/diffusion/diffusion_model.hpp"
#include "transport/diffusion/dipole.hpp"
#include "transport/fresnel.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {
bool has_warning(const DiffusionMaterial& m, const std::string& kind) {
    return std::any_of(m.warnings.begin(), m.warnings.end(), [&](const TrustWarning& w) { return w.kind == kind; });
}
}  // namespace

TEST_CASE("homogeneous materials in diffusion mode are Jensen's dipole behind a Fresnel surface", "[diffusion-model]") {
    const auto material = std::get<HomogeneousMaterial>(load_material("jensen2001-marble"));
    for (const auto mode : {DiffusionMode::dipole, DiffusionMode::multipole}) {
        for (std::size_t b = 0; b < 3; ++b) {
            const auto m = diffusion_material(material, b, {mode, {}});
            const Dipole dipole({material.reduced_scattering_per_mm[b], material.absorption_per_mm[b], material.relative_refractive_index});
            const double specular = fresnel_reflectance(1.0, 1.0, material.relative_refractive_index);
            CHECK(m.specular_reflectance == Approx(specular));
            CHECK(m.total_reflectance() == Approx(specular + (1.0 - specular) * dipole.total_reflectance()).epsilon(1e-12));
            CHECK(m.total_transmittance() == 0.0);
        }
    }
    // Ketchup's green band has a reduced albedo far below 0.9: diffusion says it cannot be trusted there.
    const auto ketchup = std::get<HomogeneousMaterial>(load_material("jensen2001-ketchup"));
    CHECK(has_warning(diffusion_material(ketchup, 1, {}), "albedo"));
    CHECK_FALSE(has_warning(diffusion_material(material, 0, {}), "albedo"));
}

TEST_CASE("skin in diffusion mode: plausible spectra, merged thin layers, trust warnings", "[diffusion-model]") {
    const auto light = std::get<LayerStack>(load_material("biospec-lightly"));
    const auto heavy = std::get<LayerStack>(load_material("biospec-heavily"));
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::parse("400:700:20", "test");
    request.quantities.transmittance = true;
    for (const auto mode : {DiffusionMode::dipole, DiffusionMode::multipole}) {
        const auto l = solve_diffusion_spectrum(light, request, {mode, {}});
        const auto h = solve_diffusion_spectrum(heavy, request, {mode, {}});
        CHECK_FALSE(l.has_uncertainty);
        for (std::size_t i = 0; i < l.wavelengths.size(); ++i) {
            INFO(to_string(mode) << " " << l.wavelengths[i].wavelength_nm << " nm");
            CHECK(l.wavelengths[i].reflectance.value > 0.0);
            CHECK(l.wavelengths[i].reflectance.value < 1.0);
            CHECK(l.wavelengths[i].transmittance.value == 0.0);  // the hypodermis reflector
            CHECK(h.wavelengths[i].reflectance.value < l.wavelengths[i].reflectance.value);  // more melanin, darker
        }
        // Red skin reflects more than blue (haemoglobin and melanin absorb in the blue).
        CHECK(l.wavelengths.back().reflectance.value > l.wavelengths.front().reflectance.value);
    }
    // The 10 um stratum corneum is far below one transport mean free path: merged, and reported.
    const auto m = diffusion_material(light, 550.0, {});
    CHECK(has_warning(m, "merged"));
    CHECK(m.slab_names.front().starts_with("stratum_corneum+epidermis"));
    // A rough top surface changes the first-surface reflection.
    const auto rough = diffusion_material(light, 550.0, {DiffusionMode::multipole, 0.3});
    CHECK(rough.specular_reflectance != Approx(m.specular_reflectance));
}

TEST_CASE("multipole skin is continuous in wavelength where a thin layer's merge fades in", "[diffusion-model]") {
    // biospec-lightly's stratum corneum + epidermis crosses one transport mean free path near 481 nm (it jumped from
    // R 0.3565 to 0.3201 there). At 0.25 nm steps the largest change must be of the spectrum's own slope (< 1e-3),
    // and where two stacks are blended their weights sum to 1.
    const auto light = std::get<LayerStack>(load_material("biospec-lightly"));
    double previous = -1.0, largest_step = 0.0;
    bool blended = false;
    for (double nm = 440.0; nm <= 520.0; nm += 0.25) {
        const auto m = diffusion_material(light, nm, {});
        double weights = 0.0;
        for (const auto& s : m.stacks) weights += s.weight;
        CHECK(weights == Approx(1.0).epsilon(1e-12));
        blended = blended || m.stacks.size() > 1;
        const double r = m.total_reflectance();
        if (previous >= 0.0) largest_step = std::max(largest_step, std::abs(r - previous));
        previous = r;
    }
    CHECK(blended);
    CHECK(largest_step < 1e-3);
}

TEST_CASE("diffusion mode refuses what it cannot compute", "[diffusion-model]") {
    auto light = std::get<LayerStack>(load_material("biospec-lightly"));
    light.layers[1].reduced.reset();
    CHECK_THROWS_WITH(diffusion_material(light, 550.0, {}), Catch::Contains("layer 'epidermis' has no reduced scattering"));
}
