#include "cli/iad_command.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "cli/common_options.hpp"
#include "cli/progress.hpp"
#include "formats/rxt_file.hpp"
#include "inverse/iad/inverse_adding_doubling.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;


struct IadOptions {
    std::string input;
    std::optional<double> m_r, m_t, m_u;
    std::map<std::string, double> setup;  // a setup field's key -> the value given (setup_fields())
    MeasurementUncertainty uncertainty;
    IadSettings settings;
    unsigned threads = 0;
    std::string output;
    bool force = false;
    bool json = false;
    bool skip_unreachable = false;
};

std::string option_name(std::string_view key) {
    std::string name(key);
    std::replace(name.begin(), name.end(), '_', '-');
    return "--" + name;
}

std::string cell(const std::optional<double>& v) { return v ? fmt::format("{:.9g}", *v) : std::string(); }

std::string csv_of(const std::vector<IadRow>& rows, const SlabSetup& header, const std::string& input, const IadOptions& o, bool partial) {
    std::string out = fmt::format("# skinspec {} iad result (docs/IAD.md){}\n# units:", version, partial ? ", partial (stopped)" : "");
    for (const auto& f : iad_result_fields()) out += fmt::format(" {} [{}];", f.key, f.unit);
    out += fmt::format("\n# input {}, channels {}, tolerance {}", input, o.settings.channels, o.settings.tolerance);
    if (o.uncertainty.given()) out += fmt::format(", measurement uncertainties M_R {} M_T {} M_U {}", o.uncertainty.m_r, o.uncertainty.m_t, o.uncertainty.m_u);
    out += "\n# setup:";
    for (const auto& f : setup_fields()) out += fmt::format(" {} {};", f.key, format_number(header.*(f.member)));
    out += "\nsource,unknowns";
    for (const auto& f : iad_result_fields()) out += "," + std::string(f.key);
    out += '\n';
    for (const auto& r : rows) {
        out += fmt::format("\"{}\",{}", r.measurement.source, to_string(r.result.unknowns));
        for (const auto& f : iad_result_fields()) {
            out += ',';
            out += cell(f.value(r));
        }
        out += '\n';
    }
    return out;
}

std::string table_of(const std::vector<IadRow>& rows, bool uncertain) {
    std::string out = fmt::format("{:>10}  {:>8} {:>8}  {:>8} {:>8}  {:>10}{}  {:>10}{}  {:>7}  {:>8}  {}\n", "row", "M_R", "fit", "M_T", "fit", "mu_a/mm",
                                  uncertain ? fmt::format(" {:>9}", "+-") : "", "mu_s'/mm", uncertain ? fmt::format(" {:>9}", "+-") : "", "g", "albedo", "unknowns");
    const auto number = [](const std::optional<double>& v, int width) {
        return v ? (std::isinf(*v) ? fmt::format("{:>{}}", "undet.", width) : fmt::format("{:>#{}.5g}", *v, width)) : fmt::format("{:>{}}", "-", width);
    };
    const auto fraction = [](const std::optional<double>& v) { return v ? fmt::format("{:>8.5f}", *v) : fmt::format("{:>8}", "-");
    };
    for (const auto& r : rows) {
        const auto& m = r.measurement;
        const auto colon = m.source.rfind(':');
        const std::string label = m.wavelength_nm ? fmt::format("{:g} nm", *m.wavelength_nm) : colon == std::string::npos ? "-" : "line " + m.source.substr(colon + 1);
        out += fmt::format("{:>10}  {:>8.5f} {:>8.5f}  {} {}  {}{}  {}{}  {:>7.4f}  {:>8.6f}  {}\n", label, *m.m_r, r.result.fitted.m_r, fraction(m.m_t),
                           fraction(m.m_t ? std::optional(r.result.fitted.m_t) : std::nullopt), number(r.result.mu_a_per_mm, 10),
                           uncertain ? " " + number(r.result.mu_a_stderr_per_mm, 9) : "", number(r.result.mu_s_reduced_per_mm, 10),
                           uncertain ? " " + number(r.result.mu_s_reduced_stderr_per_mm, 9) : "", r.result.optics.g, r.result.optics.albedo, to_string(r.result.unknowns));
    }
    return out;
}

