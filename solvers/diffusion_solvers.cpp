#include "solvers/diffusion_solvers.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "spectral/ciede2000.hpp"
#include "spectral/colorimetry.hpp"
#include "spectral/parallel_indices.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"
#include "transport/diffusion/diffusion_model.hpp"
#include "transport/diffusion/diffusion_profiles.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

// How many of a spectrum's wavelengths the model error is measured at, and adding-doubling's quadrature there
// (its own error, ~0.005 in R at 8 channels, is far below diffusion's on skin).
constexpr std::size_t model_error_wavelengths = 9;
constexpr std::size_t model_error_channels = 8;
// How many of a sweep axis's values it is measured at (every value of a shorter axis): 9 along one axis, 5 x 5 on a
// grid of two, so that a sweep costs at most ~30 adding-doubling solves per wavelength measured.
constexpr std::size_t model_error_nodes_one_axis = 9;
constexpr std::size_t model_error_nodes_per_axis = 5;

// `k` indices spread evenly over 0..n-1, both ends included (all of them when k >= n).
std::vector<std::size_t> spread(std::size_t n, std::size_t k) {
    k = std::min(n, k);
    std::vector<std::size_t> at;
    for (std::size_t i = 0; i < k; ++i) at.push_back(k == 1 ? 0 : (i * (n - 1) + (k - 1) / 2) / (k - 1));
    return at;
}

// R_diffusion - R_adding-doubling (the exact transport of the same skin's volumetric description) at the
// wavelengths `at` of `rows`, interpolated linearly in wavelength between them. None without a volumetric
// description in every layer (adding-doubling cannot solve it). `accuracy`: adding-doubling's own accuracy estimate at
// the middle of `at` (its 8 channels are ~0.007 off on skin: the stated error includes it).
std::optional<std::vector<double>> measured_difference(const LayerStack& stack, const std::vector<WavelengthResult>& rows,
                                                       const std::vector<std::size_t>& at, double incidence_deg, MeasurementGeometry geometry,
                                                       double& accuracy) {
    if (!std::all_of(stack.layers.begin(), stack.layers.end(), [](const TissueLayer& l) { return l.volumetric.has_value(); })) return std::nullopt;
    // The expanded phase functions depend on neither mu_a nor mu_s: one cache per thread serves every spectrum and
    // every member of a sweep (it compares entries by content and holds at most 16).
    thread_local AdCache phases;
    std::vector<double> difference(rows.size(), 0.0);
    for (std::size_t k = 0; k < at.size(); ++k) {
        const auto i = at[k];
        const bool check = k == at.size() / 2;
        const double nm = rows[i].wavelength_nm;
        const AdOptions options{model_error_channels, check};
        // A description derived from the BioSpec one stands for that model (matched_volumetric.hpp): the model solved
        // exactly is the reference, at a solve's cost instead of the derivation's ~30.
        const auto ad = stack.model.volumetric_matched_to_biospec
                            ? solve_biospec_adding_doubling(stack, nm, incidence_deg, BiospecAdOptions{options, FoldIntoSkin::drop, std::nullopt}, &phases).totals
                            : solve_adding_doubling(rte_stack_from(stack, nm), AdIncidence{false, incidence_deg}, options, &phases);
        difference[i] = rows[i].reflectance.value - (ad.diffuse_reflectance + (geometry == MeasurementGeometry::sce ? 0.0 : ad.specular_reflectance));
        if (check) accuracy = ad.accuracy;
    }
    for (std::size_t s = 0; s + 1 < at.size(); ++s) {
        for (std::size_t i = at[s] + 1; i < at[s + 1]; ++i) {
            const double t = (rows[i].wavelength_nm - rows[at[s]].wavelength_nm) / (rows[at[s + 1]].wavelength_nm - rows[at[s]].wavelength_nm);
            difference[i] = (1.0 - t) * difference[at[s]] + t * difference[at[s + 1]];
        }
    }
    return difference;
}

// The stated error of a result whose R differs from adding-doubling's by one of `differences` (the member's own, or
// those of the measured members around it: the largest is stated): the largest |difference| at the measured
// wavelengths `at`, and the largest CIEDE2000 (D65, 2 degrees) between the result's colour and that of its spectrum
// less a difference.
StatedError stated_error(const std::vector<WavelengthResult>& rows, const std::vector<const std::vector<double>*>& differences,
                         const std::vector<std::size_t>& at, const std::optional<TristimulusWeights>& weights, std::shared_ptr<const std::string> meaning) {
    StatedError e{0.0, std::move(meaning), {}};
    std::vector<double> r;
    for (const auto& row : rows) r.push_back(row.reflectance.value);
    for (const auto* difference : differences) {
        for (const std::size_t i : at) e.R = std::max(e.R, std::abs((*difference)[i]));
        if (!weights) continue;
        std::vector<double> corrected;
        for (std::size_t i = 0; i < rows.size(); ++i) corrected.push_back(std::clamp(r[i] - (*difference)[i], 0.0, 1.0));
        const double delta = ciede2000(xyz_to_lab(weights->integrate(corrected), weights->white()), xyz_to_lab(weights->integrate(r), weights->white()));
        e.delta_e2000 = std::max(e.delta_e2000.value_or(0.0), delta);
    }
    return e;
}

