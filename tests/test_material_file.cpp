#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

std::filesystem::path temp_path(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("skinspec_material_" + name);
}

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
    const auto path = temp_path(name);
    std::ofstream(path) << text;
    return path;
}

const std::string minimal = R"(kind = "layered"
name = "test"
[[layers]]
name = "slab"
thickness_cm = 0.1
refractive_index = 1.4
scattering = "cosine"
)";

std::string with(const std::string& extra_layer_lines) { return minimal + extra_layer_lines; }

}  // namespace

TEST_CASE("the BioSpec presets have the specified pigmentation and defaults", "[material_file]") {
    struct Case { const char* name; double melanosomes; };
    for (const auto& c : {Case{"biospec-lightly", 0.019}, Case{"biospec-moderately", 0.052}, Case{"biospec-heavily", 0.12},
                          Case{"biospec-very-heavily", 0.42}}) {
        const auto stack = std::get<LayerStack>(load_material(c.name));
        REQUIRE(stack.layers.size() == 4);
        CHECK(stack.layers[1].melanosome_fraction == c.melanosomes);
        CHECK(stack.layers[2].blood_fraction == 0.012);
        CHECK(stack.layers[3].blood_fraction == 0.0091);
        CHECK(stack.layers[2].oxygen_saturation == 0.75);
        CHECK(stack.layers[0].carotene_g_per_l == 2.1e-4);
        CHECK(stack.layers[3].carotene_g_per_l == 7e-5);
        CHECK(stack.layers[3].bilirubin_g_per_l == 0.05);
        CHECK(stack.fold_aspect_ratio == 0.75);
        CHECK(stack.bottom == BottomBoundary::diffuse_reflector);
        // The default model, its volumetric description derived from the BioSpec one (issue 31, "one skin").
        ModelOptions expected;
        expected.volumetric_matched_to_biospec = true;
        CHECK(stack.model == expected);
    }
}

TEST_CASE("the Jensen 2001 materials carry their RGB bands", "[material_file]") {
    const auto skin1 = std::get<HomogeneousMaterial>(load_material("jensen2001-skin1"));
    CHECK(skin1.bands == std::vector<std::string>{"R", "G", "B"});
    CHECK(skin1.reduced_scattering_per_mm == std::vector<double>{0.74, 0.88, 1.01});
    CHECK(skin1.absorption_per_mm == std::vector<double>{0.032, 0.17, 0.48});
    CHECK(skin1.relative_refractive_index == 1.3);
}

TEST_CASE("every preset survives load -> save -> load unchanged", "[material_file]") {
    for (const auto& file : preset_files()) {
        INFO(file.string());
        const auto original = read_material(file);
        const auto copy = temp_path("roundtrip.toml");
        write_material(original, copy, true);
        CHECK(read_material(copy) == original);
    }
    // Optional descriptions survive too.
    auto stack = std::get<LayerStack>(load_material("biospec-lightly"));
    stack.layers[3].volumetric = VolumetricScattering{210.0, 1.2, PhaseFunctionKind::rayleigh, 0.0};
    stack.layers[2].reduced = ReducedScattering{"", 30.0, 1.1};
    stack.model = model_variant("biospec-2004", "t");
    write_material(stack, temp_path("roundtrip2.toml"), true);
    CHECK(std::get<LayerStack>(read_material(temp_path("roundtrip2.toml"))) == stack);
}

TEST_CASE("a saved material writes each number as the shortest decimal that reads back as the same double", "[material_file]") {
    // 0.05 was written 0.050000000000000003 (17 digits). 0.1 + 0.2 has no shorter form than 0.30000000000000004; text
    // with numbers (the description, a key with digits) is left as it is.
    auto stack = std::get<LayerStack>(load_material("biospec-lightly", {{"epidermis.melanosome_fraction", "0.05"}}));
    stack.layers[2].blood_fraction = 0.1 + 0.2;
    stack.layers[3].blood_fraction = 1e-5;
    stack.description = "melanosome fraction 0.050000000000000003 # not a comment";
    const auto text = to_toml(stack);
    CHECK_THAT(text, Catch::Contains("melanosome_fraction = 0.05\n"));
    CHECK_THAT(text, Catch::Contains("blood_fraction = 0.30000000000000004\n"));
    CHECK_THAT(text, Catch::Contains("blood_fraction = 1e-05\n"));
    CHECK_THAT(text, Catch::Contains("eumelanin_mg_per_ml = 80.0\n"));  // a whole number stays a TOML float
    CHECK_THAT(text, Catch::Contains("mie_reduced_scattering_per_cm_at_500nm = 0.0\n"));
    CHECK_THAT(text, Catch::Contains("'melanosome fraction 0.050000000000000003 # not a comment'"));
    CHECK(parse_material(text, "text") == Material(stack));
}

