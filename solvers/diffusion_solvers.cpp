#include "solvers/diffusion_solvers.hpp"

#include "transport/diffusion/diffusion_model.hpp"
#include "transport/diffusion/diffusion_profiles.hpp"

namespace skinspec {
namespace {

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
        // refuses a request to change the bottom (it would be ignored).
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
                .bottom = !semi_infinite,
            };
        };
        static const SolverCapabilities multipole = caps(false), dipole = caps(true);
        return mode_ == DiffusionMode::dipole ? dipole : multipole;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        const auto options = diffusion_options(request.switches);
        if (const auto* bands = std::get_if<HomogeneousMaterial>(&material)) return solve_diffusion_bands(*bands, request.spectral, options);
        return solve_diffusion_spectrum(std::get<LayerStack>(material), request.spectral, options);
    }
    SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const override {
        return diffusion_profiles(material, request.wavelengths, request.radii_mm, diffusion_options(request.switches), request.transmittance);
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