void run_iad(const IadOptions& o) {
    const auto one = [](const std::optional<double>& v) { return v ? std::vector<double>{*v} : std::vector<double>{}; };
    const auto input = iad_input(o.input.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.input), {one(o.m_r), one(o.m_t), one(o.m_u), {}},
                                 o.setup);
    const auto& header = input.setup;
    const auto& measurements = input.rows;
    if (!o.output.empty()) check_output_path(o.output, o.force, {".csv", ".json"});

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    auto settings = o.settings;
    settings.cancel = &InterruptGuard::cancel_flag();
    const auto start = std::chrono::steady_clock::now();
    IadRun run;
    {
        ProgressBar bar("iad", "rows");
        run = invert_rows(measurements, o.uncertainty, settings, [&](std::size_t done, std::size_t total) { bar(Progress{0, 0, done, total}); });
        bar.clear();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& rows = run.rows;
    const auto& unreachable = run.unreachable;
    if (!unreachable.empty() && !o.skip_unreachable) {
        std::string list;
        for (std::size_t i = 0; i < std::min<std::size_t>(unreachable.size(), 5); ++i) list += "\n  " + unreachable[i];
        throw InputError(fmt::format("{} of {} measurements are unreachable (nothing written; --skip-unreachable writes the others):{}{}", unreachable.size(),
                                     measurements.size(), list, unreachable.size() > 5 ? fmt::format("\n  ... and {} more", unreachable.size() - 5) : ""));
    }
    const bool partial = InterruptGuard::interrupted();
    for (const auto& u : unreachable) std::cerr << "skinspec: skipped: " << u << '\n';
    const Json doc = o.json || o.output.ends_with(".json") ? iad_json(run, header, input.name, o.settings, o.uncertainty, partial, seconds) : Json{};
    std::cout << (o.json ? doc.dump(2) + "\n" : table_of(rows, o.uncertainty.given()));
    if (!o.output.empty()) {
        write_text_file(o.output, o.output.ends_with(".json") ? doc.dump(2) + "\n" : csv_of(rows, header, input.name, o, partial), true);
        std::cerr << "wrote " << o.output << '\n';
    }
    std::cerr << fmt::format("{} of {} rows inverted in {:.3f} s ({:.1f} ms per row, {} forward solutions, {} channels)\n", rows.size(), measurements.size(),
                             seconds, rows.empty() ? 0.0 : 1e3 * seconds / static_cast<double>(rows.size()), run.evaluations, o.settings.channels);
    if (partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": the " << rows.size() << " rows finished were written, marked partial\n";
        std::exit(InterruptGuard::exit_code());
    }
}

}  // namespace

void add_iad_command(CLI::App& app) {
    auto o = std::make_shared<IadOptions>();
    auto* cmd = app.add_subcommand("iad",
                                   "Optical properties (mu_a, mu_s', g) of a slab from measured reflection and transmission: inverse "
                                   "adding-doubling with Prahl's sphere corrections, reading iad's .rxt files (docs/IAD.md)");
    cmd->add_option("input", o->input, "iad measurement file (.rxt); or give -r [-t [-u]]");
    cmd->add_option("-r,--reflectance", o->m_r, "Measured M_R (total reflection, normalised to the standard)");
    cmd->add_option("-t,--transmittance", o->m_t, "Measured M_T (total transmission)");
    cmd->add_option("-u,--unscattered", o->m_u, "Measured unscattered (collimated) transmission M_U: g is then fitted too");
    for (const auto& f : setup_fields()) {
        const std::string key(f.key);
        cmd->add_option_function<double>(
               option_name(f.key), [o, key](const double& v) { o->setup[key] = v; },
               fmt::format("{} [{}], {}{} (default {})", f.doc, f.unit, f.range.text(),
                           f.rxt_letter ? fmt::format("; column '{}' of a file", f.rxt_letter) : "", format_number(SlabSetup{}.*(f.member))))
            ->group("Setup (overrides the file's header and columns)");
    }
    cmd->add_option("--r-uncertainty", o->uncertainty.m_r, "Standard uncertainty of M_R (absolute), propagated to the results")->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--t-uncertainty", o->uncertainty.m_t, "Standard uncertainty of M_T (absolute)")->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--u-uncertainty", o->uncertainty.m_u, "Standard uncertainty of M_U (absolute)")->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--channels", o->settings.channels, "Adding-doubling quadrature channels per hemisphere (iad -q; iad's default 8 is ~5e-4 off in R)")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{4}, std::size_t{256}));
    cmd->add_option("--tolerance", o->settings.tolerance, "Largest |predicted - measured| accepted as a fit")->capture_default_str()->check(CLI::Range(1e-12, 0.1));
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--output", o->output, "Write the results to FILE.csv or FILE.json");
    add_overwrite_flag(*cmd, o->force, "Replace the --output file if it exists");
    cmd->add_flag("--json", o->json, "Print the results as JSON");
    cmd->add_flag("--skip-unreachable", o->skip_unreachable, "Leave out measurements no slab can produce (listed on stderr) instead of refusing");
    cmd->callback([o] { run_iad(*o); });
}

}  // namespace skinspec::cli
