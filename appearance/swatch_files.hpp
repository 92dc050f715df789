#pragma once
// A swatch chart's image files (`skinspec swatch -o`, skinspec.swatch(output=...)): a linear OpenEXR of the patches'
// colours in a working space, or a display-referred PNG / TIFF through OpenColorIO with the swept fields on labelled
// axes and each patch's sRGB value; the chart's provenance (model, material, seed, sweeps, per-patch Lab
// uncertainty, settings) in the metadata.
#include <filesystem>
#include <string>
#include <vector>

#include "appearance/swatch_chart.hpp"
#include "spectral/chart_image.hpp"

namespace skinspec {

struct SwatchFiles {
    ImageOutputs images;
    int patch_px = 112;  // [32, 2048]
};

// Every output checked before any work (patch size, chart size, and check_image_outputs); returns `files` with the
// space's canonical name.
SwatchFiles check_swatch_files(const SwatchFiles& files, const SwatchRequest& request);
// Writes `chart` (computed for `request`) to every output of `files` (as check_swatch_files returned them).
void write_swatch_files(const SwatchChart& chart, const SwatchRequest& request, const SwatchFiles& files);

}  // namespace skinspec
