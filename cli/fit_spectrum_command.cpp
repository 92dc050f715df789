#include "cli/fit_spectrum_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "cli/common_options.hpp"
#include "cli/material_options.hpp"
#include "cli/progress.hpp"
#include "cli/solver_options.hpp"
#include "formats/measured_spectra.hpp"
#include "inverse/spectrum_fit/spectrum_fit.hpp"
#include "materials/material_file.hpp"
#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/line_plot.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

using Json = nlohmann::ordered_json;

// A fit whose model's stated accuracy exceeds this fraction of its residual RMS is reported (the quadrature, not the
// skin, may shape it).
constexpr double fit_model_accuracy_worth_a_warning = 0.5;

struct FitSpectrumOptions {
    std::string measured;
    std::string preset;
    std::string material;
    std::vector<std::string> overrides;
    std::string variant;
    std::vector<std::string> free;
    std::vector<std::string> bounds;
    std::vector<std::string> weights;
    std::vector<std::string> spectra;
    std::string window;  // "" = every wavelength of the file
    double incidence_deg = 0.0;
    std::uint64_t rays = 20'000;
    std::uint64_t seed = 1;
    std::size_t starts = SpectrumFitSettings{}.starts;
    unsigned threads = 0;
    SolverOptions solver;
    std::vector<std::string> walk_options_given;  // --rays, --seed as given (the exact model takes neither)
    std::string output;
    std::string plot;
    bool force = false;
    bool json = false;
};

// "FROM:TO" (two finite numbers).
std::pair<double, double> parse_range(std::string_view text, const std::string& what) {
    const auto colon = text.find(':');
    const auto a = colon == std::string_view::npos ? std::nullopt : parse_double(text.substr(0, colon));
    const auto b = colon == std::string_view::npos ? std::nullopt : parse_double(text.substr(colon + 1));
    if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b)) throw InputError(what + " '" + std::string(text) + "': must be LO:HI (two numbers)");
    return {*a, *b};
}

std::vector<FitParameter> free_parameters(const FitSpectrumOptions& o) {
    std::vector<FitParameter> free;
    if (o.free.empty()) free = default_free_parameters();
    for (const auto& key : o.free) free.push_back({key, {}, {}});
    for (const auto& b : o.bounds) {
        const auto eq = b.find('=');
        if (eq == std::string::npos) throw InputError("--bounds '" + b + "': must be FIELD=LO:HI");
        const auto key = std::string(trim(std::string_view(b).substr(0, eq)));
        const auto [lo, hi] = parse_range(std::string_view(b).substr(eq + 1), "--bounds " + key);
        if (!(lo < hi)) throw InputError("--bounds " + b + ": LO must be below HI");
        const auto it = std::find_if(free.begin(), free.end(), [&](const FitParameter& p) { return p.key == key; });
        if (it == free.end()) throw InputError("--bounds " + key + ": not a free parameter (free: " + [&] {
            std::string keys;
            for (const auto& p : free) keys += (keys.empty() ? "" : ", ") + p.key;
            return keys;
        }() + ")");
        it->lo = lo;
        it->hi = hi;
    }
    return free;
}

