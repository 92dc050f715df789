#include "cli/mcml_command.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "cli/common_options.hpp"
#include "cli/progress.hpp"
#include "cli/spectral_output.hpp"
#include "formats/mcml_files.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct McmlOptions {
    std::string file;
    std::uint64_t photons = 0;
    std::uint64_t seed = 1;
    bool seed_given = false;
    unsigned threads = 0;
    std::string boundaries;  // "" = random
    std::string solver = "rte";
    std::string json_output;
    std::string output_dir;
    bool overwrite = false;
    bool json = false;
};

void run_mcml(const McmlOptions& o) {
    auto runs = read_mci(o.file);
    // An .mci names its outputs; they stay in the output folder (or the current one): an absolute name or one
    // with '..' would write anywhere (it wrote /etc/passwd.mco and ../../escape.mco).
    for (const auto& run : runs) {
        const std::filesystem::path name(run.output_file);
        const bool climbs = std::any_of(name.begin(), name.end(), [](const std::filesystem::path& part) { return part == ".."; });
        if (name.is_absolute() || climbs) {
            throw InputError(o.file + ": output file '" + run.output_file + "' leaves the output folder (allowed: a name, or a path below the folder, without '..')");
        }
    }
    if (!o.output_dir.empty()) {
        if (!std::filesystem::is_directory(o.output_dir)) throw InputError("--output-dir " + o.output_dir + ": not a folder");
        for (auto& run : runs) run.output_file = (std::filesystem::path(o.output_dir) / run.output_file).string();
    }
    if (!o.boundaries.empty() && o.boundaries != "random" && o.boundaries != "split") {
        throw InputError("--boundaries: '" + o.boundaries + "' is not allowed (allowed: random, split)");
    }
    const bool deterministic = o.solver == "adding-doubling";
    if (!deterministic && o.solver != "rte") throw InputError("--solver: '" + o.solver + "' is not allowed (allowed: rte, adding-doubling)");
    if (deterministic && (o.photons > 0 || !o.boundaries.empty() || o.seed_given)) {
        throw InputError(std::string("--solver adding-doubling is deterministic: it takes no ") +
                         (o.photons > 0 ? "--photons" : !o.boundaries.empty() ? "--boundaries" : "--seed") + " (the volumetric walk does)");
    }
    for (const auto& run : runs) {
        if (run.output_format != 'A') throw InputError(o.file + ": output '" + run.output_file + "' asks for binary format B (only A is written)");
        // Its folder writable, its name short enough, not a folder, claimed (two runs naming one .mco are refused): before any run.
        const std::string extension = std::filesystem::path(run.output_file).extension().string();
        check_output_path(run.output_file, o.overwrite, {extension});
    }
    if (!o.json_output.empty()) check_output_path(o.json_output, o.overwrite, {".json"});
    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    Json all = Json::array();
    for (std::size_t i = 0; i < runs.size() && !InterruptGuard::interrupted(); ++i) {
        auto run = runs[i];
        if (o.photons > 0) run.photons = o.photons;
        auto request = mcml_request(run, o.seed, o.boundaries == "split" ? BoundaryMode::split : BoundaryMode::random);
        request.cancel = &InterruptGuard::cancel_flag();
        ProgressBar bar(fmt::format("run {}", i + 1));
        request.on_progress = [&bar](const Progress& p) { bar(p); };
        const auto start = std::chrono::steady_clock::now();
        if (deterministic) {
            AdOptions options;
            options.cancel = &InterruptGuard::cancel_flag();
            const auto ad = solve_adding_doubling(run.stack, {}, options);
            if (ad.cancelled) break;  // the runs finished are written; this one is not
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const auto totals = rte_totals(ad);
            const double absorbed = totals.absorbed.value;
            write_text_file(run.output_file,
                            mco_text(run, totals, fmt::format("skinspec {} adding-doubling: {} channels, accuracy {:.1e}, {:.4f} sec", version,
                                                              ad.channels, ad.accuracy, seconds),
                                     false),
                            true);
            auto j = mcml_run_json(run, totals, seconds);
            j["model"] = "adding-doubling";
            j["accuracy"] = ad.accuracy;
            all.push_back(std::move(j));
            if (!o.json) {
                std::cout << fmt::format("run {} -> {}: adding-doubling in {:.4f} s (accuracy {:.1e})\n", i + 1, run.output_file, seconds, ad.accuracy)
                          << fmt::format("  specular R {:.6f}; diffuse R {:.6f}; absorbed {:.6f}; T {:.6f}\n", ad.specular_reflectance,
                                         ad.diffuse_reflectance, absorbed, ad.transmittance);
            }
            continue;
        }
        const auto result = solve_rte(request);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        run.photons = result.photons;
        write_text_file(run.output_file,
                        mco_text(run, result, fmt::format("skinspec {} volumetric walk: {} photons in {:.2f} sec{}", version, result.photons,
                                                          seconds, result.partial ? " (INTERRUPTED)" : "")),
                        true);
        all.push_back(mcml_run_json(run, result, seconds));
        if (!o.json) {
            std::cout << fmt::format("run {} -> {}: {} photons in {:.2f} s ({:.3g} photons/s)\n", i + 1, run.output_file, result.photons, seconds,
                                     result.photons / seconds)
                      << fmt::format("  specular R {:.6f}; diffuse R {:.6f} +- {:.6f}; absorbed {:.6f} +- {:.6f}; T {:.6f} +- {:.6f}{}\n",
                                     result.specular_reflectance.value, result.diffuse_reflectance.value, result.diffuse_reflectance.stderr,
                                     result.absorbed.value, result.absorbed.stderr, result.transmittance.value, result.transmittance.stderr,
                                     result.truncated_photons ? fmt::format("; {} photons stopped at the step limit", result.truncated_photons) : "");
        }
        if (result.partial) break;
    }
    const Json doc{{"skinspec_version", version}, {"schema", "skinspec-rte-result/1"}, {"input", o.file}, {"seed", o.seed},
                   {"solver", o.solver}, {"boundaries", o.boundaries.empty() ? std::string("random") : o.boundaries}, {"runs", all}};
    if (o.json) std::cout << doc.dump(2) << '\n';
    if (!o.json_output.empty()) write_text_file(o.json_output, doc.dump(2) + "\n", true);
    if (InterruptGuard::interrupted()) std::exit(InterruptGuard::exit_code());
}

}  // namespace

