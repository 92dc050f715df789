#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "formats/renderer_media.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "scratch_folder.hpp"
#include "materials/measured_profile.hpp"

using namespace skinspec;

namespace {

const LayerStack& moderately() {
    static const auto m = std::get<LayerStack>(load_material("biospec-moderately"));
    return m;
}

// The preset's own volumetric description (its layers' fields), not the one derived from the BioSpec description.
const LayerStack& moderately_own() {
    static const auto m = std::get<LayerStack>(load_material("biospec-moderately", {parse_override("model.volumetric_matched_to_biospec=false")}));
    return m;
}

}  // namespace

TEST_CASE("renderer media carry the layers' coefficients in 1/mm and thickness in mm", "[renderer_media]") {
    const auto& stack = moderately_own();
    const auto media = renderer_media(stack, MediaRequest{{450.0, 550.0}});
    REQUIRE(media.layers.size() == stack.layers.size());
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        const auto& l = media.layers[k];
        CHECK(l.name == stack.layers[k].name);
        CHECK(l.thickness_mm == Approx(10.0 * stack.layers[k].thickness_cm).epsilon(1e-15));
        for (std::size_t w = 0; w < 2; ++w) {
            const auto o = stack.optics(k, media.wavelengths_nm[w]);
            CHECK(l.sigma_a_per_mm[w] == Approx(o.mu_a_per_cm / 10.0).epsilon(1e-15));
            // A table (one wavelength's phase) keeps the reduced scattering mu_s (1 - g) at each wavelength.
            const double g_written = l.phase.kind == RendererPhase::Kind::tabulated ? l.phase.g : *o.g;
            CHECK(l.sigma_s_per_mm[w] * (1.0 - g_written) == Approx(*o.mu_s_per_cm / 10.0 * (1.0 - *o.g)).epsilon(1e-14));
        }
    }
    CHECK(media.bottom_reflector);
    // Measured phases of the thin layers as tables, HG in the dermis.
    CHECK(media.layers[0].phase.kind == RendererPhase::Kind::tabulated);
    CHECK(media.layers[2].phase.kind == RendererPhase::Kind::henyey_greenstein);
    CHECK(media.layers[2].phase.g == 0.8);
    const auto hg = renderer_media(stack, MediaRequest{{550.0}, false, 550.0, PhaseExport::hg});
    CHECK(hg.layers[0].phase.kind == RendererPhase::Kind::henyey_greenstein);
    CHECK(hg.layers[0].phase.g == Approx(*stack.optics(0, 550.0).g));
    // The preset's derived description (matched_volumetric.hpp): one deflection per normal crossing of each thin layer
    // (mu_s d = 1 at 450-550 nm, where the dermis alone matches), the same absorption.
    const auto derived = renderer_media(moderately(), MediaRequest{{450.0, 550.0}});
    for (std::size_t k = 0; k < 2; ++k) {
        const auto& l = derived.layers[k];
        for (std::size_t w = 0; w < 2; ++w) {
            const double nm = derived.wavelengths_nm[w];
            INFO(l.name << " at " << nm << " nm");
            const double g = (k == 0 ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis()).inverse_table(nm).mean_cos();
            CHECK(l.sigma_s_per_mm[w] * (1.0 - l.phase.g) * l.thickness_mm == Approx(1.0 - g).epsilon(1e-12));
            CHECK(l.sigma_a_per_mm[w] == Approx(stack.optics(k, nm).mu_a_per_cm / 10.0).epsilon(1e-15));
        }
    }
}

TEST_CASE("a tabulated phase is normalised over the sphere and, as a renderer interpolates it, has the profile's mean cosine to 1e-4",
          "[renderer_media]") {
    for (const double nm : {400.0, 550.0, 700.0}) {
        const auto media = renderer_media(moderately(), MediaRequest{{550.0}, false, nm, PhaseExport::own});
        for (const std::size_t k : {0u, 1u}) {
            const auto& v = media.layers[k].phase.values;
            INFO(media.layers[k].name << " at " << nm << " nm, " << v.size() << " points");
            // 2 pi int p(mu) dmu = 1 (trapezoid over the regular grid), and the mean cosine of the linear interpolation,
            // also summed here by two-point Gauss-Legendre per interval (independent of tabulated_mean_cosine's closed form).
            const double h = 2.0 / static_cast<double>(v.size() - 1);
            double norm = 0.0, fine_norm = 0.0, fine_mean = 0.0;
            for (std::size_t i = 0; i < v.size(); ++i) {
                const double weight = (i == 0 || i + 1 == v.size()) ? 0.5 : 1.0;
                norm += 2.0 * std::numbers::pi * weight * h * v[i];
                CHECK(v[i] >= 0.0);
                if (i + 1 == v.size()) break;
                for (const double t : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}) {  // Gauss-Legendre, exact for mu p
                    const double mu = -1.0 + h * (static_cast<double>(i) + t), p = (1.0 - t) * v[i] + t * v[i + 1];
                    fine_norm += p * h / 2.0;
                    fine_mean += mu * p * h / 2.0;
                }
            }
            CHECK(norm == Approx(1.0).epsilon(1e-3));
            CHECK(std::abs(fine_mean / fine_norm - media.layers[k].phase.g) <= tabulated_mean_cosine_tolerance + 1e-6);
            CHECK(tabulated_mean_cosine(v) == Approx(fine_mean / fine_norm).epsilon(1e-12));
        }
    }
}

