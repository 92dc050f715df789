#include "solvers/diffusion_solvers.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "spectral/ciede2000.hpp"
#include "spectral/colorimetry.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/diffusion/diffusion_model.hpp"
#include "transport/diffusion/diffusion_profiles.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

// How many of a spectrum's wavelengths the model error is measured at, and adding-doubling's quadrature there
// (its own error, ~0.005 in R at 8 channels, is far below diffusion's on skin).
constexpr std::size_t model_error_wavelengths = 9;
constexpr std::size_t model_error_channels = 8;

// Diffusion's error on this skin, stated with its result: adding-doubling (the exact transport of the same skin's
// volumetric description) at up to model_error_wavelengths of the request's wavelengths, spread over the grid.
// R: the largest |R_diffusion - R_adding-doubling| there; CIEDE2000 (D65, 2 degrees) between the diffusion colour
// and that of the diffusion spectrum less the difference, interpolated linearly between the measured wavelengths.
// None without a volumetric description in every layer (adding-doubling cannot solve it).
std::optional<StatedError> model_error(const LayerStack& stack, const SpectralResult& result, const SpectralRequest& request) {
    const auto& rows = result.wavelengths;
    if (rows.empty() || !std::all_of(stack.layers.begin(), stack.layers.end(), [](const TissueLayer& l) { return l.volumetric.has_value(); })) {
        return std::nullopt;
    }
    const std::size_t n = rows.size(), k = std::min(n, model_error_wavelengths);
    std::vector<std::size_t> at;
    for (std::size_t i = 0; i < k; ++i) at.push_back(k == 1 ? 0 : (i * (n - 1) + (k - 1) / 2) / (k - 1));
    const AdOptions options{model_error_channels, false};
    // The expanded phase functions depend on neither mu_a nor mu_s: one cache per thread serves every spectrum and
    // every member of a sweep (it compares entries by content and holds at most 16).
    thread_local AdCache phases;
    std::vector<double> difference(n, 0.0);
    double largest = 0.0;
    for (const std::size_t i : at) {
        const auto ad = solve_adding_doubling(rte_stack_from(stack, rows[i].wavelength_nm), AdIncidence{false, request.incidence_deg}, options, &phases);
        difference[i] = rows[i].reflectance.value - (ad.diffuse_reflectance + ad.specular_reflectance);
        largest = std::max(largest, std::abs(difference[i]));
    }
    std::vector<double> nm, r, corrected;
    for (std::size_t s = 0; s + 1 < at.size(); ++s) {
        for (std::size_t i = at[s] + 1; i < at[s + 1]; ++i) {
            const double t = (rows[i].wavelength_nm - rows[at[s]].wavelength_nm) / (rows[at[s + 1]].wavelength_nm - rows[at[s]].wavelength_nm);
            difference[i] = (1.0 - t) * difference[at[s]] + t * difference[at[s + 1]];
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        nm.push_back(rows[i].wavelength_nm);
        r.push_back(rows[i].reflectance.value);
        corrected.push_back(std::clamp(r.back() - difference[i], 0.0, 1.0));
    }
    StatedError e{largest,
                  fmt::format("largest |R - R of adding-doubling| (exact transport of the same skin's volumetric description, {} channels) at {} of "
                              "the {} wavelengths",
                              model_error_channels, at.size(), n),
                  {}};
    if (has_color_span(nm)) {
        e.meaning += "; the colour difference with that difference interpolated between them";
        const TristimulusWeights weights(nm, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
        e.delta_e2000 = ciede2000(xyz_to_lab(weights.integrate(corrected), weights.white()), xyz_to_lab(weights.integrate(r), weights.white()));
    }
    return e;
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
        const auto& stack = std::get<LayerStack>(material);
        auto result = solve_diffusion_spectrum(stack, request.spectral, options);
        result.stated_error = model_error(stack, result, request.spectral);
        return result;
    }
    SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const override {
        return diffusion_profiles(material, request.wavelengths, request.radii_mm, diffusion_options(request.switches), request.transmittance, request.cancel);
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