void add_mcml_command(CLI::App& app) {
    auto o = std::make_shared<McmlOptions>();
    auto* cmd = app.add_subcommand("mcml", "Run an MCML .mci file with the volumetric walk; writes MCML .mco files (and JSON with standard errors)");
    cmd->add_option("file", o->file, "MCML input file (.mci)")->required();
    cmd->add_option("--photons", o->photons, "Override the photon count of every run")->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 50));
    add_seed_option(*cmd, o->seed, "Random seed (identical results for any thread count)");
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--boundaries", o->boundaries, "Fresnel at the outer boundaries: random (all-or-none, MCML; default) or split");
    cmd->add_option("--solver", o->solver,
                    "rte (the volumetric walk, every output) or adding-doubling (deterministic totals: the .mco's RAT and A_l)")
        ->capture_default_str();
    cmd->add_option("--output-dir", o->output_dir, "Write the .mco files here (default: the current folder, as MCML does)");
    cmd->add_option("--output", o->json_output, "Also write the results with standard errors as JSON to this file");
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing .mco / JSON files");
    cmd->add_flag("--json", o->json, "Print the JSON on standard output");
    cmd->callback([o, cmd] {
        o->seed_given = cmd->count("--seed") > 0;
        run_mcml(*o);
    });
}

}  // namespace skinspec::cli
