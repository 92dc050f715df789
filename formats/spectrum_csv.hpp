#pragma once
// Reader for spectrum files: CSV "wavelength_nm,value" (comma- or blank-separated), an optional header line,
// '#' comments and blank lines allowed; also files with more columns under a header, such as `skinspec
// spectrum --output F.csv` writes (material,wavelength_nm,R,R_stderr,...): the value column is chosen by name
// (default R when there is one) and, when a `material` column holds several materials, the rows of one; a column
// named VALUE_stderr next to it is read as the value's standard errors. A sweep's file (`spectrum --vary`) holds its
// members one after another, each named by its swept fields' values in the columns before wavelength_nm: one is
// chosen by its position or by those values. A `spectrum --json` file (schema skinspec-spectral-result/1) is read
// the same way: the results of one material, one member among them, a value array with its _stderr array.
// Every problem is an InputError of one line naming file, line, field, value and the allowed range.
#include <filesystem>
#include <string>
#include <vector>

#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

struct SpectrumFileRules {
    const char* quantity = "reflectance";  // name of the value column in messages
    bool allow_over_one = false;           // values above 1 allowed (e.g. fluorescent samples)
    double must_cover_from_nm = 400.0;     // the samples must span at least this range
    double must_cover_to_nm = 700.0;
    OutOfRangePolicy outside = OutOfRangePolicy::hold;  // policy of the returned spectrum
    std::string column;    // value column by header name ("" = the second of two columns, else R)
    std::string material;  // rows whose `material` column is this ("" = the only material in the file)
    std::size_t member = 0;  // a sweep's member by position, 1 = the first in the file (0: chosen by `where`, or the only one)
    std::vector<std::pair<std::string, double>> where;  // a sweep's member by its swept fields' values
};

struct SpectrumFile {
    TabulatedSpectrum spectrum;
    std::vector<double> standard_errors;  // the VALUE_stderr column (e.g. R_stderr), one per sample; empty without one
};

SpectrumFile read_spectrum_file(const std::filesystem::path& file, const SpectrumFileRules& rules = {});

// Whether `file` is a result skinspec wrote (spectrum --output F.csv, --json): its first line is a '# skinspec'
// comment or it is a JSON object. A file that cannot be read is an InputError naming it as `kind`.
bool is_skinspec_result(const std::filesystem::path& file, const char* kind = "spectrum file");

// Every spectrum of a skinspec result, one per material and sweep member in file order, each read as
// read_spectrum_file reads it under `rules` (its material and member set here) and named "MATERIAL" or, in a
// sweep, "MATERIAL[FIELD=VALUE;FIELD=VALUE]" (no blank or comma: one field of a CSV).
struct NamedSpectrum {
    std::string name;
    SpectrumFile file;
};
std::vector<NamedSpectrum> read_result_spectra(const std::filesystem::path& file, SpectrumFileRules rules);
// The spectrum alone.
TabulatedSpectrum read_spectrum_csv(const std::filesystem::path& file, const SpectrumFileRules& rules = {});

}  // namespace skinspec
