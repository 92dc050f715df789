#include "formats/measured_spectra.hpp"

#include <cmath>
#include <fstream>

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

MeasuredSpectra read_measured_spectra(const std::filesystem::path& path) {
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
        out.line_of_row.push_back(number);
    }
    if (!header) throw InputError(out.file + ": no header line 'wavelength_nm,NAME,...'");
    if (out.wavelength_nm.size() < min_measured_points) {
        throw InputError(out.file + ": " + std::to_string(out.wavelength_nm.size()) + " wavelengths; a fit needs at least " +
                         std::to_string(min_measured_points));
    }
    return out;
}

}  // namespace skinspec
