#include "cli/phase_study_command.hpp"

#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/common_options.hpp"
#include "cli/spectral_output.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/line_plot.hpp"
#include "spectral/text_fields.hpp"
#include "studies/phase_study/phantom_sheet.hpp"
#include "studies/phase_study/phase_study.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

struct PhaseStudyOptions {
    std::string output_dir;
    std::string background;
    std::string separations = "0.2,0.9,1.8";
    std::uint64_t seed = 1;
    bool json = false;
    bool overwrite = false;
};

std::string case_name(const std::string& tissue, double wavelength_nm) { return fmt::format("{}_{:g}nm", tissue, wavelength_nm); }
std::string case_name(const PhaseCase& c) { return case_name(c.tissue, c.wavelength_nm); }

// Every file --output-dir gets, from the study's cases (known before it runs).
std::vector<std::filesystem::path> output_files(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> files{dir / "goniometer_btdf.csv"};
    for (const auto& [tissue, nm] : phase_study_cases()) {
        files.push_back(dir / ("goniometer_" + case_name(tissue, nm) + ".png"));
        files.push_back(dir / ("phantom_" + case_name(tissue, nm) + ".png"));
    }
    return files;
}

std::string approach_label(PhaseApproach a) {
    switch (a) {
        case PhaseApproach::table_lookup: return "table look-up";
        case PhaseApproach::hg_rms: return "HG, g RMS";
        case PhaseApproach::hg_van_gemert: return "HG, g van Gemert";
    }
    return "?";
}

void print_tables(const PhaseStudy& s) {
    std::cout << "Table 2: HG asymmetry factors (Eq. 9 RMS over the 13 bins, Nelder-Mead over [-1, 1])\n";
    std::cout << fmt::format("{:<26}", "");
    for (const auto& c : s.cases) std::cout << fmt::format("{:>22}", case_name(c));
    std::cout << fmt::format("\n{:<26}", "g, RMS fit");
    for (const auto& c : s.cases) std::cout << fmt::format("{:>22.4f}", c.rms_fit.g);
    std::cout << fmt::format("\n{:<26}", "RMS at that g");
    for (const auto& c : s.cases) std::cout << fmt::format("{:>22.5f}", c.rms_fit.rms);
    std::cout << fmt::format("\n{:<26}", "g, van Gemert et al. 1989");
    for (const auto& c : s.cases) std::cout << fmt::format("{:>22.3f}", c.g_van_gemert);
    std::cout << fmt::format("\n{:<26}", "RMS at van Gemert's g");
    for (const auto& c : s.cases) std::cout << fmt::format("{:>22.5f}", c.rms_van_gemert);
    std::cout << "\n\nTable 3: relative error (%) of sampled bin fractions, max / average over the 13 bins\n";
    for (std::size_t a = 0; a < 3; ++a) {
        std::cout << fmt::format("{:<26}", approach_label(all_phase_approaches[a]));
        for (const auto& c : s.cases) {
            std::cout << fmt::format("{:>22}", fmt::format("{:.2f} / {:.2f}", c.errors[a].max_percent, c.errors[a].average_percent));
        }
        std::cout << '\n';
    }
    std::cout << fmt::format("\nCost: HG warping {:.2f} ns/sample, table look-up {:.2f} ns/sample: HG costs {:.2f}x the look-up\n",
                             1e9 * s.seconds_per_sample_hg, 1e9 * s.seconds_per_sample_lookup,
                             s.seconds_per_sample_hg / s.seconds_per_sample_lookup);
}

