// The descriptor tables: every field reads, writes and is documented from one entry.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"

using namespace skinspec;

TEST_CASE("every field of the descriptor tables is documented in docs/MATERIALS.md", "[material_fields]") {
    std::ifstream in(std::string(SKINSPEC_TEST_REFERENCE_DIR) + "/../../docs/MATERIALS.md");
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    for (const auto& row : material_field_rows()) {
        INFO(row.key);
        CHECK(text.str().find("| `" + row.key + "` |") != std::string::npos);
    }
}

TEST_CASE("every layer number field is written by save and read back with its range checked", "[material_fields]") {
    const auto toml = to_toml(load_material("biospec-moderately"));
    for (const auto& f : layer_number_fields()) {
        INFO(f.key);
        CHECK(toml.find(std::string(f.key) + " = ") != std::string::npos);
        // Just outside the range (or a non-number for an unbounded side) is refused with the field's range.
        const double outside = std::isinf(f.range.hi) ? (f.range.lo_open ? f.range.lo : f.range.lo - 1.0) : f.range.hi + 1.0;
        CHECK_THROWS_WITH(load_material("biospec-moderately", {{"epidermis." + std::string(f.key), std::to_string(outside)}}),
                          Catch::Contains("epidermis." + std::string(f.key)) && Catch::Contains(f.range.text()));
    }
}

TEST_CASE("every named field's allowed values, as documented, are the ones its reader names when refusing", "[material_fields]") {
    // The table's allowed list (help, `materials keys`, docs/MATERIALS.md) and the parser's own list must not drift.
    for (const auto& f : named_fields()) {
        if (f.section.empty() || f.key == "name") continue;  // kind (the file's), layer names (a pattern)
        const std::string key = (f.section == "layers" ? std::string("epidermis") : std::string(f.section)) + "." + std::string(f.key);
        INFO(key);
        CHECK_THROWS_WITH(load_material("biospec-lightly", {{key, "not_a_choice"}}), Catch::Contains("(allowed: " + std::string(f.allowed) + ")"));
    }
}
