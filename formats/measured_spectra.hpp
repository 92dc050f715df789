#pragma once
// Reader for measured reflectance spectra to fit: CSV with a header `wavelength_nm,NAME1,NAME2,...` (one column
// per spectrum; a two-column file is one spectrum), '#' comments and blank lines allowed, commas or blanks between
// fields; or a result skinspec wrote (spectrum --output F.csv or --json: its R, every material and sweep member a
// spectrum named after it, all on one wavelength grid). Every problem is an InputError naming file, line and column: a value that is not a finite number in
// [0, 1.5], a wavelength that does not increase, a row with the wrong number of fields, fewer than 5 rows.
#include <filesystem>
#include <string>
#include <vector>

namespace skinspec {

struct MeasuredSpectra {
    std::string file;
    std::vector<double> wavelength_nm;
    std::vector<std::string> names;               // per spectrum, from the header
    std::vector<std::vector<double>> reflectance;  // [spectrum][wavelength]
    std::vector<std::string> row_sources;          // where each wavelength was read, "FILE:LINE" (messages)
};

inline constexpr std::size_t min_measured_points = 5;
inline constexpr double max_measured_reflectance = 1.5;

MeasuredSpectra read_measured_spectra(const std::filesystem::path& file);

}  // namespace skinspec
