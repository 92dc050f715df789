#include "solvers/biospec_adding_doubling_solver.hpp"


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
            .descriptions = {ScatteringDescription::biospec},
        };
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        return solve_biospec_adding_doubling_spectrum(std::get<LayerStack>(material), request.spectral, biospec_ad_options(request.switches, AdOptions{}.channels));
    }
};

}  // namespace

BiospecAdOptions biospec_ad_options(const SolverSwitches& s, std::size_t default_channels) {
    BiospecAdOptions o;
    o.ad.channels = s.quadrature_channels.value_or(default_channels);
    if (s.fold_into_skin) o.fold_into_skin = *s.fold_into_skin;
    o.thin_layer_hg = s.thin_layer_hg;
    return o;
}

const SpectralSolver& biospec_adding_doubling_solver() {
    static const BiospecAddingDoublingSolver solver;
    return solver;
}

}  // namespace skinspec
