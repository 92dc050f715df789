#include "solvers/volumetric_walk_solver.hpp"

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
            .band_materials = false,
            .uncertainty = true,
            .radial_profiles = false,
            .switches = {SolverSwitch::boundaries},
            .replay_fields = {},
            .material_needs = "volumetric_mu_s_per_cm_at_500nm (and volumetric_g / volumetric_phase) in every layer",
        };
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        return solve_rte_spectrum(std::get<LayerStack>(material), request.spectral,
                                  request.switches.boundaries.value_or(BoundaryMode::random));
    }
};

}  // namespace

const SpectralSolver& volumetric_walk_solver() {
    static const VolumetricWalkSolver solver;
    return solver;
}

}  // namespace skinspec