TEST_CASE("a saved material still follows a later --variant, switches set by hand stay pinned", "[material_file]") {
    const auto saved = temp_path("variant.toml");
    write_material(load_material("biospec-lightly"), saved, true);
    const auto later = std::get<LayerStack>(read_material(saved, {{"model.variant", "biospec-2004"}}));
    auto expected = model_variant("biospec-2004", "t");
    expected.volumetric_matched_to_biospec = true;  // set by hand in the preset: pinned
    CHECK(later.model == expected);
    auto pinned = std::get<LayerStack>(load_material("biospec-lightly"));
    pinned.model.dermal_rayleigh = false;
    write_material(pinned, saved, true);
    const auto reread = std::get<LayerStack>(read_material(saved, {{"model.variant", "biospec-2004"}}));
    CHECK_FALSE(reread.model.dermal_rayleigh);
    CHECK(reread.model.variant == "biospec-2004");
}

TEST_CASE("saving never replaces a file unless asked", "[material_file]") {
    const auto path = write_temp("existing.toml", "user data\n");
    const auto material = load_material("biospec-lightly");
    CHECK_THROWS_WITH(write_material(material, path, false), Catch::Contains("exists already (use --overwrite"));
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    CHECK(first == "user data");
}

TEST_CASE("overrides change fields by layer name or shared suffix", "[material_file]") {
    const auto stack = std::get<LayerStack>(load_material(
        "biospec-lightly", {parse_override("epidermis.melanosome_fraction=0.3"), parse_override("dermis.blood_fraction = 0.02"),
                            parse_override("model.variant=biospec-2004"), parse_override("bottom.boundary=exit"),
                            parse_override("surface.fold_aspect_ratio=0.5")}));
    CHECK(stack.layers[1].melanosome_fraction == 0.3);
    CHECK(stack.layers[2].blood_fraction == 0.02);
    CHECK(stack.layers[3].blood_fraction == 0.02);
    CHECK_FALSE(stack.model.dermal_rayleigh);
    CHECK(stack.bottom == BottomBoundary::exit);
    CHECK(stack.fold_aspect_ratio == 0.5);
    // A switch given on its own wins over the variant.
    const auto mixed = std::get<LayerStack>(load_material(
        "biospec-lightly", {parse_override("model.variant=biospec-2004"), parse_override("model.dermal_rayleigh=true")}));
    CHECK(mixed.model.dermal_rayleigh);
    CHECK(mixed.model.molar_tables == DecadicConversion::omit_ln10);
}

TEST_CASE("bad overrides name the --set", "[material_file]") {
    CHECK_THROWS_WITH(parse_override("epidermis.melanosome_fraction"), Catch::Contains("KEY=VALUE"));
    CHECK_THROWS_WITH(load_material("biospec-lightly", {parse_override("nail.thickness_cm=1")}),
                      Catch::Contains("--set nail.thickness_cm: no layer or section 'nail' (allowed: model, surface, bottom, stratum_corneum"));
    CHECK_THROWS_WITH(load_material("biospec-lightly", {parse_override("epidermis.melanosome_fraction=1.5")}),
                      Catch::Contains("(--set epidermis.melanosome_fraction): key 'epidermis.melanosome_fraction' = 1.5 is outside [0, 1]"));
    CHECK_THROWS_WITH(load_material("biospec-lightly", {parse_override("epidermis.melanin=0.1")}),
                      Catch::Contains("(--set epidermis.melanin): unknown key 'epidermis.melanin'"));
    CHECK_THROWS_WITH(load_material("biospec-lightly", {parse_override("epidermis.thickness_cm=thin")}),
                      Catch::Contains("key 'epidermis.thickness_cm' must be a number in (0, inf)"));
}

