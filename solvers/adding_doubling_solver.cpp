#include "solvers/adding_doubling_solver.hpp"

#include "transport/adding_doubling/adding_doubling_spectrum.hpp"

namespace skinspec {
namespace {

class AddingDoublingSolver final : public SpectralSolver {
public:
    std::string_view name() const override { return "adding-doubling"; }
    std::string_view description() const override {
        return "adding-doubling radiative transfer (van de Hulst; Prahl 1995), deterministic, with a quadrature accuracy check";
    }
    const SolverCapabilities& capabilities() const override {
        static const SolverCapabilities caps{
            .quantities = {true, true, true, false},
            .layered_materials = true,
            .band_materials = false,
            .uncertainty = false,
            .radial_profiles = false,
            .switches = {SolverSwitch::channels},
            .replay_fields = {},
            .material_needs = "volumetric_mu_s_per_cm_at_500nm (and volumetric_g / volumetric_phase) in every layer",
            .geometries = {MeasurementGeometry::sci, MeasurementGeometry::sce},
            .descriptions = {ScatteringDescription::volumetric},
        };
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        AdOptions options;
        if (request.switches.quadrature_channels) options.channels = *request.switches.quadrature_channels;
        return solve_adding_doubling_spectrum(std::get<LayerStack>(material), request.spectral, options);
    }
};

}  // namespace

const SpectralSolver& adding_doubling_solver() {
    static const AddingDoublingSolver solver;
    return solver;
}

}  // namespace skinspec
