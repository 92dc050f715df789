#pragma once
// Reader for user spectrum files: CSV "wavelength_nm,value" (comma- or blank-separated), an optional
// header line, '#' comments and blank lines allowed. Every problem is an InputError of one line naming
// file, line, field, value and the allowed range.
#include <filesystem>

#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

struct SpectrumFileRules {
    const char* quantity = "reflectance";  // name of the value column in messages
    bool allow_over_one = false;           // values above 1 allowed (e.g. fluorescent samples)
    double must_cover_from_nm = 400.0;     // the samples must span at least this range
    double must_cover_to_nm = 700.0;
    OutOfRangePolicy outside = OutOfRangePolicy::hold;  // policy of the returned spectrum
};

TabulatedSpectrum read_spectrum_csv(const std::filesystem::path& file, const SpectrumFileRules& rules = {});

}  // namespace skinspec