TEST_CASE("each invalid material file gets its error naming file, line, key, value and range", "[material_file]") {
    struct Case { const char* name; std::string text; const char* message; };
    const std::vector<Case> cases{
        {"unknown_key.toml", with("thikness_cm = 0.1\n"), "unknown_key.toml:8: unknown key 'slab.thikness_cm' (allowed: name, thickness_cm"},
        {"fraction.toml", with("blood_fraction = 1.2\n"), "fraction.toml:8: key 'slab.blood_fraction' = 1.2 is outside [0, 1]"},
        {"both_fractions.toml", with("blood_fraction = 0.6\nmelanosome_fraction = 0.6\n"), "melanosome_fraction + blood_fraction = 1.2 is outside [0, 1]"},
        {"saturation.toml", with("oxygen_saturation = -0.1\n"), "key 'slab.oxygen_saturation' = -0.1 is outside [0, 1]"},
        {"concentration.toml", with("carotene_g_per_l = -1\n"), "key 'slab.carotene_g_per_l' = -1 is outside [0, inf)"},
        {"thickness.toml", "kind = \"layered\"\nname = \"t\"\n[[layers]]\nname = \"slab\"\nthickness_cm = 0\nrefractive_index = 1.4\nscattering = \"cosine\"\n",
         "thickness.toml:5: key 'slab.thickness_cm' = 0 is outside (0, inf)"},
        {"infinite.toml", "kind = \"layered\"\nname = \"t\"\n[[layers]]\nname = \"slab\"\nthickness_cm = inf\nrefractive_index = 1.4\nscattering = \"cosine\"\n",
         "key 'slab.thickness_cm' = inf is outside (0, inf)"},
        {"index.toml", "kind = \"layered\"\nname = \"t\"\n[[layers]]\nname = \"slab\"\nthickness_cm = 1\nrefractive_index = 0.9\nscattering = \"cosine\"\n",
         "key 'slab.refractive_index' = 0.9 is outside [1, 4]"},
        {"missing.toml", "kind = \"layered\"\nname = \"t\"\n[[layers]]\nname = \"slab\"\nrefractive_index = 1.4\nscattering = \"cosine\"\n",
         "key 'slab.thickness_cm' is missing"},
        {"scattering.toml", "kind = \"layered\"\nname = \"t\"\n[[layers]]\nname = \"slab\"\nthickness_cm = 1\nrefractive_index = 1.4\nscattering = \"mie\"\n",
         "scattering.toml:7: key 'slab.scattering': 'mie' is not a scattering description"},
        {"g.toml", with("hg_g = 1.5\n"), "key 'slab.hg_g' = 1.5 is outside [-1, 1]"},
        {"type.toml", with("blood_fraction = \"lots\"\n"), "key 'slab.blood_fraction' must be a number in [0, 1]"},
        {"syntax.toml", "kind = \"layered\"\nname = \n", "syntax.toml:2:"},
        {"kind.toml", "kind = \"gel\"\nname = \"t\"\n", "key 'kind' = 'gel' is not allowed (allowed: layered, homogeneous)"},
        {"nolayers.toml", "kind = \"layered\"\nname = \"t\"\n", "needs at least one [[layers]] table"},
        {"duplicate.toml", minimal + "[[layers]]\nname = \"slab\"\nthickness_cm = 1\nrefractive_index = 1.4\nscattering = \"cosine\"\n",
         "layer name 'slab' is used twice"},
        {"layername.toml", "kind = \"layered\"\nname = \"t\"\n[[layers]]\nname = \"Top Layer\"\nthickness_cm = 1\nrefractive_index = 1.4\nscattering = \"cosine\"\n",
         "layer name 'Top Layer' is not allowed"},
        {"fold.toml", minimal + "[surface]\nfold_aspect_ratio = 0\n", "key 'surface.fold_aspect_ratio' = 0 is outside (0, 1]"},
        {"bottom.toml", minimal + "[bottom]\nboundary = \"mirror\"\n", "'mirror' is not a bottom boundary"},
        {"variant.toml", minimal + "[model]\nvariant = \"biospec-1999\"\n", "'biospec-1999' is not a model variant"},
        {"model_key.toml", minimal + "[model]\nln10 = true\n", "unknown key 'model.ln10'"},
        {"mass.toml", minimal + "[model]\nhemoglobin_molar_mass_g_per_mol = 0\n", "key 'model.hemoglobin_molar_mass_g_per_mol' = 0 is outside (0, inf)"},
        {"reduced.toml", with("reduced_scattering_table = \"salomatina_nail\"\n"), "'salomatina_nail' is not a table"},
        {"reduced_both.toml", with("reduced_scattering_table = \"salomatina_dermis\"\nreduced_scattering_power = 1\n"), "not both"},
        {"volumetric.toml", with("volumetric_g = 0.9\n"), "key 'slab.volumetric_mu_s_per_cm_at_500nm' is missing"},
        {"from_reduced_alone.toml", with("volumetric_scattering = \"from_reduced_scattering\"\n"),
         "volumetric_scattering = from_reduced_scattering needs reduced_scattering_table or the reduced power law"},
        {"from_reduced_mu_s.toml", with("volumetric_scattering = \"from_reduced_scattering\"\nvolumetric_mu_s_per_cm_at_500nm = 100\n"
                                        "reduced_scattering_table = \"salomatina_dermis\"\n"),
         "volumetric_mu_s_per_cm_at_500nm contradicts volumetric_scattering = from_reduced_scattering"},
        {"measured_g.toml", with("volumetric_scattering = \"from_reduced_scattering\"\nvolumetric_phase = \"measured_epidermis\"\nvolumetric_g = 0.8\n"
                                 "reduced_scattering_table = \"salomatina_epidermis\"\n"),
         "layer 'slab': volumetric_g contradicts volumetric_phase = measured_epidermis (g is the measured profile's mean cosine)"},
        {"from_reduced_g1.toml", with("volumetric_scattering = \"from_reduced_scattering\"\nvolumetric_g = 1\nreduced_scattering_table = \"salomatina_dermis\"\n"),
         "key 'slab.volumetric_g' = 1 is outside [-1, 1)"},
        {"bands.toml", "kind = \"homogeneous\"\nname = \"m\"\nrelative_refractive_index = 1.3\nbands = [\"R\", \"G\"]\n"
                       "reduced_scattering_per_mm = [1.0]\nabsorption_per_mm = [0.1, 0.2]\n", "must have the same, non-zero length"},
        {"homogeneous_neg.toml", "kind = \"homogeneous\"\nname = \"m\"\nrelative_refractive_index = 1.3\nbands = [\"R\"]\n"
                                 "reduced_scattering_per_mm = [-1.0]\nabsorption_per_mm = [0.1]\n", "has an entry outside [0, inf)"},
    };
    for (const auto& c : cases) {
        INFO(c.name);
        CHECK_THROWS_WITH(read_material(write_temp(c.name, c.text)), Catch::Contains(c.message));
    }
    CHECK_THROWS_WITH(read_material("/nonexistent/m.toml"), Catch::Contains("material file not found"));
    CHECK_THROWS_WITH(load_material("no-such-preset"), Catch::Contains("is neither a preset nor a .toml file (presets: biospec-heavily"));
    CHECK(std::holds_alternative<LayerStack>(read_material(write_temp("ok.toml", minimal))));
}

