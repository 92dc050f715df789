// The result quantity table: which request brings which quantity, its columns and its values.
#include <catch2/catch.hpp>

#include "transport/result_quantities.hpp"

using namespace skinspec;

TEST_CASE("a result holds the quantities its request brings, named per layer and per bin", "[result_quantities]") {
    SpectralResult r;
    r.layer_names = {"stratum_corneum", "epidermis"};
    r.angular_bin_edges_deg = {0.0, 2.5, 7.5};
    r.quantities = Quantities{true, false, true, true};
    WavelengthResult w;
    w.reflectance = {0.3, 0.01};
    w.absorptance_layers = {{0.1, 0.0}, {0.2, 0.0}};
    w.brdf_per_sr = {{1.0, 0.0}, {2.0, 0.0}};
    w.btdf_per_sr = {{0.0, 0.0}, {0.0, 0.0}};
    std::vector<std::string> columns;
    for (const auto* q : quantities_of(r)) {
        REQUIRE(q->values(w).size() == q->count(r));
        for (std::size_t i = 0; i < q->count(r); ++i) columns.push_back(q->column(r, i));
    }
    CHECK(columns == std::vector<std::string>{"R", "R_specular", "A_stratum_corneum", "A_epidermis", "A_surface", "BRDF_0-2.5deg_per_sr",
                                              "BRDF_2.5-7.5deg_per_sr", "BTDF_0-2.5deg_per_sr", "BTDF_2.5-7.5deg_per_sr"});
    CHECK(result_quantities().front().values(w).front().value == 0.3);
    r.quantities = Quantities{false, true, false, false};
    REQUIRE(quantities_of(r).size() == 1);
    CHECK(quantities_of(r).front()->key == "T");
}
