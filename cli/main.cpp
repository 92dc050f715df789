// skinspec: spectral simulator of human skin appearance. Command-line entry point: parses arguments,
// dispatches to one command per file in cli/, and turns input errors into one-line messages with exit 2.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/bench_command.hpp"
#include "cli/common_options.hpp"
#include "spectral/atomic_file.hpp"
#include "cli/export_command.hpp"
#include "cli/process_group.hpp"
#include "spectral/image_files.hpp"
#include "cli/stress_command.hpp"
#include "cli/color_command.hpp"
#include "cli/materials_command.hpp"
#include "cli/spectrum_command.hpp"
#include "cli/swatch_command.hpp"
#include "cli/phase_study_command.hpp"
#include "cli/compare_phase_command.hpp"
#include "cli/mcml_command.hpp"
#include "cli/profile_command.hpp"
#include "cli/fit_profile_command.hpp"
#include "cli/fit_image_command.hpp"
#include "cli/fit_spectrum_command.hpp"
#include "cli/iad_command.hpp"
#include "skinspec/version.hpp"
#include "spectral/input_error.hpp"

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// "did you mean --wavelengths?" for each unexpected --option, from the options of the command it was given to.
void suggest_options(const CLI::App& app, const std::vector<std::string>& unexpected) {
    const CLI::App* command = &app;
    while (!command->get_subcommands().empty()) command = command->get_subcommands().back();
    for (const auto& arg : unexpected) {
        if (!arg.starts_with("--")) continue;
        const auto given = arg.substr(2, arg.find('=') == std::string::npos ? std::string::npos : arg.find('=') - 2);
        std::string best;
        std::size_t best_distance = std::max<std::size_t>(2, given.size() / 3) + 1;
        for (const auto* option : command->get_options()) {
            for (const auto& name : option->get_lnames()) {
                const auto d = edit_distance(given, name);
                if (d < best_distance || (name.starts_with(given) && given.size() >= 3 && best.empty())) {
                    best_distance = std::min(d, best_distance);
                    best = name;
                }
            }
        }
        if (!best.empty()) std::cerr << "skinspec: '--" << given << "' is not an option of '" << command->get_name() << "'; did you mean --" << best << "?\n";
    }
}

// A first argument that names no command: "did you mean spectrum?" and the list, instead of CLI11's "A subcommand is
// required"; no argument at all: the help. True when it said so (exit 2).
bool unknown_command(const CLI::App& app, int argc, char** argv, bool print) {
    std::vector<std::string> names;
    for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
    if (argc < 2) {
        if (print) std::cerr << app.help() << "skinspec: error: a command is required (skinspec COMMAND --help for its options)\n";
        return true;
    }
    const std::string given = argv[1];
    if (given.starts_with("-") || std::find(names.begin(), names.end(), given) != names.end()) return false;
    std::string best, list;
    std::size_t best_distance = std::max<std::size_t>(2, given.size() / 3) + 1;
    for (const auto& name : names) {
        list += (list.empty() ? "" : ", ") + name;
        const auto d = edit_distance(given, name);
        if (d < best_distance) {
            best_distance = d;
            best = name;
        }
    }
    if (print) std::cerr << "skinspec: error: '" << given << "' is not a command" << (best.empty() ? "" : "; did you mean '" + best + "'?") << " (commands: " << list << ")\n";
    return true;
}

// What the command printed must have reached standard output: a full disk or a closed pipe is a failure (said on
// standard error).
bool standard_output_written() {
    errno = 0;
    std::cout.flush();
    if (std::cout && std::fflush(stdout) == 0 && !std::ferror(stdout)) return true;
    const int cause = errno;
    std::cerr << "skinspec: error: writing to standard output failed" << (cause ? std::string(": ") + std::strerror(cause) : std::string()) << '\n';
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    skinspec::cli::join_process_group(argc, argv);
    CLI::App app{"skinspec: spectral simulator of human skin appearance"};
    app.set_version_flag("--version", std::string("skinspec ") + skinspec::version);
    app.require_subcommand(1);
    skinspec::cli::add_color_command(app);
    skinspec::cli::add_materials_command(app);
    skinspec::cli::add_spectrum_command(app);
    skinspec::cli::add_swatch_command(app);
    skinspec::cli::add_phase_study_command(app);
    skinspec::cli::add_compare_phase_command(app);
    skinspec::cli::add_mcml_command(app);
    skinspec::cli::add_profile_command(app);
    skinspec::cli::add_fit_profile_command(app);
    skinspec::cli::add_fit_spectrum_command(app);
    skinspec::cli::add_fit_image_command(app);
    skinspec::cli::add_iad_command(app);
    skinspec::cli::add_bench_command(app);
    skinspec::cli::add_stress_command(app);
    skinspec::cli::add_export_command(app);
    skinspec::cli::check_option_values(app);
    // With several processes only rank 0 reports an input error (every rank finds the same one); any error stops them all.
    const bool root = skinspec::cli::is_root_process();
    if (unknown_command(app, argc, argv, root)) return skinspec::cli::error_exit(2);
    const skinspec::OutputClaims outputs;  // the command's output files (spectral/atomic_file.hpp)
    try {
        app.parse(argc, argv);
    } catch (const CLI::ExtrasError& e) {
        const int code = app.exit(e);
        suggest_options(app, app.remaining());
        // Down the chain of chosen subcommands (export lut): each keeps what it did not expect.
        for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
            sub = sub->get_subcommands().back();
            suggest_options(app, sub->remaining());
        }
        return code;
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);  // --help and --version print and exit 0: what they printed must have arrived
        return code == 0 && !standard_output_written() ? skinspec::cli::error_exit(1) : code;
    } catch (const skinspec::InputError& e) {
        if (root) std::cerr << "skinspec: error: " << e.what() << '\n';
        return skinspec::cli::error_exit(2);
    } catch (const skinspec::ImageModuleError& e) {
        std::cerr << "skinspec: error: " << e.what() << " (rebuild with ./scripts/setup.sh, or set SKINSPEC_IMAGE_MODULE)\n";
        return skinspec::cli::error_exit(1);
    } catch (const std::exception& e) {
        std::cerr << "skinspec: internal error: " << e.what() << '\n';
        return skinspec::cli::error_exit(1);
    }
    return standard_output_written() ? 0 : skinspec::cli::error_exit(1);
}
