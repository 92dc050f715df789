#include "solvers/solver_switches.hpp"

#include <algorithm>
#include <cmath>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// A finite number in [lo, hi] (lo excluded when lo_open), or InputError "WHAT = TEXT is outside RANGE".
double number_in(std::string_view text, const std::string& what, double lo, double hi, bool lo_open) {
    const std::string t(trim(text));
    const auto v = parse_double(t);
    const std::string range = std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) + "]";
    if (!v) throw InputError(what + " '" + t + "' is not a number in " + range);
    if (!std::isfinite(*v) || (lo_open ? *v <= lo : *v < lo) || *v > hi) throw InputError(what + " = " + t + " is outside " + range);
    return *v;
}

}  // namespace

const std::vector<SwitchDescriptor>& switch_descriptors() {
    static const std::vector<SwitchDescriptor> table{
        {SolverSwitch::estimator, "estimator", "absorption estimator, weighted (default) or random (per-crossing test)", "random",
         [](SolverSwitches& s, std::string_view t, const std::string& what) { s.estimator = parse_absorption_estimator(t, what); },
         [](const SolverSwitches& s) { return s.estimator.has_value(); }},
        {SolverSwitch::fold_into_skin, "fold-into-skin",
         "fold-perturbed reflections pointing into the skin, drop (default, as the 2004 code) or resample", "resample",
         [](SolverSwitches& s, std::string_view t, const std::string& what) { s.fold_into_skin = parse_fold_into_skin(t, what); },
         [](const SolverSwitches& s) { return s.fold_into_skin.has_value(); }},
        {SolverSwitch::roughness, "roughness", "Beckmann RMS slope of a rough top surface, (0, 2] (default smooth)", "0.3",
         [](SolverSwitches& s, std::string_view t, const std::string& what) { s.surface_roughness = number_in(t, what, 0.0, 2.0, true); },
         [](const SolverSwitches& s) { return s.surface_roughness.has_value(); }},
        {SolverSwitch::boundaries, "boundaries", "Fresnel at the outer boundaries, random (default, as MCML) or split", "split",
         [](SolverSwitches& s, std::string_view t, const std::string& what) { s.boundaries = parse_boundary_mode(t, what); },
         [](const SolverSwitches& s) { return s.boundaries.has_value(); }},
        {SolverSwitch::thin_layer_phase, "thin-layer-phase", "HG fits in place of the measured thin-layer profiles (set by compare-phase)", "",
         nullptr, [](const SolverSwitches& s) { return s.thin_layer_hg.has_value(); }},
        {SolverSwitch::channels, "channels",
         "quadrature channels per hemisphere, [4, 256] (default 24; the stated accuracy falls about as 1/channels, the time grows as "
         "channels^3)",
         "8",
         [](SolverSwitches& s, std::string_view t, const std::string& what) {
             const double v = number_in(t, what, 4.0, 256.0, false);
             if (v != std::floor(v)) throw InputError(what + " = " + std::string(trim(t)) + " is not a whole number in [4, 256]");
             s.quadrature_channels = static_cast<std::size_t>(v);
         },
         [](const SolverSwitches& s) { return s.quadrature_channels.has_value(); }},
    };
    return table;
}

const SwitchDescriptor& describe(SolverSwitch s) {
    const auto& table = switch_descriptors();
    return *std::find_if(table.begin(), table.end(), [s](const SwitchDescriptor& d) { return d.id == s; });
}

std::string_view to_string(SolverSwitch s) { return describe(s).name; }

const SwitchDescriptor* find_switch(std::string_view name) {
    std::string dashed(name);
    std::replace(dashed.begin(), dashed.end(), '_', '-');
    for (const auto& d : switch_descriptors()) {
        if (d.parse && d.name == dashed) return &d;
    }
    return nullptr;
}

std::vector<SolverSwitch> SolverSwitches::set() const {
    std::vector<SolverSwitch> out;
    for (const auto& d : switch_descriptors()) {
        if (d.is_set(*this)) out.push_back(d.id);
    }
    return out;
}

}  // namespace skinspec
