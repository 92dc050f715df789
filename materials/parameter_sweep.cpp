#include "materials/parameter_sweep.hpp"

#include <algorithm>
#include <cmath>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr std::size_t max_steps = 1000;

}  // namespace

std::string ParameterSweep::text() const {
    return field + "=" + format_number(first) + ":" + format_number(last) + ":" + std::to_string(steps) + (log ? ":log" : "");
}

std::vector<double> ParameterSweep::values() const {
    std::vector<double> v(steps);
    // The ratio or the span of a range near the doubles' limits overflows (1e-300:1e300 gave inf): then the same
    // interpolation in logarithms, or weighted ends.
    const double ratio = last / first, span = last - first;
    for (std::size_t i = 0; i < steps; ++i) {
        const double t = steps == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(steps - 1);
        if (log) {
            v[i] = std::isfinite(ratio) ? first * std::pow(ratio, t) : std::exp(std::log(first) + t * (std::log(last) - std::log(first)));
        } else {
            v[i] = std::isfinite(span) ? first + span * t : first * (1.0 - t) + last * t;
        }
    }
    return v;
}

SweepAxis ParameterSweep::axis() const { return {field, values()}; }

std::vector<SweepAxis> sweep_axes(const std::vector<ParameterSweep>& sweeps) {
    std::vector<SweepAxis> axes;
    for (const auto& s : sweeps) {
        // A field swept twice would make a grid of which only the diagonal exists (the later value wins).
        if (std::any_of(axes.begin(), axes.end(), [&](const SweepAxis& a) { return a.field == s.field; })) {
            throw InputError("--vary " + s.field + " is given twice (sweep a field once)");
        }
        axes.push_back(s.axis());
    }
    return axes;
}

ParameterSweep parse_sweep(std::string_view text) {
    const std::string what = "--vary '" + std::string(text) + "'";
    const auto eq = text.find('=');
    if (eq == std::string_view::npos || eq == 0) throw InputError(what + ": expected FIELD=FIRST:LAST:STEPS[:log]");
    ParameterSweep sweep;
    sweep.field = std::string(trim(text.substr(0, eq)));
    auto range = text.substr(eq + 1);
    if (range.ends_with(":log")) {
        sweep.log = true;
        range.remove_suffix(4);
    }
    const auto c1 = range.find(':');
    const auto c2 = c1 == std::string_view::npos ? c1 : range.find(':', c1 + 1);
    if (c2 == std::string_view::npos) throw InputError(what + ": expected FIELD=FIRST:LAST:STEPS[:log]");
    const auto first = parse_double(range.substr(0, c1));
    const auto last = parse_double(range.substr(c1 + 1, c2 - c1 - 1));
    const auto steps = parse_double(range.substr(c2 + 1));
    if (!first || !last || !std::isfinite(*first) || !std::isfinite(*last)) {
        throw InputError(what + ": FIRST and LAST must be finite numbers");
    }
    if (!steps || *steps != std::floor(*steps) || *steps < 1 || *steps > static_cast<double>(max_steps)) {
        throw InputError(what + ": STEPS must be a whole number in [1, " + std::to_string(max_steps) + "]");
    }
    sweep.first = *first;
    sweep.last = *last;
    sweep.steps = static_cast<std::size_t>(*steps);
    if (sweep.log && !(sweep.first > 0.0 && sweep.last > 0.0)) {
        throw InputError(what + ": a log range needs FIRST and LAST > 0 (got " + format_number(sweep.first) + " and " +
                         format_number(sweep.last) + ")");
    }
    if (sweep.steps > 1 && sweep.first == sweep.last) {
        throw InputError(what + ": empty range (FIRST = LAST with " + std::to_string(sweep.steps) + " steps)");
    }
    return sweep;
}

std::vector<std::vector<double>> sweep_grid(const std::vector<SweepAxis>& axes) {
    std::vector<std::vector<double>> grid{{}};
    for (const auto& axis : axes) {
        std::vector<std::vector<double>> next;
        // The first axis varies fastest: rows (later axes) are the outer loop.
        for (const double v : axis.values) {
            for (const auto& g : grid) {
                auto combination = g;
                combination.push_back(v);
                next.push_back(std::move(combination));
            }
        }
        grid = std::move(next);
    }
    return grid;
}

bool SweptValues::operator==(const SweptValues& other) const {
    if (values != other.values) return false;
    for (std::size_t i = 0; i < size(); ++i) {
        if (field(i) != other.field(i)) return false;
    }
    return true;
}

std::shared_ptr<const std::vector<std::string>> swept_fields(const std::vector<SweepAxis>& axes) {
    std::vector<std::string> fields;
    for (const auto& a : axes) fields.push_back(a.field);
    return std::make_shared<const std::vector<std::string>>(std::move(fields));
}

std::vector<MaterialOverride> sweep_overrides(const SweptValues& swept) {
    std::vector<MaterialOverride> out;
    for (std::size_t s = 0; s < swept.size(); ++s) out.push_back({swept.field(s), format_number(swept.values[s]), "--vary", swept.values[s]});
    return out;
}

}  // namespace skinspec
