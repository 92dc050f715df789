#include "cli/compare_phase_command.hpp"

#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "materials/material_file.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/line_plot.hpp"
#include "studies/phase_study/phase_comparison.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct ComparePhaseOptions {
    std::vector<std::string> presets;
    std::vector<std::string> overrides;
    std::string hg_source = ComparePhaseDefaults::hg_source;
    std::string wavelengths = ComparePhaseDefaults::wavelengths;
    double stderr_target = ComparePhaseDefaults::stderr_target;
    std::uint64_t max_rays = ComparePhaseDefaults::max_rays;
    std::uint64_t seed = 1;
    unsigned threads = 0;
    std::string plot;
    bool overwrite = false;
    bool json = false;
};

Json comparison_json(const PhaseComparison& c) {
    Json rows = Json::array();
    for (const auto& r : c.rows) {
        rows.push_back(Json{{"wavelength_nm", r.wavelength_nm}, {"measured", r.measured.value}, {"measured_stderr", r.measured.stderr},
                            {"hg", r.hg.value}, {"hg_stderr", r.hg.stderr}, {"difference", r.difference.value},
                            {"difference_stderr", r.difference.stderr}, {"significant", r.significant}});
    }
    Json j{{"material", c.material}, {"quantity", c.quantity}, {"significant_wavelengths", c.significant_count}, {"rows", rows}};
    if (c.delta_e00) {
        j["delta_e00"] = *c.delta_e00;
        j["delta_e00_uncertainty"] = *c.delta_e00_uncertainty;
    }
    return j;
}

std::string comparison_table(const PhaseComparison& c) {
    std::string out = fmt::format("{} ({}): measured thin layers vs HG, difference = HG - measured; * = beyond {:g} standard errors\n",
                                  c.material, c.quantity == "R" ? "reflectance R" : "SC + epidermis, reflector off: transmittance T",
                                  significance_sigmas);
    out += fmt::format("{:>13}  {:>18}  {:>18}  {:>20}\n", "wavelength_nm", "measured", "HG", "difference");
    for (const auto& r : c.rows) {
        out += fmt::format("{:>13g}  {:>18}  {:>18}  {:>20} {}\n", r.wavelength_nm, fmt::format("{:.4f} +- {:.4f}", r.measured.value, r.measured.stderr),
                           fmt::format("{:.4f} +- {:.4f}", r.hg.value, r.hg.stderr),
                           fmt::format("{:+.4f} +- {:.4f}", r.difference.value, r.difference.stderr), r.significant ? "*" : "");
    }
    out += fmt::format("significant at {} of {} wavelengths", c.significant_count, c.rows.size());
    if (c.delta_e00) out += fmt::format("; colour difference CIEDE2000 {:.2f} +- {:.2f} (D65)", *c.delta_e00, *c.delta_e00_uncertainty);
    return out + "\n\n";
}

