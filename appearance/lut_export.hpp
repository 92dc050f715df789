#pragma once
// The melanosome-fraction x blood-fraction look-up texture of diffuse skin albedo (as the maps of Jimenez et al.
// 2010 and Donner & Jensen 2006 are indexed) that `skinspec export lut` and skinspec.export_lut write from a swatch
// chart (appearance/swatch_chart.hpp): a linear OpenEXR texture, optionally the spectra (OpenEXR in the spectral
// layout of Fichet, Pacanowski & Wilkie 2021, or CSV) and a display-referred preview with labelled axes.
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "appearance/swatch_chart.hpp"

namespace skinspec {

inline constexpr const char* lut_melanin_field = "epidermis.melanosome_fraction";
inline constexpr const char* lut_blood_field = "dermis.blood_fraction";

// A sweep's values as the textures' metadata write them: "0.01,0.0137,...", each exact (shortest round trip).
std::string value_list(const ParameterSweep& sweep);

// `field`=`text` as a sweep; InputError naming `option` and the form FIRST:LAST:STEPS[:log].
ParameterSweep lut_axis(const std::string& field, const std::string& text, const std::string& option);

struct LutFiles {
    std::filesystem::path texture;  // .exr, required
    std::filesystem::path spectra;  // .exr or .csv, or empty
    std::filesystem::path preview;  // .png, .tif or .tiff, or empty
    std::string space = "ACEScg";   // the texture's linear working space (an OCIO colour space)
    bool half = false;              // half float instead of float
    std::string display = "sRGB";   // the preview's OCIO display and view
    std::string view = "Standard";
    bool overwrite = false;
};

// Every output checked before any work (extension, folder, existing files unless overwrite, the space, the display
// and view, the texture size): InputError naming the file or value. Returns `files` with the space's canonical name.
LutFiles check_lut_files(const LutFiles& files, const ParameterSweep& columns, const ParameterSweep& rows);

struct LutSummary {
    std::uint64_t rays = 0;
    double worst_delta_e = 0.0;  // the largest texel's CIEDE2000 uncertainty
};

// Writes the texture (and the spectra and preview when asked) of `chart`, computed for `request` (its sweeps: columns
// u, rows v); `files` as check_lut_files returned it. A partial chart's finished texels are written, the rest black,
// and the metadata says partial.
LutSummary write_lut_files(const SwatchChart& chart, const SwatchRequest& request, const LutFiles& files);

// The summary `skinspec export lut --json` prints and skinspec.export_lut returns.
nlohmann::ordered_json lut_summary_json(const SwatchChart& chart, const SwatchRequest& request, const LutFiles& files, const LutSummary& summary,
                                        double seconds, int processes);

}  // namespace skinspec
