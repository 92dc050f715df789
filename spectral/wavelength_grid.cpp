#include "spectral/wavelength_grid.hpp"

#include <cmath>
#include <string>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr std::size_t max_grid_points = 1'000'000;

void check_wavelength(double nm, const std::string& what) {
    if (!std::isfinite(nm) || nm <= 0.0) {
        throw InputError(what + ": wavelength " + format_number(nm) + " nm is not allowed (must be finite and > 0)");
    }
}

}  // namespace

WavelengthGrid WavelengthGrid::range(double first_nm, double last_nm, double step_nm, std::string_view label) {
    const std::string what(label);
    check_wavelength(first_nm, what);
    check_wavelength(last_nm, what);
    if (last_nm < first_nm) {
        throw InputError(what + ": last " + format_number(last_nm) + " nm is below first " +
                         format_number(first_nm) + " nm (allowed: last >= first)");
    }
    if (!std::isfinite(step_nm) || step_nm <= 0.0) {
        throw InputError(what + ": step " + format_number(step_nm) + " nm is not allowed (must be finite and > 0)");
    }
    const double count = std::floor((last_nm - first_nm) / step_nm + 1e-9) + 1.0;
    if (count > static_cast<double>(max_grid_points)) {
        throw InputError(what + ": " + format_number(count) + " points is too many (allowed: at most " +
                         std::to_string(max_grid_points) + ")");
    }
    std::vector<double> nm(static_cast<std::size_t>(count));
    for (std::size_t i = 0; i < nm.size(); ++i) nm[i] = first_nm + static_cast<double>(i) * step_nm;
    return WavelengthGrid(std::move(nm));
}

WavelengthGrid WavelengthGrid::list(std::vector<double> wavelengths_nm, std::string_view label) {
    const std::string what(label);
    if (wavelengths_nm.empty()) throw InputError(what + ": empty (allowed: at least one wavelength)");
    for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
        check_wavelength(wavelengths_nm[i], what);
        if (i > 0 && !(wavelengths_nm[i] > wavelengths_nm[i - 1])) {
            throw InputError(what + ": " + format_number(wavelengths_nm[i]) + " nm follows " +
                             format_number(wavelengths_nm[i - 1]) + " nm (allowed: strictly increasing)");
        }
    }
    return WavelengthGrid(std::move(wavelengths_nm));
}

WavelengthGrid WavelengthGrid::parse(std::string_view text, std::string_view what) {
    const std::string label(what);
    const auto number = [&](std::string_view field) {
        const auto value = parse_double(field);
        if (!value) {
            throw InputError(label + ": '" + std::string(field) +
                             "' is not a number (expected FIRST:LAST:STEP, one wavelength, or a comma list, in nm)");
        }
        return *value;
    };
    if (text.find(':') != std::string_view::npos) {
        std::vector<double> parts;
        std::size_t start = 0;
        while (true) {
            const auto colon = text.find(':', start);
            parts.push_back(number(text.substr(start, colon - start)));
            if (colon == std::string_view::npos) break;
            start = colon + 1;
        }
        if (parts.size() != 3) {
            throw InputError(label + ": '" + std::string(text) + "' must have the form FIRST:LAST:STEP (nm)");
        }
        return range(parts[0], parts[1], parts[2], what);
    }
    std::vector<double> values;
    for (const auto field : split_fields(text)) values.push_back(number(field));
    return list(std::move(values), what);
}

}  // namespace skinspec
