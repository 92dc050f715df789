#include "formats/profile_inputs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "spectral/chart_image.hpp"
#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// CSV lines without '#' comments or blanks, split; the first line is the header.
std::vector<std::vector<std::string>> read_csv(const std::string& file) {
    auto in = open_input_file(file, "CSV file");
    std::vector<std::vector<std::string>> rows;
    std::string line;
    while (std::getline(in, line)) {
        const auto t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        std::vector<std::string> fields;
        for (const auto f : split_fields(t)) fields.emplace_back(f);
        rows.push_back(std::move(fields));
    }
    if (rows.size() < 2) throw InputError(file + ": needs a header line and at least one data line");
    return rows;
}

double number(const std::string& file, std::size_t row, const std::string& field, const std::string& text) {
    const auto v = parse_double(text);
    if (!v || !std::isfinite(*v)) throw InputError(fmt::format("{}: data line {}: field '{}' = '{}' is not a finite number", file, row, field, text));
    return *v;
}

}  // namespace

SurfacePatch surface_patch(const std::array<double, 9>& v, const std::string& where) {
    const double normal = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
    if (!(std::abs(normal - 1.0) <= 1e-3)) throw InputError(fmt::format("{}: the normal has length {:.4g}, expected 1", where, normal));
    if (v[6] < 0.0 || v[7] < 0.0) throw InputError(where + ": c and l must be in [0, inf)");
    if (v[8] != 0.0 && v[8] != 1.0) throw InputError(fmt::format("{}: field 'visible' = {} is not 0 or 1", where, format_number(v[8])));
    return {{v[0], v[1], v[2]}, v[6], v[7], v[8] == 1.0};
}

std::vector<SurfacePatch> read_patch_list(const std::string& file) {
    const auto rows = read_csv(file);
    const std::vector<std::string> header{"x_mm", "y_mm", "z_mm", "nx", "ny", "nz", "c", "l", "visible"};
    if (rows[0] != header) throw InputError(file + ": the header must be x_mm,y_mm,z_mm,nx,ny,nz,c,l,visible");
    std::vector<SurfacePatch> patches;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto& r = rows[i];
        if (r.size() != header.size()) throw InputError(fmt::format("{}: data line {} has {} fields, expected 9", file, i, r.size()));
        std::array<double, 9> v{};
        for (std::size_t k = 0; k < 9; ++k) v[k] = number(file, i, header[k], r[k]);
        patches.push_back(surface_patch(v, fmt::format("{}: data line {}", file, i)));
    }
    return patches;
}

RadialSamples read_radial_profile(const std::string& file, const std::string& column) {
    const auto rows = read_csv(file);
    std::size_t k = 1;
    if (!column.empty()) {
        const auto it = std::find(rows[0].begin(), rows[0].end(), column);
        if (it == rows[0].end()) throw InputError(file + ": no column '" + column + "'");
        k = static_cast<std::size_t>(it - rows[0].begin());
    }
    if (rows[0].size() < 2 || k == 0) throw InputError(file + ": expected r_mm and a profile column (1/mm^2)");
    RadialSamples samples;
    // The entry transmittance the file records for the column, if any.
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with(radial_entry_transmittance_comment)) continue;
        const auto key = " " + rows[0][k] + "=";
        const auto at = line.find(key);
        if (at == std::string::npos) continue;
        const auto end = line.find(',', at);
        const auto text = line.substr(at + key.size(), end == std::string::npos ? std::string::npos : end - at - key.size());
        const auto value = parse_double(trim(text));
        if (!value || !(*value > 0.0 && *value <= 1.0)) {
            throw InputError(file + ": entry transmittance of " + rows[0][k] + " = '" + text + "' is outside (0, 1]");
        }
        samples.entry_transmittance = *value;
    }
    for (std::size_t i = 1; i < rows.size(); ++i) {
        if (rows[i].size() != rows[0].size()) throw InputError(fmt::format("{}: data line {} has {} fields, expected {}", file, i, rows[i].size(), rows[0].size()));
        samples.radii_mm.push_back(number(file, i, rows[0][0], rows[i][0]));
        samples.profile_per_mm2.push_back(number(file, i, rows[0][k], rows[i][k]) / samples.entry_transmittance);
    }
    return samples;
}

void check_pitch(double pitch_mm) {
    if (!(pitch_mm > 0.0) || !std::isfinite(pitch_mm)) throw InputError("--pitch = " + format_number(pitch_mm) + " mm is outside (0, inf)");
}

PlanarScene planar_scene(int width, int height, double pitch_mm, std::vector<double> irradiance_per_mm2, std::vector<double> exitance_per_mm2,
                         std::vector<char> valid) {
    check_pitch(pitch_mm);
    for (auto& e : irradiance_per_mm2) e *= pitch_mm * pitch_mm;  // power entering the pixel
    return {width, height, pitch_mm, std::move(irradiance_per_mm2), std::move(exitance_per_mm2), std::move(valid)};
}

std::vector<PlanarScene> read_planar_scenes(const PlanarInputs& inputs, std::vector<std::string>& channel_names) {
    check_pitch(inputs.pitch_mm);
    const auto e = read_data_image(inputs.irradiance);
    const auto l = read_data_image(inputs.exitance);
    if (e.width != l.width || e.height != l.height) {
        throw InputError(fmt::format("{} is {}x{} but {} is {}x{}: the images must have the same size", inputs.irradiance, e.width, e.height,
                                     inputs.exitance, l.width, l.height));
    }
    if (e.channels != l.channels) throw InputError(fmt::format("{} has {} channels but {} has {}", inputs.irradiance, e.channels, inputs.exitance, l.channels));
    std::vector<char> valid(static_cast<std::size_t>(e.width) * e.height, 1);
    if (!inputs.mask.empty()) {
        const auto m = read_data_image(inputs.mask);
        if (m.width != e.width || m.height != e.height) throw InputError(fmt::format("{} is {}x{}, the images {}x{}", inputs.mask, m.width, m.height, e.width, e.height));
        for (std::size_t p = 0; p < valid.size(); ++p) valid[p] = m.values[p * m.channels] > 0.0f ? 1 : 0;
    }
    const int channels = std::min(e.channels, 3);  // colour channels; alpha is ignored
    std::vector<PlanarScene> scenes;
    for (int c = 0; c < channels; ++c) {
        std::vector<double> irradiance, exitance;
        for (std::size_t p = 0; p < valid.size(); ++p) {
            irradiance.push_back(e.values[p * e.channels + c]);
            exitance.push_back(l.values[p * l.channels + c]);
        }
        scenes.push_back(planar_scene(e.width, e.height, inputs.pitch_mm, std::move(irradiance), std::move(exitance), valid));
        channel_names.push_back(c < static_cast<int>(e.channel_names.size()) ? e.channel_names[c] : fmt::format("channel{}", c));
    }
    return scenes;
}

}  // namespace skinspec
