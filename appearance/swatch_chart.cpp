#include "appearance/swatch_chart.hpp"

#include <algorithm>

#include <cmath>
#include <memory>

#include "solvers/color_precision.hpp"
#include "solvers/result_wire.hpp"
#include "skinspec/version.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

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
    // The material is read once; each patch sets its swept values on a copy in memory.
    const auto base_material = std::make_shared<const Material>(load_material(request.material, request.overrides));
    const auto base_toml = std::make_shared<const std::string>(to_toml(*base_material));
    const auto axes = sweep_axes(request.sweeps);
    const auto fields = swept_fields(axes);
    const auto material_of = [&](std::size_t i) { return with_overrides(*base_material, sweep_overrides({fields, parameters[i]})); };
    SolverRequest base;
    base.switches = request.switches;
    base.overrides = request.overrides;
    base.sampling_options = request.sampling_options;
    auto& spectral = base.spectral;
    spectral.wavelengths = chart.wavelengths;
    spectral.quantities = Quantities{true, false, false, false};
    spectral.seed = request.seed;
    spectral.geometry = request.geometry;
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
        // The swept fields too: one the solver does not read would make a chart of one colour.
        auto checked = base;
        for (auto& o : sweep_overrides({fields, parameters[i]})) checked.overrides.push_back(std::move(o));
        check_request(solver, m, checked);
    }

    // Patches are solved in chunks through the solver's sweep (the BioSpec walk traces a chunk's paths once and
    // re-weights them per patch); progress and Ctrl-C act per chunk. With a work share each process solves its
    // chunks and the first one turns every chunk's results into patches, in order.
    const std::size_t chunk = std::max<std::size_t>(1, request.patches_per_sweep);
    const std::size_t chunks = (parameters.size() + chunk - 1) / chunk;
    // Appends a chunk's patches; false when the chunk is incomplete (stopped), after which nothing is appended.
    const auto add_chunk = [&](std::size_t c, const std::vector<SpectralResult>& results) {
        for (std::size_t j = 0; j < results.size(); ++j) {
            const auto& result = results[j];
            if (result.partial) break;
            const std::size_t i = c * chunk + j;
            SwatchPatch patch;
            patch.parameters = parameters[i];
            for (const auto& w : result.wavelengths) {
                patch.reflectance.push_back(w.reflectance.value);
                patch.reflectance_stderr.push_back(w.reflectance.stderr);
                patch.rays += w.rays;
                patch.converged = patch.converged && w.converged;
            }
            patch.xyz = weights.integrate(patch.reflectance);
            patch.lab = xyz_to_lab(patch.xyz, chart.white);
            patch.uncertainty = color_uncertainty(weights, patch.reflectance, patch.reflectance_stderr, result.stated_error ? result.stated_error->R : 0.0);
            for (auto w : result.warnings) {
                w.at = "patch " + std::to_string(i + 1) + ", " + w.at;
                chart.warnings.push_back(std::move(w));
            }
            chart.patches.push_back(std::move(patch));
            if (i == 0) chart.settings = all_settings(result);
        }
        return chart.patches.size() == std::min(parameters.size(), (c + 1) * chunk);
    };
    const auto* share = request.work_share;
    std::vector<std::pair<std::size_t, std::string>> mine;
    std::size_t own_total = 0, own_done = 0;
    for (std::size_t c = 0; c < chunks; ++c) own_total += !share || share->mine(c) ? std::min(chunk, parameters.size() - c * chunk) : 0;
    for (std::size_t c = 0; c < chunks; ++c) {
        if (share && !share->mine(c)) continue;
        if (request.cancel && request.cancel->load()) break;
        const std::size_t begin = c * chunk, end = std::min(parameters.size(), begin + chunk);
        std::vector<SweepMember> members;
        for (std::size_t i = begin; i < end; ++i) members.push_back({base_material, {fields, parameters[i]}, base_toml, {}});
        auto results = solve_sweep(solver, members, base);
        if (share) {
            const bool complete = results.size() == members.size() && !results.back().partial;
            for (auto& r : results) r.provenance = {};  // a chart keeps no provenance: not sent
            mine.emplace_back(c, results_to_bytes(results));
            if (!complete) break;
        } else if (!add_chunk(c, results)) {
            break;
        }
        own_done += members.size();
        if (request.on_progress) request.on_progress(own_done, own_total);
    }
    if (share) {
        const auto gathered = share->gather(mine, chunks);
        if (share->rank() != 0) return chart;
        for (std::size_t c = 0; c < chunks; ++c) {
            if (gathered[c].empty() || !add_chunk(c, results_from_bytes(gathered[c]))) break;
        }
    }
    chart.partial = chart.patches.size() < parameters.size();
    chart.settings["material"] = request.material;
    chart.settings["solver"] = request.solver;
    chart.settings["geometry"] = std::string(to_string(request.geometry));
    chart.settings["delta_e_target"] = request.delta_e;
    chart.settings["illuminant"] = std::string(short_name(request.illuminant));
    chart.settings["observer"] = std::string(short_name(request.observer));
    chart.settings["wavelengths"] = "380-780 nm every " + format_number(chart.wavelengths[1] - chart.wavelengths[0]) + " nm";
    chart.settings.erase("stderr_target");
    return chart;
}

std::vector<ParameterSweep> default_swatch_sweeps(const Material& material) {
    const auto* stack = std::get_if<LayerStack>(&material);
    const auto has = [&](auto&& predicate) { return stack && std::any_of(stack->layers.begin(), stack->layers.end(), predicate); };
    const bool skin_like = has([](const TissueLayer& l) { return l.name == "epidermis"; }) &&
                           has([](const TissueLayer& l) { return l.name.ends_with("_dermis"); });
    if (!skin_like) return {};
    return {parse_sweep("epidermis.melanosome_fraction=0.01:0.42:8:log"), parse_sweep("dermis.blood_fraction=0.002:0.05:5")};
}

}  // namespace skinspec