std::vector<WavelengthWeight> weights_of(const FitSpectrumOptions& o) {
    std::vector<WavelengthWeight> out;
    for (const auto& w : o.weights) {
        const auto eq = w.find('=');
        const auto value = eq == std::string::npos ? std::nullopt : parse_double(std::string_view(w).substr(eq + 1));
        if (!value || !std::isfinite(*value) || *value < 0.0) throw InputError("--weight '" + w + "': must be FROM:TO=W with W >= 0");
        const auto [from, to] = parse_range(std::string_view(w).substr(0, eq), "--weight");
        if (!(from <= to)) throw InputError("--weight '" + w + "': FROM must not exceed TO");
        out.push_back({from, to, *value});
    }
    return out;
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json fit_json(const SpectrumFit& f) {
    Json parameters = Json::object(), stderr = Json::object(), bound = Json::array();
    for (std::size_t i = 0; i < f.parameter_keys.size(); ++i) {
        parameters[f.parameter_keys[i]] = f.parameters[i];
        stderr[f.parameter_keys[i]] = number_or_null(f.parameter_stderr[i]);
        if (f.on_bound[i]) bound.push_back(f.parameter_keys[i]);
    }
    std::vector<double> residual;
    for (std::size_t w = 0; w < f.measured.size(); ++w) residual.push_back(f.fitted[w] - f.measured[w]);
    const auto lab = [](const Lab& l) { return Json::array({l.L, l.a, l.b}); };
    return Json{{"name", f.name},
                {"parameters", parameters},
                {"parameter_stderr", stderr},
                {"on_bound", bound},
                {"rms", f.rms},
                {"model_accuracy", f.model_accuracy ? Json(*f.model_accuracy) : Json(nullptr)},
                {"delta_e2000", f.delta_e2000},
                {"measured_lab", lab(f.measured_lab)},
                {"fitted_lab", lab(f.fitted_lab)},
                {"wavelength_nm", f.wavelength_nm},
                {"measured", f.measured},
                {"fitted", f.fitted},
                {"fitted_stderr", f.fitted_stderr},
                {"residual", residual},
                {"evaluations", f.evaluations},
                {"seconds", f.seconds}};
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const auto n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

std::string csv_of(const std::vector<SpectrumFit>& fits, const std::string& provenance, bool partial) {
    std::string out = fmt::format("# skinspec {} fit-spectrum (docs/SPECTRUM_FIT.md)\n# {}\n", version, provenance);
    if (partial) out += "# partial: true (stopped; the fits below finished, the others were not written)\n";
    if (fits.empty()) return out;
    out += "name";
    const auto& first = fits.front();
    for (const auto& k : first.parameter_keys) out += "," + k + "," + k + "_stderr";
    out += ",on_bound,rms,model_accuracy,delta_e2000,measured_L,measured_a,measured_b,fitted_L,fitted_a,fitted_b";
    for (const double nm : first.wavelength_nm) out += fmt::format(",fitted_{:g}nm", nm);
    for (const double nm : first.wavelength_nm) out += fmt::format(",fitted_stderr_{:g}nm", nm);
    out += '\n';
    for (const auto& f : fits) {
        out += f.name;
        std::string bound;
        for (std::size_t i = 0; i < f.parameters.size(); ++i) {
            out += fmt::format(",{:.6g},{}", f.parameters[i], std::isfinite(f.parameter_stderr[i]) ? fmt::format("{:.3g}", f.parameter_stderr[i]) : "");
            if (f.on_bound[i]) bound += (bound.empty() ? "" : ";") + f.parameter_keys[i];
        }
        out += fmt::format(",{},{:.5f},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}", bound, f.rms,
                           f.model_accuracy ? fmt::format("{:.5f}", *f.model_accuracy) : "", f.delta_e2000, f.measured_lab.L,
                           f.measured_lab.a, f.measured_lab.b, f.fitted_lab.L, f.fitted_lab.a, f.fitted_lab.b);
        for (const double v : f.fitted) out += fmt::format(",{:.5f}", v);
        for (const double v : f.fitted_stderr) out += fmt::format(",{:.5f}", v);
        out += '\n';
    }
    return out;
}

std::string table_of(const std::vector<SpectrumFit>& fits) {
    if (fits.empty()) return "no spectrum was fitted\n";
    const auto& keys = fits.front().parameter_keys;
    std::size_t width = 24;
    for (const auto& k : keys) width = std::max(width, k.size());
    std::size_t name_width = 12;
    for (const auto& f : fits) name_width = std::max(name_width, f.name.size());
    std::string out = fmt::format("{:<{}}", "spectrum", name_width);
    for (const auto& k : keys) out += fmt::format("  {:>{}}", k, width);
    const bool stated = fits.front().model_accuracy.has_value();  // one engine for every fit
    out += fmt::format("  {:>7}{}  {:>6}  {:>13}\n", "rms", stated ? fmt::format("  {:>8}", "model +-") : "", "dE00", "L* meas/fit");
    for (const auto& f : fits) {
        out += fmt::format("{:<{}}", f.name, name_width);
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const std::string se = std::isfinite(f.parameter_stderr[i]) ? fmt::format("{:.2g}", f.parameter_stderr[i]) : "n/a";
            out += fmt::format("  {:>{}}", fmt::format("{:.4g} +- {}{}", f.parameters[i], se, f.on_bound[i] ? " *" : ""), width);
        }
        out += fmt::format("  {:>7.4f}{}  {:>6.2f}  {:>6.1f}/{:<6.1f}\n", f.rms, stated ? fmt::format("  {:>8.4f}", f.model_accuracy.value_or(0.0)) : "",
                           f.delta_e2000, f.measured_lab.L, f.fitted_lab.L);
    }
    if (std::any_of(fits.begin(), fits.end(), [](const SpectrumFit& f) { return std::find(f.on_bound.begin(), f.on_bound.end(), true) != f.on_bound.end(); })) {
        out += "* on a bound of its range (--bounds FIELD=LO:HI widens it)\n";
    }
    return out;
}

void write_fit_plot(const std::string& file, const std::vector<SpectrumFit>& fits) {
    std::vector<PlotCurve> spectra, residuals;
    for (std::size_t i = 0; i < fits.size(); ++i) {
        const auto& f = fits[i];
        const auto style = distinct_series_style(i);
        spectra.push_back({f.name + " measured", f.wavelength_nm, f.measured, {}, style.colour, true, style.marker});
        spectra.push_back({f.name + " fitted", f.wavelength_nm, f.fitted, f.fitted_stderr, style.colour, false, 0});
        std::vector<double> r;
        for (std::size_t w = 0; w < f.measured.size(); ++w) r.push_back(f.fitted[w] - f.measured[w]);
        residuals.push_back({f.name, f.wavelength_nm, r, f.fitted_stderr, style.colour, false, style.marker});
    }
    write_line_plot(file, "Measured and fitted R (bands: +-2 model s.e.)", "wavelength (nm)", "R", spectra);
    const auto path = std::filesystem::path(file);
    const auto residual_file = (path.parent_path() / (path.stem().string() + "-residuals" + path.extension().string())).string();
    write_line_plot(residual_file, "Fitted - measured R (bands: +-2 model s.e.)", "wavelength (nm)", "R fitted - R measured", residuals);
    std::cerr << "wrote " << file << " and " << residual_file << '\n';
}

void run_fit_spectrum(const FitSpectrumOptions& o) {
    // How the model is evaluated, checked before any input is read.
    const FitEngine engine = o.solver.mode.empty() ? FitEngine::replayed_walk : parse_fit_engine(o.solver.mode, "--mode");
    if (!traces_rays(engine) && !o.walk_options_given.empty()) {
        throw InputError(o.walk_options_given.front() + ": --mode " + o.solver.mode + " solves the model exactly at every evaluation and traces no "
                         "rays (--rays and --seed are for --mode biospec, the replayed walk)");
    }
    if (o.solver.switches.contains("channels") && traces_rays(engine)) {
        throw InputError("--channels: the quadrature of the exact modes (--mode biospec replays traced paths and has none)");
    }
    if (!o.output.empty()) check_output_path(o.output, o.force, {".csv", ".json"});
    if (!o.plot.empty()) {
        check_output_path(o.plot, o.force, {".png", ".svg"});
        const auto path = std::filesystem::path(o.plot);
        check_output_path(path.parent_path() / (path.stem().string() + "-residuals" + path.extension().string()), o.force, {".png", ".svg"});
    }
    const auto measured = read_measured_spectra(o.measured);
    std::vector<std::size_t> chosen;
    for (const auto& name : o.spectra) {
        const auto it = std::find(measured.names.begin(), measured.names.end(), name);
        if (it == measured.names.end()) {
            std::string names;
            for (const auto& n : measured.names) names += (names.empty() ? "" : ", ") + n;
            throw InputError("--spectra: '" + name + "' is not a column of " + measured.file + " (columns: " + names + ")");
        }
        chosen.push_back(static_cast<std::size_t>(it - measured.names.begin()));
    }
    if (chosen.empty()) {
        for (std::size_t i = 0; i < measured.names.size(); ++i) chosen.push_back(i);
    }

    std::vector<MaterialOverride> overrides;
    if (!o.variant.empty()) overrides.push_back({"model.variant", o.variant, "--variant"});
    for (const auto& t : o.overrides) overrides.push_back(parse_override(t));
    const std::string base_name = chosen_material(o.preset, o.material);
    const auto material = load_material(base_name, overrides);
    const auto* base = std::get_if<LayerStack>(&material);
    if (!base) throw InputError("material '" + base_name + "' is homogeneous: the fit needs a layered skin for the BioSpec walk");
    // The fit evaluates the BioSpec model: an override of a field it does not read would be ignored.
    check_overrides(chosen_solver(o.solver), material, overrides);

    SpectrumFitSettings settings;
    settings.engine = engine;
    if (const auto channels = solver_switches(o.solver).quadrature_channels) settings.channels = *channels;
    settings.free = free_parameters(o);
    if (!o.window.empty()) std::tie(settings.window_from_nm, settings.window_to_nm) = parse_range(o.window, "--window");
    settings.weights = weights_of(o);
    settings.rays_per_wavelength = o.rays;
    settings.seed = o.seed;
    settings.geometry = measurement_geometry(o.solver, chosen_solver(o.solver));
    settings.incidence_deg = o.incidence_deg;
    settings.starts = o.starts;
    settings.wavelength_sources = measured.row_sources;

    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const InterruptGuard interrupt;
    settings.cancel = &InterruptGuard::cancel_flag();

    const auto start = std::chrono::steady_clock::now();
    const SpectrumFitter fitter(*base, measured.wavelength_nm, settings);
    const double trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<std::optional<SpectrumFit>> slots;
    if (!fitter.cancelled()) {
        ProgressBar bar("fit-spectrum", "spectra");
        std::vector<std::string> names;
        std::vector<std::vector<double>> spectra;
        for (const auto i : chosen) {
            names.push_back(measured.names[i]);
            spectra.push_back(measured.reflectance[i]);
        }
        slots = fitter.fit_all(names, spectra, [&bar](std::size_t done, std::size_t total) { bar(Progress{0, 0, done, total}); });
        bar.clear();
    }
    std::vector<SpectrumFit> fits;
    for (auto& s : slots) {
        if (s) fits.push_back(std::move(*s));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const bool exact = !traces_rays(settings.engine);
    const std::string evaluation = exact ? fmt::format("{}, {} channels", to_string(settings.engine), settings.channels)
                                         : fmt::format("biospec walk, {} rays per wavelength, seed {}", o.rays, o.seed);
    const std::string provenance = fmt::format("material {} ({}), geometry {}, {}, window {}", base_name, base->model.variant,
                                               to_string(settings.geometry), evaluation, o.window.empty() ? "all" : o.window);
    std::vector<double> rms;
    for (const auto& f : fits) rms.push_back(f.rms);
    const auto bands = residual_bands(fits);
    // Written when anything was fitted, and when stopped (then marked partial, even with no fit finished).
    if (!fits.empty() || InterruptGuard::interrupted()) {
        // One document for standard output (--json) and for --output F.json.
        const auto document = [&] {
            Json fit_list = Json::array(), band_list = Json::array(), overrides_json = Json::array();
            for (const auto& f : fits) fit_list.push_back(fit_json(f));
            for (const auto& b : bands) band_list.push_back(Json{{"band", b.name}, {"mean_residual", b.mean_residual}});
            for (const auto& ov : overrides) overrides_json.push_back(Json{{"key", ov.key}, {"value", ov.value}});
            return Json{{"skinspec_version", version},
                        {"schema", "skinspec-spectrum-fit/1"},
                        {"measured_file", measured.file},
                        {"material", base_name},
                        {"variant", base->model.variant},
                        {"overrides", overrides_json},
                        {"geometry", std::string(to_string(settings.geometry))},
                        {"mode", std::string(to_string(settings.engine))},
                        {"rays_per_wavelength", exact ? Json(nullptr) : Json(o.rays)},
                        {"seed", exact ? Json(nullptr) : Json(o.seed)},
                        {"quadrature_channels", exact ? Json(settings.channels) : Json(nullptr)},
                        {"partial", fits.size() < chosen.size()},
                        {"median_rms", rms.empty() ? Json(nullptr) : Json(median(rms))},
                        {"worst_rms", rms.empty() ? Json(nullptr) : Json(*std::max_element(rms.begin(), rms.end()))},
                        {"mean_residual_by_band", band_list},
                        {"seconds", seconds},
                        {"fits", fit_list}};
        };
        const bool json_file = o.output.ends_with(".json");
        const Json doc = o.json || json_file ? document() : Json{};
        std::cout << (o.json ? doc.dump(2) + "\n" : table_of(fits));
        if (!o.output.empty()) write_text_file(o.output, json_file ? doc.dump(2) + "\n" : csv_of(fits, provenance, fits.size() < chosen.size()), true);
        if (!o.output.empty()) std::cerr << "wrote " << o.output << '\n';
        if (!o.plot.empty() && !fits.empty()) write_fit_plot(o.plot, fits);
    }
    if (!fits.empty()) {
        std::string band_text;
        for (const auto& b : bands) band_text += fmt::format("{}{} {:+.4f}", band_text.empty() ? "" : ", ", b.name, b.mean_residual);
        const std::string setup = exact ? "the model solved exactly at each evaluation" : fmt::format("paths: {} rays in {:.2f} s", fitter.rays(), trace_seconds);
        std::cerr << fmt::format("{} spectra fitted in {:.2f} s ({}; {:.2f} s per spectrum): median RMS {:.4f}, worst {:.4f}\n", fits.size(), seconds, setup,
                                 (seconds - trace_seconds) / static_cast<double>(fits.size()), median(rms), *std::max_element(rms.begin(), rms.end()))
                  << "mean residual (fitted - measured): " << band_text << '\n';
        // The exact model's quadrature error is systematic: where it is not small beside the residual, the fit may
        // follow the quadrature rather than the skin.
        std::vector<const SpectrumFit*> coarse;
        double largest = 0.0;
        for (const auto& f : fits) {
            if (!f.model_accuracy) continue;
            largest = std::max(largest, *f.model_accuracy);
            if (*f.model_accuracy > fit_model_accuracy_worth_a_warning * f.rms) coarse.push_back(&f);
        }
        if (exact) std::cerr << fmt::format("the model's stated accuracy at the fits ({} channels): largest {:.4f}\n", settings.channels, largest);
        if (!coarse.empty()) {
            std::cerr << fmt::format("skinspec: warning: at {} of {} fits (e.g. {}: {:.4f} against RMS {:.4f}) the model's stated accuracy is more "
                                     "than {:g} of the residual RMS: the {}-channel quadrature may shape the fit; --channels {} (about 8x the "
                                     "time) reduces it\n",
                                     coarse.size(), fits.size(), coarse.front()->name, *coarse.front()->model_accuracy, coarse.front()->rms,
                                     fit_model_accuracy_worth_a_warning, settings.channels, 2 * settings.channels);
        }
    }
    if (InterruptGuard::interrupted()) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": " << fits.size() << " of " << chosen.size()
                  << " spectra were fitted and written\n";
        std::exit(InterruptGuard::exit_code());
    }
}

}  // namespace

