#pragma once
// Data-driven versus Henyey-Greenstein thin layers inside the BioSpec skin model: the same stack, seed and
// request solved with the measured profiles and with HG, the difference per wavelength with its combined
// standard error, and (for reflectance) the colour difference.
#include <string>
#include <vector>

#include "transport/biospec/biospec_options.hpp"
#include "transport/spectral_request.hpp"
#include "materials/layer_stack.hpp"
#include "spectral/colorimetry.hpp"

namespace skinspec {

inline constexpr double significance_sigmas = 3.0;

struct PhaseComparisonRow {
    double wavelength_nm = 0.0;
    Estimate measured;
    Estimate hg;
    Estimate difference;  // hg - measured, stderr combined in quadrature (independent runs)
    bool significant = false;  // |difference| > 3 combined standard errors
};

struct PhaseComparison {
    std::string material;
    std::string quantity;  // "R" or "T"
    std::vector<PhaseComparisonRow> rows;
    std::size_t significant_count = 0;
    std::optional<double> delta_e00;  // colour of measured vs HG reflectance (spans 400-700 nm only)
    std::optional<double> delta_e00_uncertainty;
};

enum class ComparedQuantity { reflectance, transmittance };

PhaseComparison compare_thin_layer_phase(const LayerStack& stack, const SpectralRequest& request, const ThinLayerHg& hg,
                                         ComparedQuantity quantity, IlluminantKind illuminant = IlluminantKind::d65);

}  // namespace skinspec
