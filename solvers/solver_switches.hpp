#pragma once
// Solver switches: options that are not properties of the skin (docs/SOLVERS.md). One descriptor per switch is the
// one place that says what it is: its name (the command-line option --NAME, the Python keyword NAME with '_' for
// '-'), the values it takes, its help and how its text is read. Which solvers take it is what they declare
// (SolverCapabilities::switches); the help text, the refusals and the capability tests are derived from both.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "transport/biospec/biospec_options.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {

enum class SolverSwitch { estimator, fold_into_skin, roughness, boundaries, thin_layer_phase, channels };

// Unset: the solver's default. Set for a solver that does not declare the switch: refused (check_request).
struct SolverSwitches {
    std::optional<AbsorptionEstimator> estimator;  // BioSpec walk: weighted or per-crossing random test
    std::optional<FoldIntoSkin> fold_into_skin;    // BioSpec walk: drop or resample fold reflections into the skin
    std::optional<double> surface_roughness;       // diffusion: Beckmann RMS slope of a rough top surface
    std::optional<BoundaryMode> boundaries;        // volumetric walk: all-or-none or split Fresnel boundaries
    std::optional<ThinLayerHg> thin_layer_hg;      // BioSpec walk: HG in place of the measured thin-layer profiles
    std::optional<std::size_t> quadrature_channels;  // adding-doubling: channels per hemisphere
    std::vector<SolverSwitch> set() const;
};

struct SwitchDescriptor {
    SolverSwitch id;
    std::string_view name;    // "fold-into-skin": the option --fold-into-skin, the Python keyword fold_into_skin
    std::string_view values;  // what it takes and its default, for help texts
    std::string_view example;  // a valid value (tests)
    // Reads `text` into `switches`; InputError naming `what` (the option or keyword), the value and what is allowed.
    // Null for a switch set only by the program (thin-layer-phase: compare-phase's HG fits).
    void (*parse)(SolverSwitches& switches, std::string_view text, const std::string& what);
    bool (*is_set)(const SolverSwitches& switches);
};
const std::vector<SwitchDescriptor>& switch_descriptors();
const SwitchDescriptor& describe(SolverSwitch s);
std::string_view to_string(SolverSwitch s);
// The descriptor of a switch a user can give by name ("fold-into-skin" or "fold_into_skin"), or nullptr.
const SwitchDescriptor* find_switch(std::string_view name);

}  // namespace skinspec
