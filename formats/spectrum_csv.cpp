#include "formats/spectrum_csv.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

TabulatedSpectrum read_spectrum_csv(const std::filesystem::path& file, const SpectrumFileRules& rules) {
    const std::string name = file.string();
    if (!std::filesystem::exists(file)) throw InputError(name + ": file not found");
    if (std::filesystem::is_directory(file)) throw InputError(name + ": is a folder, not a spectrum file");
    std::ifstream in(file);
    if (!in) throw InputError(name + ": cannot be opened for reading");

    const std::string value_field = rules.quantity;
    const std::string value_range = rules.allow_over_one ? "[0, inf)" : "[0, 1] (use --allow-over-one for values above 1)";
    std::vector<double> wavelengths;
    std::vector<double> values;
    std::string line;
    std::size_t line_number = 0;
    bool seen_first_row = false;
    while (std::getline(in, line)) {
        ++line_number;
        const auto text = trim(line);
        if (text.empty() || text.front() == '#') continue;
        const std::string where = name + ":" + std::to_string(line_number) + ": ";
        const auto fields = split_fields(text);
        const bool first_row = !seen_first_row;
        seen_first_row = true;
        const bool all_text = std::none_of(fields.begin(), fields.end(), [](auto f) { return parse_double(f).has_value(); });
        if (first_row && all_text) continue;  // header line
        if (fields.size() != 2) {
            throw InputError(where + std::to_string(fields.size()) + " field(s) (allowed: 2, wavelength_nm," + value_field + ")");
        }
        const auto wavelength = parse_double(fields[0]);
        const auto value = parse_double(fields[1]);
        if (!wavelength) throw InputError(where + "field 'wavelength_nm' = '" + std::string(fields[0]) + "' is not a number");
        if (!value) throw InputError(where + "field '" + value_field + "' = '" + std::string(fields[1]) + "' is not a number");
        if (!std::isfinite(*wavelength) || *wavelength <= 0.0) {
            throw InputError(where + "field 'wavelength_nm' = " + std::string(fields[0]) + " is not allowed (allowed: finite, > 0 nm)");
        }
        if (!std::isfinite(*value)) {
            throw InputError(where + "field '" + value_field + "' = " + std::string(fields[1]) + " is not allowed (allowed: " + value_range + ")");
        }
        if (*value < 0.0 || (!rules.allow_over_one && *value > 1.0)) {
            throw InputError(where + "field '" + value_field + "' = " + std::string(fields[1]) + " is outside " + value_range);
        }
        if (!wavelengths.empty() && !(*wavelength > wavelengths.back())) {
            throw InputError(where + "field 'wavelength_nm' = " + std::string(fields[0]) + " does not follow " +
                             format_number(wavelengths.back()) + " nm (allowed: strictly increasing wavelengths)");
        }
        wavelengths.push_back(*wavelength);
        values.push_back(*value);
    }
    if (wavelengths.size() < 2) {
        throw InputError(name + ": " + std::to_string(wavelengths.size()) + " data point(s) (allowed: at least 2)");
    }
    if (wavelengths.front() > rules.must_cover_from_nm || wavelengths.back() < rules.must_cover_to_nm) {
        throw InputError(name + ": wavelengths cover " + format_number(wavelengths.front()) + "-" +
                         format_number(wavelengths.back()) + " nm (allowed: must span at least " +
                         format_number(rules.must_cover_from_nm) + "-" + format_number(rules.must_cover_to_nm) + " nm)");
    }
    return TabulatedSpectrum(name, std::move(wavelengths), std::move(values), rules.outside);
}

}  // namespace skinspec