// The members of a sweep as a lattice: each axis's size (from the members' positions), when they form one in
// sweep_grid's order (the first axis fastest).
std::optional<std::vector<std::size_t>> lattice_shape(const std::vector<std::vector<std::size_t>>& positions) {
    if (positions.empty() || positions.front().empty()) return std::nullopt;
    std::vector<std::size_t> shape(positions.front().size(), 0);
    for (const auto& p : positions) {
        if (p.size() != shape.size()) return std::nullopt;
        for (std::size_t a = 0; a < p.size(); ++a) shape[a] = std::max(shape[a], p[a] + 1);
    }
    for (std::size_t i = 0; i < positions.size(); ++i) {
        std::size_t index = 0, stride = 1;
        for (std::size_t a = 0; a < shape.size(); ++a) {
            index += positions[i][a] * stride;
            stride *= shape[a];
        }
        if (index != i || (i + 1 == positions.size() && stride != positions.size())) return std::nullopt;
    }
    return shape;
}

class DiffusionSolver final : public SpectralSolver {
public:
    explicit DiffusionSolver(DiffusionMode mode) : mode_(mode) {}
    std::string_view name() const override { return to_string(mode_); }
    std::string_view description() const override {
        return mode_ == DiffusionMode::multipole ? "layered multipole diffusion (Donner & Jensen 2005), deterministic"
                                                 : "semi-infinite dipole diffusion (Jensen et al. 2001), deterministic";
    }
    const SolverCapabilities& capabilities() const override {
        // The dipole is one semi-infinite medium: nothing leaves through a bottom, so it computes no T and
        // refuses a request to change the bottom or a deeper layer's refractive index (they would be ignored).
        static const auto caps = [](bool semi_infinite) {
            return SolverCapabilities{
                .quantities = {true, !semi_infinite, false, false},
                .layered_materials = true,
                .band_materials = true,
                .uncertainty = false,
                .radial_profiles = true,
                .switches = {SolverSwitch::roughness},
                .replay_fields = {},
                .material_needs = "reduced_scattering_table or reduced_scattering_* in every layer",
                .geometries = {MeasurementGeometry::sci, MeasurementGeometry::sce},
                .bottom = !semi_infinite,
                .layer_refractive_indices = !semi_infinite,
                .descriptions = {ScatteringDescription::reduced},
            };
        };
        static const SolverCapabilities multipole = caps(false), dipole = caps(true);
        return mode_ == DiffusionMode::dipole ? dipole : multipole;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        const auto options = diffusion_options(request.switches);
        if (const auto* bands = std::get_if<HomogeneousMaterial>(&material)) return solve_diffusion_bands(*bands, request.spectral, options);
        const auto& stack = std::get<LayerStack>(material);
        return solve_diffusion_spectrum(stack, request.spectral, options);
    }
    // Diffusion's error on this skin, stated with its result: its difference from adding-doubling measured at up to
    // model_error_wavelengths of the request's wavelengths (interpolated linearly between them) and, in a sweep, at up
    // to model_error_nodes_* values of each axis; a member between measured ones states the largest of theirs (the
    // error changes steeply with pigment: interpolating it understated it by up to 44 % at 5 of 16 values).
    void state_errors(const std::function<Material(std::size_t)>& material_of, const std::vector<std::vector<std::size_t>>& positions,
                      const SolverRequest& request, std::span<SpectralResult> results) const override {
        const auto& rows = results.front().wavelengths;
        if (rows.empty() || !std::holds_alternative<LayerStack>(material_of(0))) return;
        const auto at = spread(rows.size(), model_error_wavelengths);
        // A description derived from the BioSpec one stands for that model, which measured_difference solves instead.
        const bool derived = std::get<LayerStack>(material_of(0)).model.volumetric_matched_to_biospec;
        const std::string reference = derived ? "biospec-adding-doubling" : "adding-doubling";
        std::string meaning = fmt::format("largest |R - R of {}| (exact transport of the same skin's {}, {} channels) at {} of the {} wavelengths", reference,
                                          derived ? "BioSpec description, from which its volumetric one is derived" : "volumetric description",
                                          model_error_channels, at.size(), rows.size());
        std::vector<double> nm;
        for (const auto& row : rows) nm.push_back(row.wavelength_nm);
        std::optional<TristimulusWeights> weights;
        if (has_color_span(nm)) weights.emplace(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
        const std::size_t members = positions.size();
        const auto shape = lattice_shape(positions);
        // Per axis: the measured indices.
        std::vector<std::vector<std::size_t>> nodes;
        std::size_t measured = 1;
        if (shape) {
            for (const auto n : *shape) {
                nodes.push_back(spread(n, shape->size() == 1 ? model_error_nodes_one_axis : model_error_nodes_per_axis));
                measured *= nodes.back().size();
            }
            if (measured < members) {
                meaning += fmt::format(" and at {} of the sweep's {} members (a member between them: the largest of the measured members around it)",
                                       measured, members);
            }
        }
        // The measured members around each result: itself, or the corners of its lattice cell.
        std::vector<std::vector<std::size_t>> around_of(results.size());
        for (std::size_t i = 0; i < results.size(); ++i) {
            std::vector<std::size_t> around{0};
            if (!shape) around = {i};
            std::size_t stride = 1;
            for (std::size_t a = 0; shape && a < shape->size(); ++a) {
                const auto p = positions[i][a];
                const auto hi = std::lower_bound(nodes[a].begin(), nodes[a].end(), p);
                std::vector<std::size_t> next;
                for (const auto index : around) {
                    next.push_back(index + *hi * stride);
                    if (*hi != p) next.push_back(index + *(hi - 1) * stride);
                }
                around = std::move(next);
                stride *= (*shape)[a];
            }
            around_of[i] = std::move(around);
        }
        // Each measured member's difference, computed once, in parallel (from its own result, or solved here when a
        // stop left it out).
        std::vector<std::size_t> wanted;
        for (const auto& around : around_of) wanted.insert(wanted.end(), around.begin(), around.end());
        std::sort(wanted.begin(), wanted.end());
        wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
        std::vector<std::optional<std::vector<double>>> wanted_differences(wanted.size());
        // Adding-doubling's own accuracy at each measured member (it changes with the swept values: on a description
        // derived from the BioSpec one by up to 0.01 between neighbouring members); a member states the largest of those
        // around it, as for the difference.
        std::vector<double> accuracies(wanted.size(), 0.0);
        parallel_indices(wanted.size(), [&](std::size_t k) {
            const auto i = wanted[k];
            const auto material = material_of(i);
            const auto& stack = std::get<LayerStack>(material);
            const double incidence = request.spectral.incidence_deg;
            wanted_differences[k] = measured_difference(stack, i < results.size() ? results[i].wavelengths : solve(material, request).wavelengths, at, incidence,
                                                        request.spectral.geometry, accuracies[k]);
        });
        meaning += fmt::format(", plus {}'s own accuracy there (twice the change of its R with the channels doubled, at the middle measured wavelength{})",
                               reference, members > 1 ? ", the largest of the measured members around it" : "");
        if (weights) meaning += "; the colour difference with that difference (interpolated between the measured wavelengths)";
        const auto shared_meaning = std::make_shared<const std::string>(std::move(meaning));
        const auto wanted_index = [&](std::size_t i) { return static_cast<std::size_t>(std::lower_bound(wanted.begin(), wanted.end(), i) - wanted.begin()); };
        parallel_indices(results.size(), [&](std::size_t i) {
            std::vector<const std::vector<double>*> differences;
            double accuracy = 0.0;
            for (const auto member : around_of[i]) {
                const auto k = wanted_index(member);
                if (!wanted_differences[k]) return;
                differences.push_back(&*wanted_differences[k]);
                accuracy = std::max(accuracy, accuracies[k]);
            }
            results[i].stated_error = stated_error(results[i].wavelengths, differences, at, weights, shared_meaning);
            results[i].stated_error->R += accuracy;
        });
    }
    SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const override {
        return diffusion_profiles(material, request.wavelengths, request.radii_mm, diffusion_options(request.switches), request.transmittance, request.cancel,
                                  request.on_progress);
    }

private:
    DiffusionOptions diffusion_options(const SolverSwitches& s) const { return DiffusionOptions{mode_, s.surface_roughness}; }
    DiffusionMode mode_;
};

}  // namespace

const SpectralSolver& multipole_solver() {
    static const DiffusionSolver solver(DiffusionMode::multipole);
    return solver;
}

const SpectralSolver& dipole_solver() {
    static const DiffusionSolver solver(DiffusionMode::dipole);
    return solver;
}

}  // namespace skinspec