void run_compare_phase(const ComparePhaseOptions& o) {
    const auto names = o.presets.empty() ? std::vector<std::string>{"biospec-lightly", "biospec-moderately", "biospec-heavily"} : o.presets;
    const auto hg = thin_layer_hg(o.hg_source, "--hg-source");
    std::vector<MaterialOverride> overrides;
    for (const auto& t : o.overrides) overrides.push_back(parse_override(t));
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::parse(o.wavelengths, "--wavelengths");
    request.stderr_target = o.stderr_target;
    request.max_rays_per_wavelength = o.max_rays;
    request.seed = o.seed;
    if (!o.plot.empty()) {
        if (!o.plot.ends_with(".png") && !o.plot.ends_with(".svg")) throw InputError("--plot " + o.plot + ": extension not supported (allowed: .png, .svg)");
        if (std::filesystem::exists(o.plot) && !o.overwrite) throw InputError(o.plot + ": exists already (use --overwrite to replace it)");
        OutputClaims::claim(o.plot, o.overwrite);
    }
    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);

    std::vector<PhaseComparison> comparisons;
    for (const auto& name : names) {
        const auto material = load_material(name, overrides);
        const auto* stack = std::get_if<LayerStack>(&material);
        if (!stack) throw InputError("material '" + name + "' is homogeneous; compare-phase needs a layered material");
        for (auto& c : compare_phase_in_skin(*stack, request, hg)) comparisons.push_back(std::move(c));
    }
    if (o.json) {
        Json all = Json::array();
        for (const auto& c : comparisons) all.push_back(comparison_json(c));
        std::cout << Json{{"skinspec_version", version}, {"hg_source", hg.source}, {"seed", o.seed}, {"comparisons", all}}.dump(2) << '\n';
    } else {
        std::cout << "HG source: " << hg.source << "\n\n";
        for (const auto& c : comparisons) std::cout << comparison_table(c);
    }
    if (!o.plot.empty()) {
        // Top: the spectra, measured solid and HG dashed in one colour per material and quantity; bottom: their
        // difference, the quantity of interest, with its +-2 combined standard errors.
        PlotPanel spectra{"Reflectance R, transmittance T (fraction)", {}, {}, {}};
        PlotPanel differences{"HG - measured (fraction)", {}, {}, {}};
        for (std::size_t i = 0; i < comparisons.size(); ++i) {
            const auto& c = comparisons[i];
            const auto style = distinct_series_style(i);
            const auto name = c.material + " " + c.quantity;
            PlotCurve measured{name + " measured", {}, {}, {}, style.colour, false};
            PlotCurve modelled{name + " HG", {}, {}, {}, style.colour, true};
            PlotCurve difference{name + " HG - measured", {}, {}, {}, style.colour, false, style.marker};
            for (const auto& r : c.rows) {
                for (auto* curve : {&measured, &modelled, &difference}) curve->x.push_back(r.wavelength_nm);
                measured.value.push_back(r.measured.value);
                measured.stderr.push_back(r.measured.stderr);
                modelled.value.push_back(r.hg.value);
                modelled.stderr.push_back(r.hg.stderr);
                difference.value.push_back(r.difference.value);
                difference.stderr.push_back(r.difference.stderr);
            }
            spectra.curves.push_back(std::move(measured));
            spectra.curves.push_back(std::move(modelled));
            differences.curves.push_back(std::move(difference));
        }
        write_figure(o.plot, "Measured (solid) vs HG (dashed) thin layers; R of the skin, T of SC + epidermis; bands +-2 s.e.", "Wavelength (nm)",
                     {spectra, differences});
        std::cerr << "wrote " << o.plot << '\n';
    }
}

}  // namespace

void add_compare_phase_command(CLI::App& app) {
    auto o = std::make_shared<ComparePhaseOptions>();
    auto* cmd = app.add_subcommand("compare-phase", "Measured vs Henyey-Greenstein scattering in the thin layers of the BioSpec skin model");
    cmd->add_option("--preset", o->presets, "Preset (repeatable; default lightly, moderately and heavily pigmented)");
    cmd->add_option("--set", o->overrides, set_option_help);
    cmd->add_option("--hg-source", o->hg_source, "g for HG: rms (fitted, Eq. 9), van-gemert, or a number in [-1, 1]")->capture_default_str();
    cmd->add_option("--wavelengths", o->wavelengths, "FIRST:LAST:STEP, one wavelength or a comma list (nm)")->capture_default_str();
    cmd->add_option("--stderr", o->stderr_target, "Standard error target per wavelength and run")->capture_default_str()->check(CLI::PositiveNumber);
    add_ray_count_option(*cmd, "--max-rays", o->max_rays, "Ray budget per wavelength and run")->capture_default_str();
    add_seed_option(*cmd, o->seed, "Random seed");
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--plot", o->plot, "Plot the spectra to FILE.png or FILE.svg");
    add_overwrite_flag(*cmd, o->overwrite, "Replace the --plot file if it exists");
    cmd->add_flag("--json", o->json, "Print the comparison as JSON");
    cmd->callback([o] { run_compare_phase(*o); });
}

}  // namespace skinspec::cli
