#include "solvers/biospec_walk_solver.hpp"

#include "materials/material_fields.hpp"
#include "transport/biospec/biospec_solver.hpp"
#include "transport/biospec/biospec_walk.hpp"

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
            .replay_fields = absorption_only_fields(),
            .material_needs = "",
            .geometries = {MeasurementGeometry::sci, MeasurementGeometry::sce, MeasurementGeometry::zero_45},
            .descriptions = {ScatteringDescription::biospec},
        };
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        return solve_biospec(std::get<LayerStack>(material), request.spectral, options(request.switches));
    }
    // Absorption replay: materials that trace alike (path keys) are traced once, in groups of at
    // most max_replay_sets (the per-ray cost grows with the sets; progress and Ctrl-C act per group).
    std::vector<SpectralResult> solve_many(const std::vector<const Material*>& materials, const SolverRequest& request) const override {
        const auto o = options(request.switches);
        if (o.estimator != AbsorptionEstimator::weighted) return SpectralSolver::solve_many(materials, request);
        return solve_in_replay_groups(materials, request, solve_groups(materials, request),
                                      [&](const std::vector<const LayerStack*>& stacks, const SpectralRequest& part) { return solve_biospec_sets(stacks, part, o); });
    }
    std::vector<std::vector<std::size_t>> solve_groups(const std::vector<const Material*>& materials, const SolverRequest& request) const override {
        if (options(request.switches).estimator != AbsorptionEstimator::weighted) return SpectralSolver::solve_groups(materials, request);
        return replay_groups(materials, max_replay_sets, TracedPaths::biospec);
    }

private:
    static constexpr std::size_t max_replay_sets = 256;
    static BiospecOptions options(const SolverSwitches& s) {
        BiospecOptions o;
        if (s.estimator) o.estimator = *s.estimator;
        if (s.fold_into_skin) o.fold_into_skin = *s.fold_into_skin;
        o.thin_layer_hg = s.thin_layer_hg;
        return o;
    }
};

}  // namespace

const SpectralSolver& biospec_walk_solver() {
    static const BiospecWalkSolver solver;
    return solver;
}

}  // namespace skinspec
