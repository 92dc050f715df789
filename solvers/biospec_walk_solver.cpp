#include "solvers/biospec_walk_solver.hpp"

#include "transport/biospec/biospec_solver.hpp"

namespace skinspec {
namespace {

class BiospecWalkSolver final : public SpectralSolver {
public:
    std::string_view name() const override { return "biospec"; }
    std::string_view description() const override {
        return "the BioSpec walk: per-crossing measured/Rayleigh-cosine scattering, Monte Carlo with standard errors";
    }
    const SolverCapabilities& capabilities() const override {
        static const SolverCapabilities caps{
            .quantities = {true, true, true, true},
            .layered_materials = true,
            .band_materials = false,
            .uncertainty = true,
            .radial_profiles = false,
            .switches = {SolverSwitch::estimator, SolverSwitch::fold_into_skin, SolverSwitch::thin_layer_phase},
            .replay_fields = {},
            .material_needs = "",
        };
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        BiospecOptions options;
        const auto& s = request.switches;
        if (s.estimator) options.estimator = *s.estimator;
        if (s.fold_into_skin) options.fold_into_skin = *s.fold_into_skin;
        options.thin_layer_hg = s.thin_layer_hg;
        return solve_biospec(std::get<LayerStack>(material), request.spectral, options);
    }
};

}  // namespace

const SpectralSolver& biospec_walk_solver() {
    static const BiospecWalkSolver solver;
    return solver;
}

}  // namespace skinspec