TEST_CASE("material_field reads every field as --set addresses it, material_keys lists them", "[material_file]") {
    auto m = load_material("biospec-moderately", {{"dermis.oxygen_saturation", "0.8"}});
    CHECK(std::get<double>(material_field(m, "epidermis.melanosome_fraction")) == 0.052);
    CHECK(std::get<double>(material_field(m, "dermis.oxygen_saturation")) == 0.8);
    CHECK(std::get<std::string>(material_field(m, "model.variant")) == "biospec");
    CHECK(std::get<std::string>(material_field(m, "name")) == "biospec-moderately");
    // Every model switch reads, also those the variant sets and a file leaves out.
    for (const auto& key : material_keys(m)) CHECK_NOTHROW(material_field(m, key));
    const auto keys = material_keys(m);
    CHECK(std::find(keys.begin(), keys.end(), "epidermis.melanosome_fraction") != keys.end());
    CHECK(std::find(keys.begin(), keys.end(), "model.dermal_rayleigh") != keys.end());
    CHECK_THROWS_WITH(material_field(m, "epiderm.melanosome_fraction"), Catch::Contains("no layer or section 'epiderm'"));
    CHECK_THROWS_WITH(material_field(m, "epidermis.melanin"), Catch::Contains("is not set in biospec-moderately"));
    CHECK_THROWS_WITH(material_field(m, "colour"), Catch::Contains("is not one of biospec-moderately's"));
    m = load_material("biospec-moderately", {{"papillary_dermis.blood_fraction", "0.01"}, {"reticular_dermis.blood_fraction", "0.002"}});
    CHECK_THROWS_WITH(material_field(m, "dermis.blood_fraction"), Catch::Contains("which differ"));
    const auto jensen = load_material("jensen2001-skin1");
    CHECK(std::get<std::vector<std::string>>(material_field(jensen, "bands")) == std::vector<std::string>{"R", "G", "B"});
    CHECK(std::get<std::vector<double>>(material_field(jensen, "absorption_per_mm")).size() == 3);
}

