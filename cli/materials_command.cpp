#include "cli/materials_command.hpp"

#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"
#include "spectral/wavelength_grid.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct MaterialsOptions {
    std::string material;
    std::string wavelengths = "400:700:10";
    std::vector<std::string> overrides;
    std::string output;
    bool json = false;
    bool markdown = false;
    bool force = false;
};

Json model_json(const ModelOptions& m) {
    Json j = Json::object();
    for (const auto& [key, value] : model_settings(m)) j[key] = std::visit([](const auto& v) { return Json(v); }, value);
    return j;
}

// Per-layer optics over the grid: one vector per layer per quantity.
struct StackOpticsTable {
    std::vector<std::vector<LayerOptics>> by_wavelength;  // [wavelength][layer]
};

StackOpticsTable tabulate(const LayerStack& stack, const WavelengthGrid& grid) {
    StackOpticsTable t;
    for (const double nm : grid.nm()) t.by_wavelength.push_back(stack.optics(nm));
    return t;
}

void show_stack(const LayerStack& stack, const WavelengthGrid& grid, bool json) {
    const auto optics = tabulate(stack, grid);
    if (json) {
        Json j{{"kind", "layered"}, {"name", stack.name}, {"description", stack.description}, {"model", model_json(stack.model)},
               {"above_refractive_index", stack.above_refractive_index}, {"fold_aspect_ratio", stack.fold_aspect_ratio},
               {"bottom", std::string(to_string(stack.bottom))}, {"below_refractive_index", stack.below_refractive_index},
               {"wavelength_nm", std::vector<double>(grid.nm().begin(), grid.nm().end())}};
        Json layers = Json::array();
        for (std::size_t k = 0; k < stack.layers.size(); ++k) {
            const auto& l = stack.layers[k];
            Json layer{{"name", l.name}, {"thickness_cm", l.thickness_cm}, {"refractive_index", l.refractive_index},
                       {"scattering", std::string(to_string(optics.by_wavelength.front()[k].crossing))}};
            std::vector<double> mu_a, rayleigh, mie, reduced;
            for (const auto& row : optics.by_wavelength) {
                mu_a.push_back(row[k].mu_a_per_cm);
                rayleigh.push_back(row[k].rayleigh_per_cm);
                mie.push_back(row[k].mie_reduced_per_cm);
                if (row[k].mu_s_reduced_per_cm) reduced.push_back(*row[k].mu_s_reduced_per_cm);
            }
            layer["mu_a_per_cm"] = mu_a;
            if (optics.by_wavelength.front()[k].crossing == CrossingScattering::rayleigh_cosine) {
                layer["rayleigh_per_cm"] = rayleigh;
                layer["mie_reduced_per_cm"] = mie;
            }
            if (!reduced.empty()) layer["mu_s_reduced_per_cm"] = reduced;
            layers.push_back(layer);
        }
        j["layers"] = layers;
        std::cout << j.dump(2) << '\n';
        return;
    }
    const auto& m = stack.model;
    std::cout << fmt::format("{}: {}\n", stack.name, stack.description)
              << fmt::format("model {}: dermal Rayleigh {}, ln10 on molar tables {}, ln10 on melanin {}, baseline absorption {}, "
                             "haemoglobin M = {} g/mol\n",
                             m.variant, m.dermal_rayleigh ? "on" : "off",
                             m.molar_tables == DecadicConversion::multiply_ln10 ? "on" : "off",
                             m.melanin_tables == DecadicConversion::multiply_ln10 ? "on" : "off",
                             m.baseline_absorption ? "on" : "off", m.hemoglobin_molar_mass_g_per_mol)
              << fmt::format("above: n = {}, fold aspect ratio {}; bottom: {} (below n = {})\n\n", stack.above_refractive_index,
                             stack.fold_aspect_ratio, to_string(stack.bottom), stack.below_refractive_index);
    std::cout << fmt::format("{:<20}{:>13}{:>7}{:>8}{:>8}  {}\n", "layer", "thickness_cm", "n", "v_mel", "v_blood", "scattering");
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        const auto& l = stack.layers[k];
        std::cout << fmt::format("{:<20}{:>13g}{:>7g}{:>8g}{:>8g}  {}\n", l.name, l.thickness_cm, l.refractive_index,
                                 l.melanosome_fraction, l.blood_fraction, to_string(optics.by_wavelength.front()[k].crossing));
    }
    const auto block = [&](const char* title, auto value) {
        std::cout << '\n' << title << '\n' << fmt::format("{:>13}", "wavelength_nm");
        for (const auto& l : stack.layers) std::cout << fmt::format("{:>20}", l.name.substr(0, 19));
        std::cout << '\n';
        for (std::size_t w = 0; w < grid.size(); ++w) {
            std::cout << fmt::format("{:>13g}", grid[w]);
            for (const auto& o : optics.by_wavelength[w]) std::cout << value(o);
            std::cout << '\n';
        }
    };
    block("absorption coefficient mu_a [1/cm]", [](const LayerOptics& o) { return fmt::format("{:>20.5g}", o.mu_a_per_cm); });
    block("scattering: turn coefficient [1/cm], Rayleigh beta + Mie mu_s' (rayleigh_cosine layers) / reduced scattering mu_s' [1/cm]",
          [](const LayerOptics& o) {
              const auto beta = o.crossing != CrossingScattering::rayleigh_cosine ? std::string("-")
                                : o.mie_reduced_per_cm > 0.0 ? fmt::format("{:.4g}+{:.3g}", o.rayleigh_per_cm, o.mie_reduced_per_cm)
                                                             : fmt::format("{:.4g}", o.rayleigh_per_cm);
              const auto reduced = o.mu_s_reduced_per_cm ? fmt::format("{:.4g}", *o.mu_s_reduced_per_cm) : "-";
              return fmt::format("{:>20}", beta + " / " + reduced);
          });
}

