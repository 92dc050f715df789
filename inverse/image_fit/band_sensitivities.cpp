#include "inverse/image_fit/band_sensitivities.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "inverse/image_fit/albedo_lut.hpp"
#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

BandSensitivities read_band_sensitivities(const std::filesystem::path& file) {
    auto in = open_input_file(file, "band sensitivity file");
    BandSensitivities out;
    std::string line;
    std::size_t number = 0;
    const auto where = [&] { return file.string() + " line " + std::to_string(number); };
    while (std::getline(in, line)) {
        ++number;
        const auto text = trim(line);
        if (text.empty() || text.front() == '#') continue;
        const auto fields = split_fields(text);
        if (out.names.empty() && out.wavelengths_nm.empty()) {
            if (fields.size() < 2 || fields.front() != "wavelength_nm") {
                throw InputError(where() + ": expected the header wavelength_nm,BAND,... (one column per band), got '" + std::string(text) + "'");
            }
            if (fields.size() - 1 > max_lut_channels) {
                throw InputError(where() + ": " + std::to_string(fields.size() - 1) + " bands; allowed at most " + std::to_string(max_lut_channels));
            }
            for (std::size_t b = 1; b < fields.size(); ++b) {
                if (fields[b].empty()) throw InputError(where() + ": band " + std::to_string(b) + " has no name");
                out.names.emplace_back(fields[b]);
            }
            out.sensitivity.resize(out.names.size());
            continue;
        }
        if (fields.size() != out.names.size() + 1) {
            throw InputError(where() + ": " + std::to_string(fields.size()) + " fields, the header has " + std::to_string(out.names.size() + 1));
        }
        std::vector<double> row;
        for (std::size_t f = 0; f < fields.size(); ++f) {
            const auto value = parse_double(fields[f]);
            if (!value || !std::isfinite(*value) || (f > 0 && *value < 0.0) || (f == 0 && *value <= 0.0)) {
                throw InputError(where() + ": '" + std::string(fields[f]) + "' is not " +
                                 (f == 0 ? "a wavelength in nm (finite, > 0)" : "a sensitivity (finite, >= 0)"));
            }
            row.push_back(*value);
        }
        if (!out.wavelengths_nm.empty() && row[0] <= out.wavelengths_nm.back()) {
            throw InputError(where() + ": wavelength " + format_number(row[0]) + " nm is not above the previous " +
                             format_number(out.wavelengths_nm.back()) + " nm (wavelengths must increase)");
        }
        out.wavelengths_nm.push_back(row[0]);
        for (std::size_t b = 0; b < out.names.size(); ++b) out.sensitivity[b].push_back(row[b + 1]);
    }
    if (out.wavelengths_nm.size() < 2) throw InputError(file.string() + ": needs a header and at least 2 rows of wavelength_nm,BAND,...");
    return out;
}

std::vector<std::vector<double>> band_weights(const BandSensitivities& bands, std::span<const double> nm) {
    std::vector<std::vector<double>> out;
    const auto& x = bands.wavelengths_nm;
    for (std::size_t b = 0; b < bands.names.size(); ++b) {
        const auto& s = bands.sensitivity[b];
        for (std::size_t i = 0; i < x.size(); ++i) {
            if (s[i] > 0.0 && (x[i] < nm.front() || x[i] > nm.back())) {
                throw InputError("band " + bands.names[b] + " is sensitive at " + format_number(x[i]) + " nm, outside the model's " +
                                 format_number(nm.front()) + "-" + format_number(nm.back()) + " nm");
            }
        }
        // Relative to the band's peak (only ratios matter; any finite scale then interpolates and sums finitely).
        const double peak = *std::max_element(s.begin(), s.end());
        std::vector<double> w;
        double sum = 0.0;
        for (const double l : nm) {
            double value = 0.0;
            if (peak > 0.0 && l >= x.front() && l <= x.back()) {
                const auto hi = static_cast<std::size_t>(std::lower_bound(x.begin(), x.end(), l) - x.begin());
                const double a = s[hi == 0 ? 0 : hi - 1] / peak, b = s[hi] / peak;
                value = x[hi] == l ? b : a + (b - a) * (l - x[hi - 1]) / (x[hi] - x[hi - 1]);
            }
            w.push_back(value);
            sum += value;
        }
        if (!(sum > 0.0)) {
            throw InputError("band " + bands.names[b] + " has no sensitivity at the model's wavelengths (" + format_number(nm.front()) + "-" +
                             format_number(nm.back()) + " nm)");
        }
        for (auto& v : w) v /= sum;
        out.push_back(std::move(w));
    }
    return out;
}

}  // namespace skinspec