void add_fit_spectrum_command(CLI::App& app) {
    auto o = std::make_shared<FitSpectrumOptions>();
    auto* cmd = app.add_subcommand("fit-spectrum",
                                   "Fit biophysical parameters (melanin, blood, oxygenation, ...) to measured skin reflectance spectra "
                                   "with the BioSpec walk on replayed paths");
    cmd->add_option("measured", o->measured, "CSV: wavelength_nm, then one column per spectrum (header = name)")->required();
    add_base_material_options(*cmd, o->preset, o->material, o->overrides);
    cmd->add_option("--variant", o->variant, "Model variant: biospec (default), biospec-2004, biospec-authors-code");
    cmd->add_option("--free", o->free,
                    "Free fields, LAYER.FIELD (comma list; default epidermis.melanosome_fraction, papillary_dermis.blood_fraction, "
                    "reticular_dermis.blood_fraction, dermis.oxygen_saturation): fields that change absorption only (also "
                    "carotene_g_per_l, bilirubin_g_per_l, vessel_radius_um, water_fraction, melanin_cluster_radius_um, ...) or thickness_cm of a layer without Rayleigh scattering")
        ->delimiter(',');
    cmd->add_option("--bounds", o->bounds, "FIELD=LO:HI for a free field (repeatable; defaults in docs/SPECTRUM_FIT.md)");
    add_geometry_option(*cmd, o->solver);
    std::string modes;
    for (const auto& e : fit_engines()) modes += "\n  " + std::string(e.name) + ": " + std::string(e.doc);
    cmd->add_option("--mode", o->solver.mode, "How the model is evaluated:" + modes);
    add_switch_option(*cmd, o->solver, SolverSwitch::channels);
    cmd->add_option("--incidence", o->incidence_deg, "Polar angle of the incident beam, deg, [0, 90)")->capture_default_str();
    cmd->add_option("--window", o->window, "Fit only the wavelengths in FROM:TO nm (default: all of the file)");
    cmd->add_option("--weight", o->weights, "FROM:TO=W: residuals in [FROM, TO] nm count W times (repeatable; default 1)");
    cmd->add_option("--spectra", o->spectra, "Fit only these columns (comma list)")->delimiter(',');
    cmd->add_option("--rays", o->rays, "Traced rays per wavelength (the model's Monte Carlo noise ~ 0.4 / sqrt(rays))")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t{100}, std::uint64_t{100'000'000}));
    add_seed_option(*cmd, o->seed, "Random seed");
    cmd->add_option("--starts", o->starts, fmt::format("Local searches per spectrum, from the best points of a {}-point scan", SpectrumFitSettings{}.scan_points))
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{1}, SpectrumFitSettings::scan_points));
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1u, 1024u));
    cmd->add_option("--output", o->output, "Write the fits to FILE.csv (one row per spectrum) or FILE.json");
    cmd->add_option("--plot", o->plot, "Plot measured vs fitted to FILE.png|.svg (and the residuals to FILE-residuals.png|.svg)");
    add_overwrite_flag(*cmd, o->force, "Replace the --output / --plot files if they exist");
    cmd->add_flag("--json", o->json, "Print the fits as JSON");
    cmd->callback([o, cmd] {
        o->walk_options_given = given_options(*cmd, {"--rays", "--seed"});
        run_fit_spectrum(*o);
    });
}

}  // namespace skinspec::cli