void show_homogeneous(const HomogeneousMaterial& m, bool json) {
    if (json) {
        std::cout << Json{{"kind", "homogeneous"}, {"name", m.name}, {"description", m.description},
                          {"relative_refractive_index", m.relative_refractive_index}, {"bands", m.bands},
                          {"reduced_scattering_per_mm", m.reduced_scattering_per_mm}, {"absorption_per_mm", m.absorption_per_mm},
                          {"published_diffuse_reflectance", m.published_diffuse_reflectance}}
                         .dump(2)
                  << '\n';
        return;
    }
    std::cout << fmt::format("{}: {}\nhomogeneous, relative refractive index {}\n\n", m.name, m.description, m.relative_refractive_index)
              << fmt::format("{:<6}{:>22}{:>18}{:>16}\n", "band", "mu_s' [1/mm]", "mu_a [1/mm]", "published Rd");
    for (std::size_t b = 0; b < m.bands.size(); ++b) {
        std::cout << fmt::format("{:<6}{:>22g}{:>18g}{:>16}\n", m.bands[b], m.reduced_scattering_per_mm[b], m.absorption_per_mm[b],
                                 m.published_diffuse_reflectance.empty() ? "-" : fmt::format("{:g}", m.published_diffuse_reflectance[b]));
    }
}

void run_list(bool json) {
    Json j = Json::array();
    for (const auto& file : preset_files()) {
        const auto material = read_material(file);
        const bool layered = std::holds_alternative<LayerStack>(material);
        if (json) {
            j.push_back(Json{{"name", file.stem().string()}, {"kind", layered ? "layered" : "homogeneous"},
                             {"description", material_description(material)}, {"file", file.string()}});
        } else {
            std::cout << fmt::format("{:<28}{:<13}{}\n", file.stem().string(), layered ? "layered" : "homogeneous",
                                     material_description(material));
        }
    }
    if (json) std::cout << j.dump(2) << '\n';
}

