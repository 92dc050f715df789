#include "solvers/matched_multipole_solver.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "solvers/biospec_adding_doubling_solver.hpp"
#include "solvers/diffusion_solvers.hpp"
#include "spectral/input_error.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

// The totals' quadrature: within ~0.005 of the converged totals on the biospec presets, 0.012 on forearm-nist2017-p10
// at 700 nm (stated: 0.0163; docs/ADDING_DOUBLING.md, "Convergence in the channels"), 31 wavelengths in ~3 ms on one
// core.
constexpr std::size_t matched_channels = 12;

class MatchedMultipoleSolver final : public SpectralSolver {
public:
    std::string_view name() const override { return "matched-multipole"; }
    std::string_view description() const override {
        return "multipole profiles scaled to the exact totals of the BioSpec model (biospec-adding-doubling): the BioSpec colour with diffusion's spatial spread";
    }
    const SolverCapabilities& capabilities() const override {
        // biospec-adding-doubling's (its totals, switches and geometries), with radial profiles shaped by the reduced
        // scattering.
        static const SolverCapabilities caps = [] {
            auto c = biospec_adding_doubling_solver().capabilities();
            c.radial_profiles = true;
            c.descriptions.push_back(ScatteringDescription::reduced);  // the multipole's shapes of its profiles
            return c;
        }();
        return caps;
    }
    SpectralResult solve(const Material& material, const SolverRequest& request) const override {
        auto result = solve_biospec_adding_doubling_spectrum(std::get<LayerStack>(material), request.spectral, biospec_ad_options(request.switches, matched_channels));
        result.model = std::string(name());
        return result;
    }
    SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const override {
        // The multipole's shapes (its own switches: none of ours), then each channel scaled to the exact totals.
        const auto& stack = std::get<LayerStack>(material);
        auto out = shapes(stack, request);
        out.model = std::string(name());
        const auto options = biospec_ad_options(request.switches, matched_channels);
        AdCache cache;
        for (auto& channel : out.channels) {
            if (request.cancel && request.cancel->load()) {
                out.partial = true;
                break;
            }
            const auto exact = solve_biospec_adding_doubling(stack, channel.wavelength_nm, 0.0, options, &cache).totals;
            if (!(channel.total_reflectance > 0.0) || (request.transmittance && exact.transmittance > 0.0 && !(channel.total_transmittance > 0.0))) {
                throw InputError(fmt::format("matched-multipole: the multipole's profile of '{}' at {} carries no light (total R {}, T {}), so it has no "
                                             "shape to scale to the exact totals; use --mode biospec-adding-doubling for the totals",
                                             out.material, channel.label, channel.total_reflectance, channel.total_transmittance));
            }
            const double r_scale = exact.diffuse_reflectance / channel.total_reflectance;
            for (auto& v : channel.reflectance_per_mm2) v *= r_scale;
            channel.total_reflectance = exact.diffuse_reflectance;
            channel.specular_reflectance = exact.specular_reflectance;
            const double t_scale = channel.total_transmittance > 0.0 ? exact.transmittance / channel.total_transmittance : 0.0;
            for (auto& v : channel.transmittance_per_mm2) v *= t_scale;
            channel.total_transmittance = exact.transmittance;
        }
        return out;
    }

private:
    // The multipole's profiles of the skin whose totals they are scaled to. On a material whose volumetric description
    // is derived from the BioSpec one (model.volumetric_matched_to_biospec: the presets), each wavelength's multipole
    // spreads by the derived layers' reduced scattering mu_s (1 - g) there (rte_stack_from), the skin every other
    // solver of this material describes (its dermis scatters 2-4x less in the red than the layers' Salomatina tables;
    // the share of R within a radius then comes 0.14-0.53 off the volumetric walk's on the three paper presets instead
    // of 0.32-0.68, docs/DIFFUSION.md). Otherwise, and for a stack without a dermal layer (which has no derived
    // description: e.g. the stratum corneum and epidermis alone, as measured in vitro), the layers' own reduced
    // scattering; the latter says so in a warning.
    static SpectralProfiles shapes(const LayerStack& stack, ProfileRequest request) {
        request.switches = {};
        const bool dermal = std::any_of(stack.layers.begin(), stack.layers.end(),
                                        [&](const TissueLayer& l) { return is_dermal(crossing_in_effect(l, stack.model)); });
        if (!stack.model.volumetric_matched_to_biospec || !dermal) {
            auto own = multipole_solver().profiles(stack, request);
            if (stack.model.volumetric_matched_to_biospec) {
                own.warnings.push_back({"spread by the layers' own reduced scattering: no dermal layer, so no volumetric description derived from the "
                                        "BioSpec one (model.volumetric_matched_to_biospec)", stack.name, "every wavelength", 0.0});
            }
            return own;
        }
        SpectralProfiles out;
        const auto wavelengths = request.wavelengths;
        const auto progress = request.on_progress;
        request.on_progress = {};
        for (std::size_t c = 0; c < wavelengths.size(); ++c) {
            const double nm = wavelengths.nm()[c];
            if (request.cancel && request.cancel->load()) {
                out.partial = true;
                break;
            }
            const auto derived = rte_stack_from(stack, nm);
            auto spread = stack;
            for (std::size_t k = 0; k < spread.layers.size(); ++k) {
                const auto& layer = derived.layers[k];
                spread.layers[k].reduced = ReducedScattering{"", layer.mu_s_per_cm * (1.0 - layer.phase.mean_cosine()), 0.0};
            }
            request.wavelengths = WavelengthGrid::list({nm});
            auto one = multipole_solver().profiles(spread, request);
            if (c == 0) {
                out.material = stack.name;
                out.radii_mm = one.radii_mm;
                out.converged = true;
            }
            out.channels.insert(out.channels.end(), one.channels.begin(), one.channels.end());
            out.warnings.insert(out.warnings.end(), one.warnings.begin(), one.warnings.end());
            out.max_pairs = std::max(out.max_pairs, one.max_pairs);
            out.frequencies = std::max(out.frequencies, one.frequencies);
            out.converged = out.converged && one.converged;
            if (one.partial) {
                out.partial = true;
                break;
            }
            if (progress) progress(Progress{0, 0, c + 1, wavelengths.size()});
        }
        return out;
    }
};

}  // namespace

const SpectralSolver& matched_multipole_solver() {
    static const MatchedMultipoleSolver solver;
    return solver;
}

}  // namespace skinspec
