#include "cli/color_command.hpp"

#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli/color_output.hpp"
#include "spectral/data_paths.hpp"
#include "formats/spectrum_csv.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

struct ColorOptions {
    std::string file;
    std::string illuminant = "D65";
    std::string observer = "2";
    std::vector<std::string> spaces;
    bool json = false;
    bool allow_over_one = false;
    bool transmittance = false;
    std::string column;
    std::string material;
    std::size_t member = 0;
    std::vector<std::string> where;
};

void run_color(const ColorOptions& o) {
    const auto file = o.file.empty() ? data_file("spectra/example_reflectance.csv") : std::filesystem::path(o.file);
    SpectrumFileRules rules;
    rules.quantity = o.transmittance ? "transmittance" : "reflectance";
    rules.allow_over_one = o.allow_over_one;
    rules.column = o.column;
    rules.material = o.material;
    rules.member = o.member;
    for (const auto& w : o.where) {
        const auto eq = w.find('=');
        const auto value = eq == std::string::npos ? std::nullopt : parse_double(w.substr(eq + 1));
        if (!value || !std::isfinite(*value)) throw InputError("--where '" + w + "' must have the form FIELD=NUMBER (e.g. epidermis.melanosome_fraction=0.1)");
        rules.where.emplace_back(w.substr(0, eq), *value);
    }
    const auto illuminant = parse_illuminant(o.illuminant, "--illuminant");
    const auto observer = parse_observer(o.observer, "--observer");
    const auto [spectrum, standard_errors] = read_spectrum_file(file, rules);
    const TristimulusWeights weights(spectrum.wavelengths_nm(), illuminant, observer, spectrum.outside());
    std::optional<ColorUncertainty> uncertainty;
    if (!standard_errors.empty()) uncertainty = color_uncertainty(weights, spectrum.values(), standard_errors);
    const auto summary = summarize_color(weights.integrate(spectrum.values()), weights, illuminant, observer, o.spaces, uncertainty);

    const auto samples = spectrum.wavelengths_nm().size();
    const auto lo = spectrum.domain_min_nm();
    const auto hi = spectrum.domain_max_nm();
    if (o.json) {
        auto j = to_json(summary);
        j["file"] = file.string();
        j["quantity"] = rules.quantity;
        j["samples"] = samples;
        j["domain_nm"] = {lo, hi};
        j["outside_domain"] = "hold";
        std::cout << j.dump(2) << '\n';
        return;
    }
    std::cout << fmt::format("{:<16}{}\n{:<16}{} samples, {}-{} nm; held at the end values over the rest of 360-830 nm\n",
                             "spectrum", file.string(), "", samples, format_number(lo), format_number(hi))
              << to_table(summary);
}

}  // namespace

void add_color_command(CLI::App& app) {
    auto options = std::make_shared<ColorOptions>();
    auto* cmd = app.add_subcommand("color", "Colour of a reflectance or transmittance spectrum (CSV: wavelength_nm,value, or spectrum's own CSV)");
    cmd->add_option("file", options->file,
                    "Spectrum CSV; '#' comments and a header line allowed (default: data/spectra/example_reflectance.csv)");
    cmd->add_option("--illuminant", options->illuminant, "Illuminant: D65, D50, A or E")->capture_default_str();
    cmd->add_option("--observer", options->observer, "Observer: 2 (CIE 1931) or 10 (CIE 1964)")->capture_default_str();
    cmd->add_option("--space", options->spaces, "Also report this OCIO colour space (repeatable), e.g. 'Display P3'");
    cmd->add_flag("--json", options->json, "Print one JSON object instead of the table");
    cmd->add_flag("--allow-over-one", options->allow_over_one, "Accept values above 1 (e.g. fluorescent samples)");
    cmd->add_flag("--transmittance", options->transmittance, "The file holds a transmittance (only changes messages)");
    cmd->add_option("--column", options->column,
                    "Value column by header name, e.g. R or T of a 'skinspec spectrum --output F.csv' file (default: the second of "
                    "two columns, else R); a column VALUE_stderr next to it gives the colour's standard uncertainty");
    cmd->add_option("--material", options->material, "The rows of this material, in a file with a material column (e.g. spectrum's CSV)");
    cmd->add_option("--member", options->member, "A sweep's member by position, 1 = the first (a 'spectrum --vary' CSV)")->check(CLI::PositiveNumber);
    cmd->add_option("--where", options->where, "A sweep's member by a swept field's value, FIELD=NUMBER (repeatable: one per swept field)");
    cmd->callback([options] { run_color(*options); });
}

}  // namespace skinspec::cli
