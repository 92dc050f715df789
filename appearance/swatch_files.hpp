#pragma once
// A swatch chart's image files (`skinspec swatch -o`, skinspec.swatch(output=...)): a linear OpenEXR of the patches'
// colours in a working space, or a display-referred PNG / TIFF through OpenColorIO with the swept fields on labelled
// axes and each patch's sRGB value; the chart's provenance (model, material, seed, sweeps, per-patch Lab
// uncertainty, settings) in the metadata.
#include <filesystem>
#include <string>
#include <vector>

#include "appearance/swatch_chart.hpp"

namespace skinspec {

struct SwatchFiles {
    std::vector<std::filesystem::path> outputs;  // .exr (linear), .png, .tif, .tiff (display-referred)
    std::string space = "ACEScg";                // working space of the patches
    bool half = false;                           // EXR in half float
    std::string display = "sRGB";
    std::string view = "Standard";
    int patch_px = 112;  // [32, 2048]
    bool overwrite = false;
};

// Every output checked before any work (patch size, chart size, space, display and view, extension, folder,
// existing files unless overwrite); returns `files` with the space's canonical name.
SwatchFiles check_swatch_files(const SwatchFiles& files, const SwatchRequest& request);
// Writes `chart` (computed for `request`) to every output of `files` (as check_swatch_files returned them).
void write_swatch_files(const SwatchChart& chart, const SwatchRequest& request, const SwatchFiles& files);

}  // namespace skinspec
