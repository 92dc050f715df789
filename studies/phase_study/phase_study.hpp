#pragma once
// The experiments of Baranoski, Krishnaswamy & Kimmel 2005 (Sec. 4-5) for the four measured
// profiles (stratum corneum and epidermis at 436 and 546 nm): HG fits (Table 2), sampling errors
// (Table 3), the virtual goniometer (Figs. 6-9) and the cost of HG warping against table look-up.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "studies/phase_study/hg_fit.hpp"
#include "studies/phase_study/phase_sampling.hpp"

namespace skinspec {

enum class PhaseApproach { table_lookup, hg_rms, hg_van_gemert };
inline constexpr PhaseApproach all_phase_approaches[] = {PhaseApproach::table_lookup, PhaseApproach::hg_rms,
                                                        PhaseApproach::hg_van_gemert};
std::string_view to_string(PhaseApproach approach);

struct PhaseCase {
    std::string tissue;  // "stratum_corneum" or "epidermis"
    double wavelength_nm = 0.0;
    std::vector<double> measured_fractions;  // Eq. 6
    HgFit rms_fit;                           // Table 2, RMS row
    double g_van_gemert = 0.0;               // Table 2, van Gemert row
    double rms_van_gemert = 0.0;             // Eq. 9 at van Gemert's g
    // Indexed like all_phase_approaches.
    std::vector<BinnedSamples> sampled;      // N = sampling_samples
    std::vector<RelativeErrors> errors;      // Table 3
    std::vector<std::vector<double>> btdf_per_sr;  // N = goniometer_samples, Eq. 10
    std::vector<double> btdf_measured_per_sr;
    std::vector<AngleSampler> samplers;
};

struct PhaseStudy {
    std::vector<double> bin_edges_deg;  // 0, 2.5, 7.5, ..., 62.5
    std::vector<PhaseCase> cases;
    double seconds_per_sample_hg = 0.0;      // HG warping (Eq. 5 and arccos)
    double seconds_per_sample_lookup = 0.0;  // randomized table look-up (1000 entries)
};

struct PhaseStudySettings {
    std::uint64_t seed = 1;
    std::uint64_t sampling_samples = 100'000;
    std::uint64_t goniometer_samples = 1'000'000;
    std::uint64_t cost_samples = 20'000'000;
};

PhaseStudy run_phase_study(const PhaseStudySettings& settings);
// Every table's numbers, as `skinspec phase-study --json` prints them and skinspec.phase_study returns them.
nlohmann::ordered_json phase_study_json(const PhaseStudy& study);
// The study's cases in order, (tissue, wavelength nm), known before it runs (so that outputs are checked first).
std::vector<std::pair<std::string, double>> phase_study_cases();

// g of HG standing in for a measured profile at any wavelength: the fitted (RMS) or van Gemert values at 436
// and 546 nm, linear in wavelength between them and held outside (issue "compare-phase").
struct ThinLayerAsymmetry {
    double stratum_corneum(double wavelength_nm) const;
    double epidermis(double wavelength_nm) const;
    double sc_436 = 0.0, sc_546 = 0.0, ep_436 = 0.0, ep_546 = 0.0;
};
ThinLayerAsymmetry thin_layer_asymmetry_rms();
ThinLayerAsymmetry thin_layer_asymmetry_van_gemert();

}  // namespace skinspec
