#pragma once
// Sweeps over material fields: "FIELD=FIRST:LAST:STEPS[:log]" (at most two form a grid), used by `spectrum
// --vary` and `swatch --vary`.
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "materials/material_file.hpp"
#include "materials/swept_values.hpp"

namespace skinspec {

// "FIELD=FIRST:LAST:STEPS[:log]", e.g. "epidermis.melanosome_fraction=0.01:0.42:8:log": STEPS values from
// FIRST to LAST inclusive, evenly spaced or, with ":log", evenly spaced in the logarithm (FIRST, LAST > 0);
// STEPS = 1: FIRST alone.
struct SweepAxis;
struct ParameterSweep {
    std::string field;
    double first = 0.0;
    double last = 0.0;
    std::size_t steps = 1;
    bool log = false;
    std::vector<double> values() const;
    SweepAxis axis() const;
    std::string text() const;  // as parse_sweep reads it: "FIELD=FIRST:LAST:STEPS[:log]", numbers exact
};

// One swept field and its values in order (a parsed --vary, or any list, e.g. from Python).
struct SweepAxis {
    std::string field;
    std::vector<double> values;
};
std::vector<SweepAxis> sweep_axes(const std::vector<ParameterSweep>& sweeps);
// InputError naming the --vary text for a malformed sweep, an empty range or a log range through 0.
ParameterSweep parse_sweep(std::string_view text);

// Every combination of the axes' values, the first axis varying fastest (columns, then rows).
std::vector<std::vector<double>> sweep_grid(const std::vector<SweepAxis>& axes);

// The swept fields' names of `axes`, to share among the members.
std::shared_ptr<const std::vector<std::string>> swept_fields(const std::vector<SweepAxis>& axes);
// The overrides that make a combination: FIELD=VALUE each, as "--vary" (values exact, shortest round-trip form).
std::vector<MaterialOverride> sweep_overrides(const SweptValues& swept);

}  // namespace skinspec
