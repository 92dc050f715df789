#include "studies/phase_study/phase_study.hpp"

#include <algorithm>

#include "materials/measured_profile.hpp"
#include "skinspec/version.hpp"
#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"

namespace skinspec {
namespace {

const MeasuredProfile& profile_of(const std::string& tissue) {
    return tissue == "stratum_corneum" ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis();
}

double van_gemert_g(const std::string& tissue, double wavelength_nm) {
    static const auto table = DataTable::read(data_file("scattering/hg_asymmetry_van_gemert_1989.csv"));
    return table.spectrum(tissue + "_g", "van Gemert g")(wavelength_nm);
}

double linear_between(double at_436, double at_546, double wavelength_nm) {
    const double t = std::clamp((wavelength_nm - 436.0) / (546.0 - 436.0), 0.0, 1.0);
    return at_436 + t * (at_546 - at_436);
}

}  // namespace

std::string_view to_string(PhaseApproach approach) {
    switch (approach) {
        case PhaseApproach::table_lookup: return "table_lookup";
        case PhaseApproach::hg_rms: return "hg_rms";
        case PhaseApproach::hg_van_gemert: return "hg_van_gemert";
    }
    return "?";
}

std::vector<std::pair<std::string, double>> phase_study_cases() {
    return {{"stratum_corneum", 436.0}, {"stratum_corneum", 546.0}, {"epidermis", 436.0}, {"epidermis", 546.0}};
}

PhaseStudy run_phase_study(const PhaseStudySettings& settings) {
    PhaseStudy study;
    const auto angles = MeasuredProfile::stratum_corneum().angles_deg();
    study.bin_edges_deg.assign(angles.begin(), angles.end());
    for (const auto& [tissue, nm] : phase_study_cases()) {
        {
            PhaseCase c;
            c.tissue = tissue;
            c.wavelength_nm = nm;
            const auto& profile = profile_of(c.tissue);
            const auto cumulative = profile.cumulative(nm);
            c.measured_fractions = measured_bin_fractions(cumulative);
            c.rms_fit = fit_hg_rms(cumulative, study.bin_edges_deg);
            c.g_van_gemert = van_gemert_g(c.tissue, nm);
            c.rms_van_gemert = rms_error(c.measured_fractions, hg_bin_fractions(c.g_van_gemert, study.bin_edges_deg));
            c.samplers = {table_angle_sampler(profile.inverse_table(nm, 1000)), hg_angle_sampler(c.rms_fit.g),
                          hg_angle_sampler(c.g_van_gemert)};
            for (std::size_t a = 0; a < c.samplers.size(); ++a) {
                // Distinct streams per case and approach (the wavelength key carries both).
                const double key = nm + 1000.0 * static_cast<double>(a) + (c.tissue == "epidermis" ? 0.5 : 0.0);
                c.sampled.push_back(bin_samples(c.samplers[a], study.bin_edges_deg, settings.sampling_samples, settings.seed, key));
                c.errors.push_back(relative_errors(c.sampled.back().fractions, c.measured_fractions));
                const auto gonio = bin_samples(c.samplers[a], study.bin_edges_deg, settings.goniometer_samples, settings.seed, key + 0.25);
                c.btdf_per_sr.push_back(goniometer_btdf_per_sr(gonio.fractions, study.bin_edges_deg));
            }
            c.btdf_measured_per_sr = goniometer_btdf_per_sr(c.measured_fractions, study.bin_edges_deg);
            study.cases.push_back(std::move(c));
        }
    }
    // Cost: both samplers of the first case, timed back to back in one call.
    const auto seconds = seconds_per_sample({study.cases.front().samplers[1], study.cases.front().samplers[0]}, settings.cost_samples);
    study.seconds_per_sample_hg = seconds[0];
    study.seconds_per_sample_lookup = seconds[1];
    return study;
}

double ThinLayerAsymmetry::stratum_corneum(double nm) const { return linear_between(sc_436, sc_546, nm); }
double ThinLayerAsymmetry::epidermis(double nm) const { return linear_between(ep_436, ep_546, nm); }

ThinLayerAsymmetry thin_layer_asymmetry_rms() {
    static const ThinLayerAsymmetry fitted = [] {
        const auto angles = MeasuredProfile::stratum_corneum().angles_deg();
        const std::vector<double> edges(angles.begin(), angles.end());
        const auto g = [&](const MeasuredProfile& p, double nm) { return fit_hg_rms(p.cumulative(nm), edges).g; };
        return ThinLayerAsymmetry{g(MeasuredProfile::stratum_corneum(), 436.0), g(MeasuredProfile::stratum_corneum(), 546.0),
                                  g(MeasuredProfile::epidermis(), 436.0), g(MeasuredProfile::epidermis(), 546.0)};
    }();
    return fitted;
}

ThinLayerAsymmetry thin_layer_asymmetry_van_gemert() {
    return ThinLayerAsymmetry{van_gemert_g("stratum_corneum", 436.0), van_gemert_g("stratum_corneum", 546.0),
                              van_gemert_g("epidermis", 436.0), van_gemert_g("epidermis", 546.0)};
}

nlohmann::ordered_json phase_study_json(const PhaseStudy& s) {
    using Json = nlohmann::ordered_json;
    Json cases = Json::array();
    for (const auto& c : s.cases) {
        Json approaches = Json::object();
        for (std::size_t a = 0; a < c.samplers.size(); ++a) {
            approaches[std::string(to_string(all_phase_approaches[a]))] =
                Json{{"fractions", c.sampled[a].fractions}, {"kept", c.sampled[a].kept}, {"drawn", c.sampled[a].drawn},
                     {"max_relative_error_percent", c.errors[a].max_percent},
                     {"average_relative_error_percent", c.errors[a].average_percent}, {"btdf_per_sr", c.btdf_per_sr[a]}};
        }
        cases.push_back(Json{{"tissue", c.tissue}, {"wavelength_nm", c.wavelength_nm},
                             {"measured_fractions", c.measured_fractions}, {"g_rms", c.rms_fit.g}, {"rms_at_g_rms", c.rms_fit.rms},
                             {"nelder_mead_evaluations", c.rms_fit.evaluations}, {"g_van_gemert", c.g_van_gemert},
                             {"rms_at_g_van_gemert", c.rms_van_gemert}, {"btdf_measured_per_sr", c.btdf_measured_per_sr},
                             {"approaches", approaches}});
    }
    return Json{{"skinspec_version", version}, {"bin_edges_deg", s.bin_edges_deg}, {"cases", cases},
                {"seconds_per_sample_hg_warping", s.seconds_per_sample_hg},
                {"seconds_per_sample_table_lookup", s.seconds_per_sample_lookup},
                {"cost_ratio_hg_over_lookup", s.seconds_per_sample_hg / s.seconds_per_sample_lookup}};
}

}  // namespace skinspec