void write_files(const PhaseStudy& s, const PhaseStudyOptions& o) {
    const auto& cm = ColorManagement::builtin();
    const auto background_file = o.background.empty() ? data_file("images/phantom_background.png") : std::filesystem::path(o.background);
    const auto background = read_linear_image(background_file, "Linear Rec.709", cm);
    const auto separations = WavelengthGrid::parse(o.separations, "--separations");  // positive, increasing numbers
    const auto files = output_files(o.output_dir);

    std::string csv = "# skinspec phase-study: virtual goniometer BTDF (Baranoski et al. 2005 Eq. 10) per polar bin, 1/sr\n"
                      "tissue,wavelength_nm,bin_low_deg,bin_high_deg,measured,table_lookup,hg_rms,hg_van_gemert\n";
    for (const auto& c : s.cases) {
        for (std::size_t b = 0; b + 1 < s.bin_edges_deg.size(); ++b) {
            csv += fmt::format("{},{:g},{:g},{:g},{:.6g},{:.6g},{:.6g},{:.6g}\n", c.tissue, c.wavelength_nm, s.bin_edges_deg[b],
                               s.bin_edges_deg[b + 1], c.btdf_measured_per_sr[b], c.btdf_per_sr[0][b], c.btdf_per_sr[1][b],
                               c.btdf_per_sr[2][b]);
        }
    }
    write_text_file(files[0].string(), csv, true);

    for (std::size_t i = 0; i < s.cases.size(); ++i) {
        const auto& c = s.cases[i];
        std::vector<double> centres;
        for (std::size_t b = 0; b + 1 < s.bin_edges_deg.size(); ++b) centres.push_back(0.5 * (s.bin_edges_deg[b] + s.bin_edges_deg[b + 1]));
        std::vector<PlotCurve> curves;
        for (std::size_t a = 0; a < 3; ++a) {
            const auto style = distinct_series_style(a);
            curves.push_back({approach_label(all_phase_approaches[a]), centres, c.btdf_per_sr[a], {}, style.colour, false, style.marker});
        }
        // Drawn last, black with open circles, so that the curves that agree with it do not hide it.
        curves.push_back({"measured (Bruls & van der Leun)", centres, c.btdf_measured_per_sr, {}, {0.1, 0.1, 0.1}, true, 5});
        write_line_plot(files[1 + 2 * i], fmt::format("Virtual goniometer: {} at {:g} nm", c.tissue, c.wavelength_nm),
                        "Polar angle (deg)", "BTDF (1/sr)", curves);

        std::vector<LinearImage> panels;
        std::vector<std::string> labels;
        for (const double separation : separations.nm()) {
            for (std::size_t a = 0; a < 3; ++a) {
                PhantomView view;
                view.separation = separation;
                view.seed = o.seed;
                panels.push_back(render_phantom(background, c.samplers[a], view));
                labels.push_back(fmt::format("{}\nseparation {:g}", approach_label(all_phase_approaches[a]), separation));
            }
        }
        write_image_grid(files[2 + 2 * i], panels, 3, labels, "Linear Rec.709", "sRGB", "Standard",
                         {{"Software", std::string("skinspec ") + version},
                          {"ImageDescription", fmt::format("phantom sheet, {} at {:g} nm profile; background width 8 units", c.tissue,
                                                           c.wavelength_nm)}},
                         cm);
    }
    for (const auto& f : files) std::cerr << "wrote " << f.string() << '\n';
}

void run_phase_study_command(const PhaseStudyOptions& o) {
    if (!o.output_dir.empty() && std::filesystem::exists(o.output_dir) && !std::filesystem::is_directory(o.output_dir)) {
        throw InputError("--output-dir " + o.output_dir + ": exists and is not a folder");
    }
    // Made before the study, so that a folder that cannot be made fails at once (/proc/nope failed after the study).
    if (!o.output_dir.empty()) {
        std::error_code error;
        std::filesystem::create_directories(o.output_dir, error);
        if (error) throw InputError("--output-dir " + o.output_dir + ": cannot be made (" + error.message() + ")");
        // Every output and input checked before the study (an existing file was refused after 6-9 s of it).
        for (const auto& f : output_files(o.output_dir)) check_output_path(f, o.overwrite, {".csv", ".png"});
        WavelengthGrid::parse(o.separations, "--separations");
        if (!o.background.empty()) open_input_file(o.background, "--background");
    }
    PhaseStudySettings settings;
    settings.seed = o.seed;
    const auto study = run_phase_study(settings);
    if (o.json) std::cout << phase_study_json(study).dump(2) << '\n';
    else print_tables(study);
    if (!o.output_dir.empty()) write_files(study, o);
}

}  // namespace

void add_phase_study_command(CLI::App& app) {
    auto o = std::make_shared<PhaseStudyOptions>();
    auto* cmd = app.add_subcommand("phase-study", "Reproduce Baranoski et al. 2005: HG fits, sampling errors, goniometer, cost, phantom sheets");
    cmd->add_option("--output-dir", o->output_dir, "Write goniometer CSV and plots and phantom-sheet images here");
    cmd->add_option("--background", o->background, "Phantom background image (any OpenImageIO format; default data/images/phantom_background.png)");
    cmd->add_option("--separations", o->separations, "Sheet-to-background separations, comma list (background is 8 units wide)")->capture_default_str();
    add_seed_option(*cmd, o->seed, "Random seed");
    cmd->add_flag("--json", o->json, "Print every table's numbers as one JSON object");
    add_overwrite_flag(*cmd, o->overwrite, "Replace existing files in --output-dir");
    cmd->callback([o] { run_phase_study_command(*o); });
}

}  // namespace skinspec::cli
