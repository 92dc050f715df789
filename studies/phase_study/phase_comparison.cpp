#include "studies/phase_study/phase_comparison.hpp"

#include <cmath>

#include "solvers/spectral_solver.hpp"
#include "spectral/ciede2000.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "studies/phase_study/phase_study.hpp"

namespace skinspec {

PhaseComparison compare_thin_layer_phase(const LayerStack& stack, const SpectralRequest& request, const ThinLayerHg& hg,
                                         ComparedQuantity quantity, IlluminantKind illuminant) {
    SolverRequest r{request, {}, {}, {}, {}};
    r.spectral.quantities = Quantities{true, quantity == ComparedQuantity::transmittance, false, false};
    const auto& walk = find_solver("biospec");
    const auto measured = solve_spectrum(walk, stack, r);
    r.switches.thin_layer_hg = hg;
    const auto modelled = solve_spectrum(walk, stack, r);
    PhaseComparison out;
    out.material = stack.name;
    out.quantity.assign(1, quantity == ComparedQuantity::reflectance ? 'R' : 'T');  // one letter
    const auto pick = [&](const WavelengthResult& w) { return quantity == ComparedQuantity::reflectance ? w.reflectance : w.transmittance; };
    std::vector<double> nm, r_measured, r_hg, se_measured, se_hg;
    for (std::size_t i = 0; i < measured.wavelengths.size() && i < modelled.wavelengths.size(); ++i) {
        PhaseComparisonRow row;
        row.wavelength_nm = measured.wavelengths[i].wavelength_nm;
        row.measured = pick(measured.wavelengths[i]);
        row.hg = pick(modelled.wavelengths[i]);
        row.difference = {row.hg.value - row.measured.value, std::hypot(row.hg.stderr, row.measured.stderr)};
        row.significant = std::abs(row.difference.value) > significance_sigmas * row.difference.stderr;
        out.significant_count += row.significant;
        nm.push_back(row.wavelength_nm);
        r_measured.push_back(measured.wavelengths[i].reflectance.value);
        r_hg.push_back(modelled.wavelengths[i].reflectance.value);
        se_measured.push_back(measured.wavelengths[i].reflectance.stderr);
        se_hg.push_back(modelled.wavelengths[i].reflectance.stderr);
        out.rows.push_back(row);
    }
    if (quantity == ComparedQuantity::reflectance && nm.size() >= 2 && nm.front() <= 400.0 && nm.back() >= 700.0) {
        const TristimulusWeights weights(nm, illuminant, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold);
        const auto lab = [&](const std::vector<double>& v) { return xyz_to_lab(weights.integrate(v), weights.white()); };
        out.delta_e00 = ciede2000(lab(r_measured), lab(r_hg));
        out.delta_e00_uncertainty = std::hypot(ciede2000_uncertainty(weights, r_measured, se_measured),
                                               ciede2000_uncertainty(weights, r_hg, se_hg));
    }
    return out;
}

ThinLayerHg thin_layer_hg(const std::string& source, const std::string& what) {
    if (source == "rms" || source == "van-gemert") {
        const auto g = source == "rms" ? thin_layer_asymmetry_rms() : thin_layer_asymmetry_van_gemert();
        return {[g](double nm) { return g.stratum_corneum(nm); }, [g](double nm) { return g.epidermis(nm); },
                source == "rms" ? "g fitted by RMS (Eq. 9), linear 436-546 nm, clamped" : "g of van Gemert et al. 1989, linear 436-546 nm, clamped"};
    }
    const auto value = parse_double(source);
    if (!value || !(*value >= -1.0 && *value <= 1.0)) {  // NaN is outside too
        throw InputError(what + " '" + source + "' is not allowed (allowed: rms, van-gemert, or a number in [-1, 1])");
    }
    const double g = *value;
    return {[g](double) { return g; }, [g](double) { return g; }, "g = " + format_number(g)};
}

std::vector<PhaseComparison> compare_phase_in_skin(const LayerStack& stack, const SpectralRequest& request, const ThinLayerHg& hg) {
    std::vector<PhaseComparison> out{compare_thin_layer_phase(stack, request, hg, ComparedQuantity::reflectance)};
    auto sub = stack.sub_stack({"stratum_corneum", "epidermis"});
    sub.bottom = BottomBoundary::exit;
    out.push_back(compare_thin_layer_phase(sub, request, hg, ComparedQuantity::transmittance));
    return out;
}

}  // namespace skinspec
