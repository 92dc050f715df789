#include "solvers/volumetric_walk_solver.hpp"

#include <algorithm>

#include "materials/material_fields.hpp"
#include "spectral/input_error.hpp"
#include "spectral/parallel_indices.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/matched_volumetric.hpp"
#include "transport/rte/rte_profiles.hpp"

namespace skinspec {
namespace {

class VolumetricWalkSolver final : public SpectralSolver {
public:
    std::string_view name() const override { return "rte"; }
    std::string_view description() const override {
        return "the volumetric walk (MCML-class radiative transfer), Monte Carlo with standard errors";
    }
    const SolverCapabilities& capabilities() const override {
        static const SolverCapabilities caps{
            .quantities = {true, true, true, false},
            .layered_materials = true,
            .band_materials = true,
            .uncertainty = true,
            .radial_profiles = true,
            .switches = {SolverSwitch::boundaries},
            .replay_fields = absorption_only_fields(),
            .material_needs = "volumetric_mu_s_per_cm_at_500nm (and volumetric_g / volumetric_phase) in every layer",
            .geometries = {MeasurementGeometry::sci, MeasurementGeometry::sce},
            .descriptions = {ScatteringDescription::volumetric},
        };
        return caps;
    }
    // A band material (R per band, Jensen et al. 2001's tables) is walked as the semi-infinite medium it stands for.
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        if (const auto* bands = std::get_if<HomogeneousMaterial>(&material)) return solve_rte_bands(*bands, request.spectral, boundaries(request));
        return solve_rte_spectrum(std::get<LayerStack>(material), request.spectral, boundaries(request));
    }
    // Absorption replay: materials whose volumetric paths agree are traced once per wavelength in white Monte
    // Carlo (at most max_replay_sets together; a material alone runs MCML's way).
    std::vector<SpectralResult> solve_many(const std::vector<const Material*>& materials, const SolverRequest& request) const override {
        if (any_bands(materials)) return SpectralSolver::solve_many(materials, request);
        return solve_in_replay_groups(materials, request, solve_groups(materials, request),
                                      [&](const std::vector<const LayerStack*>& stacks, const SpectralRequest& part) { return solve_rte_spectra(stacks, part, boundaries(request), false); });
    }
    // A fixed photon count, else the precision target within the budget (rte_profiles.hpp); a band material's bands as the
    // semi-infinite media `spectrum --mode rte` walks.
    SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const override {
        if (const auto* bands = std::get_if<HomogeneousMaterial>(&material)) {
            return solve_rte_profiles(*bands, request.radii_mm, request.transmittance, profile_options(request));
        }
        return solve_rte_profiles(std::get<LayerStack>(material), request.wavelengths, request.radii_mm, request.transmittance, profile_options(request));
    }
    // Pigmentation grids: each group of materials whose volumetric paths agree from one walk per wavelength (the exit
    // replay, rte_profiles.hpp), up to max_exit_replay_sets together.
    std::vector<SpectralProfiles> profiles_many(const std::vector<const Material*>& materials, const ProfileRequest& request) const override {
        if (any_bands(materials) || materials.size() == 1) return SpectralSolver::profiles_many(materials, request);
        const auto groups = replay_groups(materials, max_exit_replay_sets, TracedPaths::volumetric);
        std::vector<std::optional<SpectralProfiles>> by_index(materials.size());
        SpectralRequest whole;
        whole.on_progress = request.on_progress;
        PartProgress progress(whole.on_progress, groups.size());
        for (std::size_t k = 0; k < groups.size(); ++k) {
            if (request.cancel && request.cancel->load()) break;
            std::vector<const LayerStack*> stacks;
            for (const auto i : groups[k]) stacks.push_back(&std::get<LayerStack>(*materials[i]));
            auto options = profile_options(request);
            options.on_progress = progress.part(whole, k).on_progress;
            auto results = solve_rte_profiles(stacks, request.wavelengths, request.radii_mm, request.transmittance, options);
            progress.finish_part();
            for (std::size_t j = 0; j < results.size(); ++j) by_index[groups[k][j]] = std::move(results[j]);
        }
        std::vector<SpectralProfiles> out;
        for (auto& p : by_index) {
            if (!p) break;
            out.push_back(std::move(*p));
            if (out.back().partial) break;
        }
        return out;
    }
    // On a description derived from the BioSpec one (matched_volumetric.hpp) the walk solves the derived medium, which
    // has the BioSpec model's R_d at normal incidence only: its miss at the request's incidence and geometry, by
    // adding-doubling of both descriptions at every wavelength, is stated with the standard errors (a systematic error
    // they do not cover: up to ~0.04 at 60 deg).
    void state_errors(const std::function<Material(std::size_t)>& material_of, const std::vector<std::vector<std::size_t>>&, const SolverRequest& request,
                      std::span<SpectralResult> results) const override {
        static const auto meaning = std::make_shared<const std::string>(
            "largest |R - R of biospec-adding-doubling| of adding-doubling on the derived description at the request's incidence and geometry "
            "(the derived description's miss of the BioSpec model; both at " + std::to_string(matched_volumetric_channels) +
            " channels, every wavelength): systematic, beside the standard errors");
        const auto& spectral = request.spectral;
        parallel_indices(results.size(), [&](std::size_t i) {
            const auto material = material_of(i);
            const auto* stack = std::get_if<LayerStack>(&material);
            if (!stack || !stack->model.volumetric_matched_to_biospec) return;
            thread_local AdCache cache;
            const AdOptions options{matched_volumetric_channels, false, spectral.cancel};
            double largest = 0.0;
            for (const auto& row : results[i].wavelengths) {
                const double nm = row.wavelength_nm;
                const auto derived = solve_adding_doubling(rte_stack_from(*stack, nm), AdIncidence{false, spectral.incidence_deg}, options, &cache);
                if (derived.cancelled) return;
                largest = std::max(largest, std::abs(derived_description_miss(*stack, derived, nm, spectral.incidence_deg,
                                                                              spectral.geometry != MeasurementGeometry::sce, options, &cache)));
            }
            results[i].stated_error = StatedError{largest, meaning, {}};
        });
    }
    std::vector<std::vector<std::size_t>> solve_groups(const std::vector<const Material*>& materials, const SolverRequest& request) const override {
        if (any_bands(materials)) return SpectralSolver::solve_groups(materials, request);
        return replay_groups(materials, max_replay_sets, TracedPaths::volumetric);
    }

private:
    static constexpr std::size_t max_replay_sets = 64;
    // The exit replay's cost per set is an exponential per exit, its memory the exits of one wavelength: a 32 x 32 grid
    // in one walk.
    static constexpr std::size_t max_exit_replay_sets = 1024;
    // A fixed photon count, else the precision target within the budget.
    static RteProfileOptions profile_options(const ProfileRequest& request) {
        return RteProfileOptions{request.rays_per_wavelength.value_or(request.max_rays_per_wavelength),
                                 request.rays_per_wavelength ? std::nullopt : std::optional(request.stderr_target), request.seed,
                                 request.switches.boundaries.value_or(BoundaryMode::random), request.cancel, request.on_progress};
    }
    static bool any_bands(const std::vector<const Material*>& materials) {
        return std::any_of(materials.begin(), materials.end(), [](const Material* m) { return std::holds_alternative<HomogeneousMaterial>(*m); });
    }
    static BoundaryMode boundaries(const SolverRequest& request) { return request.switches.boundaries.value_or(BoundaryMode::random); }
};

}  // namespace

const SpectralSolver& volumetric_walk_solver() {
    static const VolumetricWalkSolver solver;
    return solver;
}

}  // namespace skinspec