TEST_CASE("with_overrides applies --set checks to a material in memory, parse_material names its source", "[material_file]") {
    const auto base = load_material("biospec-lightly");
    const auto changed = with_overrides(base, {{"epidermis.melanosome_fraction", "0.03", "set"}});
    CHECK(changed == load_material("biospec-lightly", {{"epidermis.melanosome_fraction", "0.03"}}));
    CHECK(with_overrides(base, {}) == base);
    CHECK_THROWS_WITH(with_overrides(base, {{"epidermis.melanosome_fraction", "-1", "set"}}),
                      "material biospec-lightly (set epidermis.melanosome_fraction): key 'epidermis.melanosome_fraction' = -1 is outside [0, 1]");
    CHECK_THROWS_WITH(with_overrides(base, {{"epidermis.melanosome_fraction", "nan", "set"}}), Catch::Contains("= nan is outside [0, 1]"));
    CHECK(parse_material(to_toml(base), "text") == base);
    CHECK_THROWS_WITH(parse_material("kind = \"layered\"\nname = [", "notebook cell"), Catch::StartsWith("notebook cell:2:"));
}

TEST_CASE("numbers set in memory equal the file reader's result, and every refusal is the reader's", "[material_file]") {
    const auto base = load_material("biospec-moderately");
    const auto through_file = [&](const std::vector<MaterialOverride>& o) { return parse_material(to_toml(base), "material biospec-moderately", o); };
    for (const std::vector<MaterialOverride>& o : std::vector<std::vector<MaterialOverride>>{
             {{"epidermis.melanosome_fraction", "0.07", "--vary"}},
             {{"dermis.blood_fraction", "0.03", "--vary"}, {"dermis.oxygen_saturation", "5e-1", "--set"}},
             {{"model.hemoglobin_molar_mass_g_per_mol", "64500", "--set"}},
             {{"surface.fold_aspect_ratio", "0.5", "--set"}, {"bottom.below_refractive_index", "1.4", "--set"}},
             {{"papillary_dermis.volumetric_g", "0.7", "--set"}},
             {{"model.dermal_rayleigh", "false", "--set"}},
             {{"epidermis.scattering", "cosine", "--set"}}}) {
        CHECK(with_overrides(base, o) == through_file(o));
    }
    for (const MaterialOverride& o : {MaterialOverride{"epidermis.melanosome_fraction", "1.5", "--vary"},
                                      MaterialOverride{"epidermis.blood_fraction", "0.99", "--vary"},
                                      MaterialOverride{"hypodermis.blood_fraction", "0.1", "--vary"},
                                      MaterialOverride{"epidermis.volumetric_g", "0.5", "--set"},
                                      MaterialOverride{"epidermis.melanosome_fraction", "inf", "--vary"}}) {
        std::string direct, file;
        try { with_overrides(base, {o}); } catch (const InputError& e) { direct = e.what(); }
        try { through_file({o}); } catch (const InputError& e) { file = e.what(); }
        INFO(o.key << "=" << o.value);
        CHECK_FALSE(direct.empty());
        CHECK(direct == file);
    }
}
