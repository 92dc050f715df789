#pragma once
// A multispectral camera's bands for `skinspec fit-image --bands` (docs/FIT_IMAGE.md): each band's relative spectral
// sensitivity against wavelength, and the reflectance factor a band records of a reflectance spectrum,
// sum R(lambda) S(lambda) / sum S(lambda) over the model's wavelengths (S linearly interpolated, 0 outside its table).
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace skinspec {

struct BandSensitivities {
    std::vector<std::string> names;
    std::vector<double> wavelengths_nm;            // strictly increasing
    std::vector<std::vector<double>> sensitivity;  // per band, per wavelength: finite, >= 0
};

// CSV: '#' comment lines, a header "wavelength_nm,NAME,..." (one column per band), then numeric rows. InputError
// naming the file, the line and the value for anything else (at most 16 bands).
BandSensitivities read_band_sensitivities(const std::filesystem::path& file);

// Per band, the weights of the grid's wavelengths (summing to 1). InputError when a band is sensitive outside
// [nm.front(), nm.back()] (the model computes nothing there) or nowhere on the grid.
std::vector<std::vector<double>> band_weights(const BandSensitivities& bands, std::span<const double> nm);

}  // namespace skinspec
