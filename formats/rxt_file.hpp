#pragma once
// Reader of the measurement files Prahl's `iad` reads (.rxt; iad manual, "The Data File"), so that a lab can switch
// tools without rewriting its data. "IAD1" first; then, '#' comments and blanks anywhere, the header numbers in
// order: sample index, slide index, sample thickness [mm], slide thickness [mm], beam diameter [mm], reflectance of
// the reflection standard, number of spheres, the reflection sphere (diameter, sample port, entrance port, detector
// port [mm], wall reflectance) and the transmission sphere (diameter, sample port, third port, detector port [mm],
// wall reflectance); then the data legend and the rows. The legend is either a count of columns (1-7:
// [wavelength] M_R [M_T [M_U [w [W [R [T]]]]]], a first number above 1 being the wavelength) or one letter per
// column: L (wavelength), r, t, u (M_R, M_T, M_U) and the letters of the setup fields (inverse/iad/slab_measurement.hpp:
// n N d D B i S R T c C f g w W; M is iad's other letter for S); w also sets W unless a W column is given.
// A slide of thickness 0 or index 0 or 1 is no slide. Every problem is an InputError naming file and line.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "inverse/iad/slab_measurement.hpp"

namespace skinspec {

struct RxtFile {
    SlabSetup setup;                    // the header's (each row's own setup is in its SlabMeasurement)
    std::vector<SlabMeasurement> rows;  // in file order
};

RxtFile read_rxt(const std::filesystem::path& file);
RxtFile parse_rxt(std::string_view text, const std::string& name);

// Measurements given directly (options, or arrays from Python): one row per M_R; M_T, M_U and the wavelengths empty
// or one per M_R.
struct GivenMeasurements {
    std::vector<double> m_r, m_t, m_u, wavelength_nm;
};

// What `skinspec iad` and skinspec.iad solve: the rows of `file`, or (no file) the given measurements in the default
// setup; `setup` (a setup field's key -> value, inverse/iad/slab_measurement.hpp) applies to every row and to the header.
// InputError for both a file and measurements, neither, lists of other lengths, an unknown key, or any row
// check_measurement refuses.
struct IadInput {
    SlabSetup setup;
    std::vector<SlabMeasurement> rows;
    std::string name;  // the file, or "options"
};
IadInput iad_input(const std::optional<std::filesystem::path>& file, const GivenMeasurements& given, const std::map<std::string, double>& setup);

}  // namespace skinspec