TEST_CASE("bad media requests are input errors", "[renderer_media]") {
    CHECK_THROWS_WITH(renderer_media(moderately(), MediaRequest{{650.0, 550.0}, true}), Catch::Contains("exactly three wavelengths"));
    CHECK_THROWS_WITH(renderer_media(moderately(), MediaRequest{{}}), Catch::Contains("no wavelength"));
    CHECK_THROWS_WITH(renderer_media(moderately(), MediaRequest{{550.0}, false, -1.0}), Catch::Contains("--phase-wavelength -1 nm"));
    const auto rayleigh = std::get<LayerStack>(load_material("biospec-moderately", {{"reticular_dermis.volumetric_phase", "rayleigh"}}));
    CHECK_THROWS_WITH(renderer_media(rayleigh, MediaRequest{{550.0}}), Catch::Contains("Rayleigh"));
    CHECK_NOTHROW(renderer_media(rayleigh, MediaRequest{{550.0}, false, 550.0, PhaseExport::hg}));
    auto plain = moderately();
    plain.layers[0].volumetric.reset();
    CHECK_THROWS_WITH(renderer_media(plain, MediaRequest{{550.0}}), Catch::Contains("no volumetric scattering"));
}

TEST_CASE("spectrum files read back exactly, malformed ones are input errors", "[renderer_media]") {
    const auto folder = testing::scratch_folder();
    const auto file = folder / "a.spd";
    write_spd_file(file, {400.0, 410.5}, {0.1, 1.0 / 3.0}, "test");
    const auto [nm, values] = read_spd_file(file);
    CHECK(nm == std::vector<double>{400.0, 410.5});
    CHECK(values == std::vector<double>{0.1, 1.0 / 3.0});
    std::ofstream(folder / "bad.spd") << "# x\n400 0.1\n410 abc\n";
    CHECK_THROWS_WITH(read_spd_file(folder / "bad.spd"), Catch::Contains("bad.spd line 3: expected 'wavelength value'"));
    std::ofstream(folder / "empty.spd") << "# nothing\n";
    CHECK_THROWS_WITH(read_spd_file(folder / "empty.spd"), Catch::Contains("has no values"));
    CHECK_THROWS_WITH(read_spd_file(folder / "missing.spd"), Catch::Contains("cannot be read"));
    CHECK(spectrum_file_path("out/skin.pbrt", "epidermis", "sigma_a") == std::filesystem::path("out/skin_spectra/epidermis_sigma_a.spd"));
    std::filesystem::remove_all(folder);
}

TEST_CASE("the default spectral media cover what the renderers sample, 360-830 nm (issue 37)", "[renderer_media]") {
    // pbrt-v4's PiecewiseLinearSpectrum and Mitsuba 3's spectrum files are 0 outside their range: media must reach it.
    const auto grid = WavelengthGrid::parse(renderer_sampled_wavelengths, "wavelengths");
    REQUIRE(grid.nm().front() <= 360.0);
    REQUIRE(grid.nm().back() >= 830.0);
    MediaRequest request;
    request.wavelengths_nm.assign(grid.nm().begin(), grid.nm().end());
    const auto media = renderer_media(moderately(), request);
    for (const auto& l : media.layers) {
        for (std::size_t i = 0; i < grid.nm().size(); ++i) {
            INFO(l.name << " at " << grid.nm()[i] << " nm");
            CHECK(std::isfinite(l.sigma_a_per_mm[i]));
            CHECK(l.sigma_a_per_mm[i] > 0.0);
            CHECK(l.sigma_s_per_mm[i] > 0.0);
        }
    }
}
