#include <catch2/catch.hpp>

#include <cstring>

#include "solvers/result_wire.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

SpectralResult solved() {
    SolverRequest request;
    request.spectral.wavelengths = WavelengthGrid::list({450.0, 550.0});
    request.spectral.quantities = Quantities{true, true, true, true};
    request.spectral.max_rays_per_wavelength = 2000;
    auto result = solve_spectrum(find_solver("biospec"), load_material("biospec-lightly", {{"epidermis.melanosome_fraction", "0.03"}}), request);
    result.warnings.push_back({"a kind", "epidermis", "450 nm", 0.25});
    result.settings["flag"] = true;
    result.settings["ratio"] = 0.1;
    result.stated_error = StatedError{0.0123, std::make_shared<const std::string>("a meaning"), 1.5};
    result.provenance.varied = {std::make_shared<const std::vector<std::string>>(std::vector<std::string>{"dermis.blood_fraction"}), {0.01}};
    return result;
}

}  // namespace

TEST_CASE("results read back from bytes equal the results written, bit for bit", "[result_wire]") {
    const auto original = solved();
    const auto back = results_from_bytes(results_to_bytes({original, original}));
    REQUIRE(back.size() == 2);
    const auto& r = back[1];
    CHECK(r.model == original.model);
    CHECK(r.settings == original.settings);
    REQUIRE(r.model_settings);
    CHECK(*r.model_settings == *original.model_settings);
    CHECK(r.layer_names == original.layer_names);
    CHECK(r.angular_bin_edges_deg == original.angular_bin_edges_deg);
    CHECK(r.quantities.angular);
    REQUIRE(r.wavelengths.size() == original.wavelengths.size());
    for (std::size_t i = 0; i < r.wavelengths.size(); ++i) {
        const auto& x = r.wavelengths[i];
        const auto& y = original.wavelengths[i];
        CHECK(same_bits(x.reflectance.value, y.reflectance.value));
        CHECK(same_bits(x.reflectance.stderr, y.reflectance.stderr));
        CHECK(same_bits(x.transmittance.value, y.transmittance.value));
        REQUIRE(x.absorptance_layers.size() == y.absorptance_layers.size());
        for (std::size_t k = 0; k < x.absorptance_layers.size(); ++k) CHECK(same_bits(x.absorptance_layers[k].value, y.absorptance_layers[k].value));
        REQUIRE(x.brdf_per_sr.size() == y.brdf_per_sr.size());
        for (std::size_t k = 0; k < x.brdf_per_sr.size(); ++k) CHECK(same_bits(x.brdf_per_sr[k].value, y.brdf_per_sr[k].value));
        CHECK(x.rays == y.rays);
        CHECK(x.converged == y.converged);
    }
    CHECK(r.warnings.back().kind == "a kind");
    CHECK(r.warnings.back().value == 0.25);
    REQUIRE(r.stated_error);
    CHECK(same_bits(r.stated_error->R, 0.0123));
    CHECK(*r.stated_error->meaning == "a meaning");
    CHECK(r.stated_error->delta_e2000 == 1.5);
    CHECK(*r.provenance.material_toml == *original.provenance.material_toml);
    CHECK(r.provenance.overrides == original.provenance.overrides);
    CHECK(r.provenance.varied == original.provenance.varied);
    CHECK(results_from_bytes(results_to_bytes({})).empty());
}

TEST_CASE("truncated or padded result bytes are input errors, not crashes", "[result_wire]") {
    const auto bytes = results_to_bytes({solved()});
    for (const std::size_t cut : {std::size_t{0}, std::size_t{3}, bytes.size() / 2, bytes.size() - 1}) {
        CHECK_THROWS_AS(results_from_bytes(bytes.substr(0, cut)), InputError);
    }
    CHECK_THROWS_WITH(results_from_bytes(bytes + "x"), Catch::Contains("hold more than the results"));
    std::string huge(8, '\xff');
    CHECK_THROWS_WITH(results_from_bytes(huge), Catch::Contains("a length of"));
}
