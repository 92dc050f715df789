// skinspec: spectral simulator of human skin appearance. Command-line entry point: parses arguments,
// dispatches to one command per file in cli/, and turns input errors into one-line messages with exit 2.
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/bench_command.hpp"
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
#include "skinspec/version.hpp"
#include "spectral/input_error.hpp"

int main(int argc, char** argv) {
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
    skinspec::cli::add_bench_command(app);
    skinspec::cli::add_stress_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const skinspec::InputError& e) {
        std::cerr << "skinspec: error: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "skinspec: internal error: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