void run_show(const MaterialsOptions& o) {
    const auto material = load_material(o.material, parsed_overrides(o.overrides));
    if (const auto* stack = std::get_if<LayerStack>(&material)) {
        show_stack(*stack, WavelengthGrid::parse(o.wavelengths, "--wavelengths"), o.json);
    } else {
        show_homogeneous(std::get<HomogeneousMaterial>(material), o.json);
    }
}

void run_save(const MaterialsOptions& o) {
    const auto overrides = parsed_overrides(o.overrides);
    auto material = load_material(o.material, overrides);
    // A changed copy is named after its file (standard output: NAME_changed) and says what changed; an unchanged
    // copy is the material itself.
    const bool to_stdout = o.output == "-";
    if (!overrides.empty()) {
        const auto name = to_stdout ? material_name(material) + "_changed" : std::filesystem::path(o.output).stem().string();
        material = relabelled(std::move(material), name, overrides);
    }
    if (to_stdout) {
        std::cout << to_toml(material);
        return;
    }
    write_material(material, o.output, o.force);
    std::cout << "wrote " << o.output << '\n';
}

// Every field of a material file from the descriptor tables (materials/material_fields.hpp).
void run_keys(bool json, bool markdown) {
    const auto rows = material_field_rows();
    if (json) {
        auto j = nlohmann::ordered_json::array();
        for (const auto& r : rows) j.push_back({{"key", r.key}, {"unit", r.unit}, {"allowed", r.allowed}, {"doc", r.doc}});
        std::cout << j.dump(2) << '\n';
        return;
    }
    if (markdown) {
        std::cout << "| key | unit | allowed | meaning |\n|---|---|---|---|\n";
        for (const auto& r : rows) std::cout << fmt::format("| `{}` | {} | {} | {} |\n", r.key, r.unit, r.allowed, r.doc);
        return;
    }
    std::size_t width = 0;
    for (const auto& r : rows) width = std::max(width, r.key.size());
    for (const auto& r : rows) {
        std::cout << fmt::format("{:<{}}  {:<6}  {:<24}  {}\n", r.key, width, r.unit, r.allowed, r.doc);
    }
    std::cout << "\nLAYER: a layer name, or a suffix shared by several layers ('dermis' sets every *_dermis layer), for --set.\n";
}

}  // namespace

void add_materials_command(CLI::App& app) {
    auto options = std::make_shared<MaterialsOptions>();
    auto* cmd = app.add_subcommand("materials", "Material presets: list them, show a stack's per-layer optics, save a customised copy");
    cmd->require_subcommand(1);

    auto* list = cmd->add_subcommand("list", "List the presets in data/materials");
    list->add_flag("--json", options->json, "Print JSON");
    list->callback([options] { run_list(options->json); });

    const auto add_material_options = [&](CLI::App* sub) {
        sub->add_option("material", options->material, "Preset name (see 'materials list') or a .toml file")->required();
        sub->add_option("--set", options->overrides, set_option_help);
    };
    auto* show = cmd->add_subcommand("show", "Show a material: layers and per-layer mu_a and scattering with units");
    add_material_options(show);
    show->add_option("--wavelengths", options->wavelengths, "FIRST:LAST:STEP, one wavelength or a comma list (nm)")->capture_default_str();
    show->add_flag("--json", options->json, "Print JSON");
    show->callback([options] { run_show(*options); });

    auto* keys = cmd->add_subcommand("keys", "Every field of a material file: key, unit, allowed values, meaning (what --set takes)");
    keys->add_flag("--json", options->json, "Print JSON");
    keys->add_flag("--markdown", options->markdown, "Print a Markdown table (as in docs/MATERIALS.md)");
    keys->callback([options] { run_keys(options->json, options->markdown); });

    auto* save = cmd->add_subcommand("save", "Write a material (with --set overrides applied) as a TOML file");
    add_material_options(save);
    save->add_option("output", options->output, "Output .toml file, or - for standard output; with --set, the copy is named after the file")->required();
    add_overwrite_flag(*save, options->force, "Replace the output file if it exists");
    save->callback([options] { run_save(*options); });
}

}  // namespace skinspec::cli
