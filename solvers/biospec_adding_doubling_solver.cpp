#include "solvers/biospec_adding_doubling_solver.hpp"

#include "transport/adding_doubling/biospec_adding_doubling.hpp"

namespace skinspec {
namespace {

class BiospecAddingDoublingSolver final : public SpectralSolver {
public:
    std::string_view name() const override { return "biospec-adding-doubling"; }
    std::string_view description() const override {
        return "the BioSpec model (the walk's per-crossing scattering) by adding-doubling: deterministic, no noise, with a quadrature accuracy check";
    }
    const SolverCapabilities& capabilities() const override {
        static const SolverCapabilities caps{
            .quantities = {true, true, true, false},
            .layered_materials = true,
            .band_materials = false,
            .uncertainty = false,
            .radial_profiles = false,
            .switches = {SolverSwitch::channels, SolverSwitch::fold_into_skin, SolverSwitch::thin_layer_phase},
            .replay_fields = {},
            .material_needs = "",
            .geometries = {MeasurementGeometry::sci, MeasurementGeometry::sce},
        };
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        BiospecAdOptions options;
        const auto& s = request.switches;
        if (s.quadrature_channels) options.ad.channels = *s.quadrature_channels;
        if (s.fold_into_skin) options.fold_into_skin = *s.fold_into_skin;
        options.thin_layer_hg = s.thin_layer_hg;
        return solve_biospec_adding_doubling_spectrum(std::get<LayerStack>(material), request.spectral, options);
    }
};

}  // namespace

const SpectralSolver& biospec_adding_doubling_solver() {
    static const BiospecAddingDoublingSolver solver;
    return solver;
}

}  // namespace skinspec
