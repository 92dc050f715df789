#include "formats/measured_spectra.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "formats/spectrum_csv.hpp"

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

namespace {

// A skinspec result's R spectra (formats/spectrum_csv.hpp) as spectra to fit: one grid, values in range.
MeasuredSpectra from_result(const std::filesystem::path& path) {
    MeasuredSpectra out;
    out.file = path.string();
    SpectrumFileRules rules;
    rules.allow_over_one = true;  // checked against max_measured_reflectance below
    rules.must_cover_from_nm = std::numeric_limits<double>::infinity();
    rules.must_cover_to_nm = 0.0;
    for (const auto& s : read_result_spectra(path, rules)) {
        const auto span_nm = s.file.spectrum.wavelengths_nm(), span_values = s.file.spectrum.values();
        const std::vector<double> nm(span_nm.begin(), span_nm.end()), values(span_values.begin(), span_values.end());
        if (out.names.empty()) {
            out.wavelength_nm = nm;
            for (const double w : nm) out.row_sources.push_back(out.file + ": " + s.name + " at " + format_number(w) + " nm");
        } else if (nm != out.wavelength_nm) {
            throw InputError(out.file + ": " + s.name + " has other wavelengths than " + out.names.front() + " (spectra fitted together share one grid)");
        }
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (values[i] > max_measured_reflectance) {
                throw InputError(out.file + ": " + s.name + " at " + format_number(nm[i]) + " nm: R = " + format_number(values[i]) +
                                 " is not a reflectance in [0, " + format_number(max_measured_reflectance) + "]");
            }
        }
        out.names.push_back(s.name);
        out.reflectance.push_back(values);
    }
    return out;
}

}  // namespace

MeasuredSpectra read_measured_spectra(const std::filesystem::path& path) {
    if (is_skinspec_result(path, "measured spectra file")) {
        auto out = from_result(path);
        if (out.wavelength_nm.size() < min_measured_points) {
            throw InputError(out.file + ": " + std::to_string(out.wavelength_nm.size()) + " wavelengths; a fit needs at least " +
                             std::to_string(min_measured_points));
        }
        return out;
    }
    MeasuredSpectra out;
    out.file = path.string();
    auto in = open_input_file(path, "measured spectra file");
    std::string line;
    std::size_t number = 0;
    bool header = false;
    while (std::getline(in, line)) {
        ++number;
        const auto text = trim(line);
        if (text.empty() || text.front() == '#') continue;
        const auto fields = split_fields(text);
        const std::string where = out.file + ":" + std::to_string(number) + ": ";
        if (!header) {
            if (fields.size() < 2 || fields.front() != "wavelength_nm") {
                throw InputError(where + "the header must be 'wavelength_nm' followed by one name per spectrum (got '" + std::string(text) + "')");
            }
            for (std::size_t c = 1; c < fields.size(); ++c) {
                if (fields[c].empty()) throw InputError(where + "column " + std::to_string(c + 1) + " has no name");
                for (const auto& n : out.names) {
                    if (n == fields[c]) throw InputError(where + "column name '" + std::string(fields[c]) + "' is used twice");
                }
                out.names.emplace_back(fields[c]);
            }
            out.reflectance.resize(out.names.size());
            header = true;
            continue;
        }
        if (fields.size() != out.names.size() + 1) {
            throw InputError(where + "row has " + std::to_string(fields.size()) + " fields, the header " + std::to_string(out.names.size() + 1));
        }
        const auto wavelength = parse_double(fields[0]);
        if (!wavelength || !std::isfinite(*wavelength) || *wavelength <= 0.0) {
            throw InputError(where + "column 'wavelength_nm': '" + std::string(fields[0]) + "' is not a wavelength in nm (a finite number > 0)");
        }
        if (!out.wavelength_nm.empty() && !(*wavelength > out.wavelength_nm.back())) {
            throw InputError(where + "column 'wavelength_nm': " + format_number(*wavelength) + " does not increase (previous " +
                             format_number(out.wavelength_nm.back()) + ")");
        }
        for (std::size_t c = 0; c < out.names.size(); ++c) {
            const auto v = parse_double(fields[c + 1]);
            if (!v || !std::isfinite(*v) || *v < 0.0 || *v > max_measured_reflectance) {
                throw InputError(where + "column '" + out.names[c] + "': '" + std::string(fields[c + 1]) +
                                 "' is not a reflectance in [0, " + format_number(max_measured_reflectance) + "]");
            }
            out.reflectance[c].push_back(*v);
        }
        out.wavelength_nm.push_back(*wavelength);
        out.row_sources.push_back(out.file + ":" + std::to_string(number));
    }
    if (!header) throw InputError(out.file + ": no header line 'wavelength_nm,NAME,...'");
    if (out.wavelength_nm.size() < min_measured_points) {
        throw InputError(out.file + ": " + std::to_string(out.wavelength_nm.size()) + " wavelengths; a fit needs at least " +
                         std::to_string(min_measured_points));
    }
    return out;
}

}  // namespace skinspec
