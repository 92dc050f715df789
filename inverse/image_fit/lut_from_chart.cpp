#include "inverse/image_fit/lut_from_chart.hpp"

#include <stdexcept>

namespace skinspec {
namespace {

void check_complete(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v) {
    if (chart.partial || chart.patches.size() != u.steps * v.steps) throw std::logic_error("fit-image: the table's chart is not complete");
}

}  // namespace

AlbedoLut rgb_albedo_lut(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v, std::string_view space, const ColorManagement& cm) {
    check_complete(chart, u, v);
    std::vector<double> values;
    for (const auto& p : chart.patches) {
        const auto rgb = cm.from_xyz(p.xyz, chart.white, space);
        values.insert(values.end(), rgb.begin(), rgb.end());
    }
    return AlbedoLut(u, v, {"R", "G", "B"}, std::move(values));
}

AlbedoLut band_albedo_lut(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v, const BandSensitivities& bands) {
    check_complete(chart, u, v);
    const auto weights = band_weights(bands, chart.wavelengths.nm());
    std::vector<double> values;
    for (const auto& p : chart.patches) {
        for (const auto& w : weights) {
            double sum = 0.0;
            for (std::size_t i = 0; i < w.size(); ++i) sum += w[i] * p.reflectance[i];
            values.push_back(sum);
        }
    }
    return AlbedoLut(u, v, bands.names, std::move(values));
}

}  // namespace skinspec
