#pragma once
// The table fit-image inverts through, made from a swatch chart (appearance/swatch_chart.hpp: the material solved
// over the two fields by a registered solver): each node's reflectance spectrum as the image records it, either the
// colour of the albedo as linear RGB in a working space (CIE observer and illuminant of the chart, then OpenColorIO;
// white = 1) or a multispectral camera's band reflectance factors.
#include <string_view>

#include "appearance/swatch_chart.hpp"
#include "inverse/image_fit/albedo_lut.hpp"
#include "inverse/image_fit/band_sensitivities.hpp"
#include "spectral/color_management.hpp"

namespace skinspec {

// `chart` complete (columns x rows patches of the sweeps u, v).
AlbedoLut rgb_albedo_lut(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v, std::string_view space, const ColorManagement& cm);
AlbedoLut band_albedo_lut(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v, const BandSensitivities& bands);

}  // namespace skinspec
