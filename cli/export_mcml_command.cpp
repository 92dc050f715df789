// `skinspec export mcml`: a material's volumetric description as an MCML input file (formats/mcml_export.hpp), one run
// per wavelength, with what MCML could not hold said and measured.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli/common_options.hpp"
#include "cli/export_command.hpp"
#include "cli/material_options.hpp"
#include "formats/mcml_export.hpp"
#include "materials/material_file.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::cli {
namespace {

struct McmlExportOptions {
    std::string preset;
    std::string material_file;
    std::vector<std::string> overrides;
    std::string wavelengths = "450,550,650";
    McmlExportRequest request;
    std::string output;
    bool overwrite = false;
};

void run_export_mcml(const McmlExportOptions& o) {
    const std::string name = chosen_material(o.preset, o.material_file);
    if (o.output.empty()) throw InputError("export mcml: give -o FILE.mci");
    check_output_path(o.output, o.overwrite, {".mci"});
    const auto material = load_material(name, parsed_overrides(o.overrides));
    const auto* stack = std::get_if<LayerStack>(&material);
    if (!stack) throw InputError("material '" + name + "' is given per band (no layers); export mcml writes the layers of a layered material");
    auto request = o.request;
    const auto grid = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    request.wavelengths_nm.assign(grid.nm().begin(), grid.nm().end());
    request.output_stem = std::filesystem::path(o.output).stem().string();
    const auto exported = mcml_export(*stack, request);
    const auto comments = mcml_export_comments(exported, name, request.wavelengths_nm);
    write_text_file(o.output, mci_text(exported.runs, comments), o.overwrite);
    for (const auto& c : comments) std::cout << c << '\n';
    std::cout << fmt::format("wrote {}: {} runs of {} photons, rings of {:g} mm to {:g} mm; run it with MCML 1.2 (`mcml {}`) or `skinspec mcml {}` "
                             "(the walk on this same description)\n",
                             o.output, exported.runs.size(), request.photons, request.ring_mm, request.reach_mm, o.output, o.output);
}

}  // namespace

void add_export_mcml_command(CLI::App& exporter) {
    auto o = std::make_shared<McmlExportOptions>();
    auto* cmd = exporter.add_subcommand("mcml", "The layers' volumetric description as an MCML input file (.mci), one run per wavelength");
    add_base_material_options(*cmd, o->preset, o->material_file, o->overrides);
    cmd->add_option("--wavelengths", o->wavelengths, "Wavelengths (nm), one run each")->capture_default_str();
    add_ray_count_option(*cmd, "--photons", o->request.photons, "Photons per run")->capture_default_str();
    cmd->add_option("--ring", o->request.ring_mm, "Width of the radial rings (MCML's dr) in mm")->capture_default_str();
    cmd->add_option("--reach", o->request.reach_mm, "Radius the rings cover in mm")->capture_default_str();
    cmd->add_option("--depth-bin", o->request.depth_bin_mm, "Depth bins (MCML's dz) in mm")->capture_default_str();
    cmd->add_option("-o,--output", o->output, "The .mci file");
    add_overwrite_flag(*cmd, o->overwrite, "Replace an existing file");
    cmd->callback([o] { run_export_mcml(*o); });
}

}  // namespace skinspec::cli
