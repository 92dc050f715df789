#include "transport/rte/rte_model.hpp"

#include <cmath>

#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"
#include "spectral/text_fields.hpp"
#include "transport/adding_doubling/hypodermis_reflectance.hpp"
#include "transport/adding_doubling/matched_volumetric.hpp"

namespace skinspec {

std::string_view to_string(BoundaryMode mode) { return mode == BoundaryMode::split ? "split" : "random"; }

BoundaryMode parse_boundary_mode(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what, std::array{BoundaryMode::random, BoundaryMode::split}, "a boundary mode");
}


RteStack rte_stack_from(const LayerStack& stack, double wavelength_nm) {
    RteStack out;
    out.above_refractive_index = stack.above_refractive_index;
    out.below_refractive_index = stack.below_refractive_index;
    out.bottom_reflector = has_reflector(stack.bottom);
    out.bottom_reflectance = bottom_reflectance(stack, wavelength_nm);
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        const auto o = stack.optics(k, wavelength_nm, OpticsScope{true, false});
        if (!o.mu_s_per_cm) {
            throw InputError("layer '" + stack.layers[k].name + "' of '" + stack.name +
                             "' has no volumetric scattering (set volumetric_mu_s_per_cm_at_500nm and volumetric_g)");
        }
        // Scattering fields far beyond tissue's overflow mu_s (validate() below would name only "layer 3"); an overflowing
        // mu_a is refused where it is computed (absorption_per_cm).
        if (!std::isfinite(*o.mu_s_per_cm)) {
            throw InputError("layer '" + stack.layers[k].name + "' of '" + stack.name + "': mu_s at " + format_number(wavelength_nm) +
                             " nm = " + format_number(*o.mu_s_per_cm) + " 1/cm, from its fields' values: beyond what the model can compute");
        }
        PhaseFunction phase = PhaseFunction::henyey_greenstein(*o.g);
        if (*o.phase == PhaseFunctionKind::isotropic) phase = PhaseFunction::isotropic();
        if (*o.phase == PhaseFunctionKind::rayleigh) phase.kind = PhaseFunction::Kind::rayleigh;
        if (o.phase_table) phase = {PhaseFunction::Kind::tabulated, *o.g, 0.0, 1.0, o.phase_table};
        out.layers.push_back({o.refractive_index, o.mu_a_per_cm, *o.mu_s_per_cm, o.thickness_cm, phase});
    }
    if (stack.model.volumetric_matched_to_biospec) return match_volumetric_to_biospec(stack, out, wavelength_nm).stack;
    return out;
}

void validate(const RteStack& stack) {
    const auto check = [](bool ok, const std::string& what, double value, const char* range) {
        if (!ok) throw InputError(what + " = " + format_number(value) + " is outside " + range);
    };
    if (stack.layers.empty()) throw InputError("the volumetric walk needs at least one layer");
    check(std::isfinite(stack.above_refractive_index) && stack.above_refractive_index > 0.0, "refractive index above",
          stack.above_refractive_index, "(0, inf)");
    check(std::isfinite(stack.below_refractive_index) && stack.below_refractive_index > 0.0, "refractive index below",
          stack.below_refractive_index, "(0, inf)");
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        const auto& l = stack.layers[k];
        const std::string name = "layer " + std::to_string(k + 1) + " ";
        check(std::isfinite(l.refractive_index) && l.refractive_index > 0.0, name + "n", l.refractive_index, "(0, inf)");
        check(std::isfinite(l.mu_a_per_cm) && l.mu_a_per_cm >= 0.0, name + "mu_a [1/cm]", l.mu_a_per_cm, "[0, inf)");
        check(std::isfinite(l.mu_s_per_cm) && l.mu_s_per_cm >= 0.0, name + "mu_s [1/cm]", l.mu_s_per_cm, "[0, inf)");
        check(std::isfinite(l.thickness_cm) && l.thickness_cm > 0.0, name + "thickness [cm]", l.thickness_cm, "(0, inf)");
        check(std::isfinite(l.phase.g) && l.phase.g >= -1.0 && l.phase.g <= 1.0, name + "g", l.phase.g, "[-1, 1]");
        check(std::isfinite(l.phase.g2) && l.phase.g2 >= -1.0 && l.phase.g2 <= 1.0, name + "g2", l.phase.g2, "[-1, 1]");
    }
}

}  // namespace skinspec
