#include "appearance/swatch_chart.hpp"

#include <cmath>

#include "solvers/color_precision.hpp"
#include "skinspec/version.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr std::size_t max_steps = 1000;

std::vector<MaterialOverride> patch_overrides(const SwatchRequest& request, const std::vector<double>& parameters) {
    auto overrides = request.overrides;
    for (std::size_t s = 0; s < request.sweeps.size(); ++s) {
        overrides.push_back({request.sweeps[s].field, format_number(parameters[s])});
    }
    return overrides;
}

}  // namespace

std::vector<double> ParameterSweep::values() const {
    std::vector<double> v(steps);
    for (std::size_t i = 0; i < steps; ++i) {
        const double t = steps == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(steps - 1);
        v[i] = log ? first * std::pow(last / first, t) : first + (last - first) * t;
    }
    return v;
}

ParameterSweep parse_sweep(std::string_view text) {
    const std::string what = "--vary '" + std::string(text) + "'";
    const auto eq = text.find('=');
    if (eq == std::string_view::npos || eq == 0) throw InputError(what + ": expected FIELD=FIRST:LAST:STEPS[:log]");
    ParameterSweep sweep;
    sweep.field = std::string(trim(text.substr(0, eq)));
    auto range = text.substr(eq + 1);
    if (range.ends_with(":log")) {
        sweep.log = true;
        range.remove_suffix(4);
    }
    const auto c1 = range.find(':');
    const auto c2 = c1 == std::string_view::npos ? c1 : range.find(':', c1 + 1);
    if (c2 == std::string_view::npos) throw InputError(what + ": expected FIELD=FIRST:LAST:STEPS[:log]");
    const auto first = parse_double(range.substr(0, c1));
    const auto last = parse_double(range.substr(c1 + 1, c2 - c1 - 1));
    const auto steps = parse_double(range.substr(c2 + 1));
    if (!first || !last || !std::isfinite(*first) || !std::isfinite(*last)) {
        throw InputError(what + ": FIRST and LAST must be finite numbers");
    }
    if (!steps || *steps != std::floor(*steps) || *steps < 1 || *steps > static_cast<double>(max_steps)) {
        throw InputError(what + ": STEPS must be a whole number in [1, " + std::to_string(max_steps) + "]");
    }
    sweep.first = *first;
    sweep.last = *last;
    sweep.steps = static_cast<std::size_t>(*steps);
    if (sweep.log && !(sweep.first > 0.0 && sweep.last > 0.0)) {
        throw InputError(what + ": a log range needs FIRST and LAST > 0 (got " + format_number(sweep.first) + " and " +
                         format_number(sweep.last) + ")");
    }
    if (sweep.steps > 1 && sweep.first == sweep.last) {
        throw InputError(what + ": empty range (FIRST = LAST with " + std::to_string(sweep.steps) + " steps)");
    }
    return sweep;
}

WavelengthGrid swatch_wavelengths(double delta_e) { return WavelengthGrid::range(380.0, 780.0, delta_e < 1.0 ? 5.0 : 10.0); }

SwatchChart compute_swatch(const SwatchRequest& request) {
    if (!(std::isfinite(request.delta_e) && request.delta_e > 0.0)) {
        throw InputError("--delta-e " + format_number(request.delta_e) + " is outside (0, inf)");
    }
    if (request.sweeps.size() > 2) throw InputError("--vary: at most two fields (columns and rows)");
    SwatchChart chart;
    chart.columns = request.sweeps.empty() ? 1 : request.sweeps[0].steps;
    chart.rows = request.sweeps.size() < 2 ? 1 : request.sweeps[1].steps;
    chart.wavelengths = swatch_wavelengths(request.delta_e);
    const TristimulusWeights weights(chart.wavelengths.nm(), request.illuminant, request.observer, OutOfRangePolicy::hold);
    chart.white = weights.white();

    // The parameters of every patch, row-major.
    const auto& solver = find_solver(request.solver);
    std::vector<std::vector<double>> parameters;
    for (std::size_t row = 0; row < chart.rows; ++row) {
        for (std::size_t column = 0; column < chart.columns; ++column) {
            std::vector<double> p;
            if (!request.sweeps.empty()) p.push_back(request.sweeps[0].values()[column]);
            if (request.sweeps.size() > 1) p.push_back(request.sweeps[1].values()[row]);
            parameters.push_back(std::move(p));
        }
    }
    // A bad field or value fails before any ray is traced: every range the material file checks is an interval
    // (and v_m + v_b <= 1 a linear bound) and each sweep is monotonic, so the corner patches are the extremes.
    // The other patches are loaded as they are solved.
    std::vector<std::size_t> corners{0, chart.columns - 1, (chart.rows - 1) * chart.columns, chart.rows * chart.columns - 1};
    const auto material_of = [&](std::size_t i) { return load_material(request.material, patch_overrides(request, parameters[i])); };
    SolverRequest base;
    base.switches = request.switches;
    auto& spectral = base.spectral;
    spectral.wavelengths = chart.wavelengths;
    spectral.quantities = Quantities{true, false, false, false};
    spectral.seed = request.seed;
    spectral.max_rays_per_wavelength = request.max_rays_per_wavelength;
    spectral.rays_per_batch = 256;
    spectral.initial_batches = 2;
    if (solver.capabilities().uncertainty) spectral.stderr_targets = color_stderr_targets(weights, request.delta_e);
    spectral.cancel = request.cancel;
    for (const auto i : corners) {
        const auto m = material_of(i);
        if (std::holds_alternative<HomogeneousMaterial>(m)) {
            throw InputError("material '" + request.material + "' is given per band; a swatch needs reflectance spectra (a layered material)");
        }
        check_request(solver, m, base);
    }

    for (std::size_t i = 0; i < parameters.size(); ++i) {
        auto patch_request = base;
        patch_request.overrides = patch_overrides(request, parameters[i]);
        const auto result = solve_spectrum(solver, material_of(i), patch_request);
        if (result.partial) {
            chart.partial = true;
            break;
        }
        std::vector<double> r, se;
        SwatchPatch patch;
        patch.parameters = parameters[i];
        for (const auto& w : result.wavelengths) {
            r.push_back(w.reflectance.value);
            se.push_back(w.reflectance.stderr);
            patch.rays += w.rays;
            patch.converged = patch.converged && w.converged;
        }
        patch.xyz = weights.integrate(r);
        patch.lab = xyz_to_lab(patch.xyz, chart.white);
        patch.delta_e_uncertainty = ciede2000_uncertainty(weights, r, se);
        for (auto w : result.warnings) {
            w.at = "patch " + std::to_string(i + 1) + ", " + w.at;
            chart.warnings.push_back(std::move(w));
        }
        chart.patches.push_back(std::move(patch));
        if (i == 0) chart.settings = result.settings;
        if (request.on_progress) request.on_progress(i + 1, parameters.size());
    }
    chart.settings["material"] = request.material;
    chart.settings["solver"] = request.solver;
    chart.settings["delta_e_target"] = request.delta_e;
    chart.settings["illuminant"] = std::string(short_name(request.illuminant));
    chart.settings["observer"] = std::string(short_name(request.observer));
    chart.settings["wavelengths"] = "380-780 nm every " + format_number(chart.wavelengths[1] - chart.wavelengths[0]) + " nm";
    chart.settings.erase("stderr_target");
    return chart;
}

}  // namespace skinspec
