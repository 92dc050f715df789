#pragma once
// Data-driven versus Henyey-Greenstein thin layers inside the BioSpec skin model: the same stack, seed and
// request solved with the measured profiles and with HG, the difference per wavelength with its combined
// standard error, and (for reflectance) the colour difference.
#include <cstdint>
#include <string>
#include <vector>

#include "transport/biospec/biospec_options.hpp"
#include "transport/spectral_request.hpp"
#include "materials/layer_stack.hpp"
#include "spectral/colorimetry.hpp"

namespace skinspec {

inline constexpr double significance_sigmas = 3.0;

// compare-phase's defaults, for the command and the Python function alike.
struct ComparePhaseDefaults {
    static constexpr const char* wavelengths = "400:700:10";
    static constexpr double stderr_target = 0.002;
    static constexpr std::uint64_t max_rays = 10'000'000;
    static constexpr const char* hg_source = "rms";
};

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

// The HG thin layers to compare with: "rms" (g fitted by RMS, Baranoski et al. 2005 Eq. 9), "van-gemert" (van
// Gemert et al. 1989) or a number in [-1, 1]; InputError naming `what` otherwise.
ThinLayerHg thin_layer_hg(const std::string& source, const std::string& what);

// compare-phase for one skin: R of the whole skin, then T of its stratum corneum and epidermis with no reflector
// below (what the thin layers' phase function changes most directly).
std::vector<PhaseComparison> compare_phase_in_skin(const LayerStack& stack, const SpectralRequest& request, const ThinLayerHg& hg);

}  // namespace skinspec
