#include "formats/spectrum_csv.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

SpectrumFile read_spectrum_file(const std::filesystem::path& file, const SpectrumFileRules& rules) {
    const std::string name = file.string();
    auto in = open_input_file(file, "spectrum file");

    const std::string value_range = rules.allow_over_one ? "[0, inf)" : "[0, 1] (use --allow-over-one for values above 1)";
    std::vector<std::string> header;
    std::size_t wavelength_column = 0, value_column = 1;
    std::optional<std::size_t> material_column, stderr_column;
    std::string value_field = rules.quantity;
    std::vector<std::string> materials_seen;
    // Chooses the columns once the header (or the first data row, without one) is known.
    const auto choose_columns = [&](std::size_t line_number) {
        const std::string where = name + ":" + std::to_string(line_number) + ": ";
        if (header.empty()) {
            if (!rules.column.empty()) throw InputError(where + "--column " + rules.column + ": the file has no header line naming columns");
            if (!rules.material.empty()) throw InputError(where + "--material " + rules.material + ": the file has no material column");
            return;
        }
        const auto find = [&](const std::string& column) -> std::optional<std::size_t> {
            const auto it = std::find(header.begin(), header.end(), column);
            return it == header.end() ? std::nullopt : std::optional<std::size_t>(static_cast<std::size_t>(it - header.begin()));
        };
        std::string names;
        for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
        wavelength_column = find("wavelength_nm").value_or(0);
        material_column = find("material");
        if (!rules.material.empty() && !material_column) throw InputError(where + "--material " + rules.material + ": the file has no material column (columns: " + names + ")");
        if (!rules.column.empty()) {
            const auto c = find(rules.column);
            if (!c || *c == wavelength_column || c == material_column) {
                throw InputError(where + "--column " + rules.column + " is not a value column of the file (columns: " + names + ")");
            }
            value_column = *c;
        } else if (header.size() == 2) {
            value_column = 1 - wavelength_column;
        } else if (const auto r = find("R")) {
            value_column = *r;
        } else {
            throw InputError(where + std::to_string(header.size()) + " columns; choose the value column with --column (columns: " + names + ")");
        }
        value_field = header[value_column];
        stderr_column = find(value_field + "_stderr");
    };
    std::vector<double> wavelengths;
    std::vector<double> values, standard_errors;
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
        if (first_row) {
            if (all_text) header.assign(fields.begin(), fields.end());
            choose_columns(line_number);
            if (all_text) continue;
        }
        const std::size_t expected = header.empty() ? 2 : header.size();
        if (fields.size() != expected) {
            throw InputError(where + std::to_string(fields.size()) + " field(s) (allowed: " + std::to_string(expected) +
                             (header.empty() ? ", wavelength_nm," + value_field : ", as the header") + ")");
        }
        if (material_column) {
            const std::string material(fields[*material_column]);
            if (std::find(materials_seen.begin(), materials_seen.end(), material) == materials_seen.end()) materials_seen.push_back(material);
            if (rules.material.empty() && materials_seen.size() > 1) {
                throw InputError(where + "the file holds several materials (" + materials_seen.front() + ", " + material +
                                 "); choose one with --material");
            }
            if (!rules.material.empty() && material != rules.material) continue;
        }
        const auto wavelength = parse_double(fields[wavelength_column]);
        const auto value = parse_double(fields[value_column]);
        const std::string wavelength_text(fields[wavelength_column]), value_text(fields[value_column]);
        if (!wavelength) throw InputError(where + "field 'wavelength_nm' = '" + wavelength_text + "' is not a number");
        if (!value) throw InputError(where + "field '" + value_field + "' = '" + value_text + "' is not a number");
        if (!std::isfinite(*wavelength) || *wavelength <= 0.0) {
            throw InputError(where + "field 'wavelength_nm' = " + wavelength_text + " is not allowed (allowed: finite, > 0 nm)");
        }
        if (!std::isfinite(*value)) {
            throw InputError(where + "field '" + value_field + "' = " + value_text + " is not allowed (allowed: " + value_range + ")");
        }
        if (*value < 0.0 || (!rules.allow_over_one && *value > 1.0)) {
            throw InputError(where + "field '" + value_field + "' = " + value_text + " is outside " + value_range);
        }
        if (!wavelengths.empty() && !(*wavelength > wavelengths.back())) {
            throw InputError(where + "field 'wavelength_nm' = " + wavelength_text + " does not follow " +
                             format_number(wavelengths.back()) + " nm (allowed: strictly increasing wavelengths)");
        }
        if (stderr_column) {
            const std::string text(fields[*stderr_column]);
            const auto error = parse_double(text);
            if (!error || !std::isfinite(*error) || *error < 0.0) {
                throw InputError(where + "field '" + value_field + "_stderr' = '" + text + "' is not allowed (allowed: a number in [0, inf))");
            }
            standard_errors.push_back(*error);
        }
        wavelengths.push_back(*wavelength);
        values.push_back(*value);
    }
    if (!rules.material.empty() && wavelengths.empty()) {
        std::string seen;
        for (const auto& m : materials_seen) seen += (seen.empty() ? "" : ", ") + m;
        throw InputError(name + ": --material " + rules.material + " has no rows (materials: " + seen + ")");
    }
    if (wavelengths.size() < 2) {
        throw InputError(name + ": " + std::to_string(wavelengths.size()) + " data point(s) (allowed: at least 2)");
    }
    if (wavelengths.front() > rules.must_cover_from_nm || wavelengths.back() < rules.must_cover_to_nm) {
        throw InputError(name + ": wavelengths cover " + format_number(wavelengths.front()) + "-" +
                         format_number(wavelengths.back()) + " nm (allowed: must span at least " +
                         format_number(rules.must_cover_from_nm) + "-" + format_number(rules.must_cover_to_nm) + " nm)");
    }
    return {TabulatedSpectrum(name, std::move(wavelengths), std::move(values), rules.outside), std::move(standard_errors)};
}

TabulatedSpectrum read_spectrum_csv(const std::filesystem::path& file, const SpectrumFileRules& rules) {
    return read_spectrum_file(file, rules).spectrum;
}

}  // namespace skinspec
