#include "solvers/volumetric_walk_solver.hpp"

#include <algorithm>

#include "materials/material_fields.hpp"
#include "spectral/input_error.hpp"
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
    SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const override {
        if (std::holds_alternative<HomogeneousMaterial>(material)) {
            throw InputError("solver 'rte' computes radial profiles of layered materials; '" + material_name(material) +
                             "' is given per band (radial profiles of band materials: --mode multipole or dipole)");
        }
        return solve_rte_profiles(std::get<LayerStack>(material), request.wavelengths, request.radii_mm, request.transmittance,
                                  RteProfileOptions{request.rays_per_wavelength.value_or(1'000'000), request.seed,
                                                    request.switches.boundaries.value_or(BoundaryMode::random), request.cancel,
                                                    request.on_progress});
    }
    std::vector<std::vector<std::size_t>> solve_groups(const std::vector<const Material*>& materials, const SolverRequest& request) const override {
        if (any_bands(materials)) return SpectralSolver::solve_groups(materials, request);
        return replay_groups(materials, max_replay_sets, TracedPaths::volumetric);
    }

private:
    static constexpr std::size_t max_replay_sets = 64;
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
