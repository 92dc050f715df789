#pragma once
// Options of the BioSpec walk that are not properties of the skin (those live in the LayerStack).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace skinspec {

enum class AbsorptionEstimator {
    weighted,     // multiply the ray weight by exp(-mu_a d / |cos|) on each crossing (expected value; default)
    random_test,  // the original: the ray survives each crossing with that probability
};

enum class FoldIntoSkin {
    drop,      // the 2004 code: a fold-perturbed reflection pointing into the skin is lost (A_surface)
    resample,  // draw the perturbation again until it points out of the skin
};

// Henyey-Greenstein in place of the measured profiles of the thin layers (SC and epidermis), with g as a
// function of wavelength (nm); for comparing data-driven and HG scattering inside the skin model.
struct ThinLayerHg {
    std::function<double(double)> stratum_corneum_g;
    std::function<double(double)> epidermis_g;
    std::string source;  // recorded in the result's settings
};

struct BiospecOptions {
    AbsorptionEstimator estimator = AbsorptionEstimator::weighted;
    FoldIntoSkin fold_into_skin = FoldIntoSkin::drop;
    // Interface and layer crossings per ray before it is stopped; its remaining weight is then counted as
    // absorbed in its current layer and the ray is reported in truncated_rays.
    std::uint32_t max_events_per_ray = 1'000'000;
    std::size_t profile_table_entries = 1000;  // randomized table look-up size (Baranoski et al. 2005 Sec. 4)
    std::optional<ThinLayerHg> thin_layer_hg;  // unset: the measured profiles (default)
};

std::string_view to_string(AbsorptionEstimator estimator);
std::string_view to_string(FoldIntoSkin fold);
AbsorptionEstimator parse_absorption_estimator(std::string_view text, std::string_view what);
FoldIntoSkin parse_fold_into_skin(std::string_view text, std::string_view what);

}  // namespace skinspec
