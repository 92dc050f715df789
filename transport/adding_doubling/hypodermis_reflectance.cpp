#include "transport/adding_doubling/hypodermis_reflectance.hpp"

#include <algorithm>
#include <map>
#include <mutex>

#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"

namespace skinspec {

double semi_infinite_diffuse_reflectance(double mu_a_per_cm, double mu_s_per_cm, double g) {
    // Optical depth 1e6, the solver's largest (T below 1e-5 even without absorption; R converged).
    const double thickness_cm = 1e6 / std::max(mu_a_per_cm + mu_s_per_cm, 1e-6);
    RteStack stack{1.0, 1.0, false, {{1.0, mu_a_per_cm, mu_s_per_cm, thickness_cm, PhaseFunction::henyey_greenstein(g)}}};
    AdOptions options;
    options.channels = 32;
    options.accuracy_check = false;
    return solve_adding_doubling(stack, AdIncidence{true, 0.0}, options).diffuse_reflectance;
}

double hypodermis_reflectance(double wavelength_nm) {
    static const auto tables = [] {
        const auto absorption = DataTable::read(data_file("tissue/salomatina_hypodermis_absorption.csv"));
        const auto scattering = DataTable::read(data_file("tissue/salomatina_hypodermis.csv"));
        return std::pair{absorption.spectrum("mu_a_per_mm", "hypodermis absorption (Salomatina)"),
                         scattering.spectrum("mu_s_reduced_per_mm", "hypodermis reduced scattering (Salomatina)")};
    }();
    static std::mutex mutex;
    static std::map<double, double> computed;
    const auto& [mu_a, mu_s_reduced] = tables;
    if (!mu_a.in_domain(wavelength_nm)) {
        throw InputError("bottom.boundary = hypodermis: the measured hypodermis (Salomatina et al. 2006, ex vivo) covers " +
                         format_number(mu_a.domain_min_nm()) + "-" + format_number(mu_a.domain_max_nm()) + " nm; " + format_number(wavelength_nm) +
                         " nm is outside it (use diffuse_reflector or exit there)");
    }
    {
        const std::lock_guard lock(mutex);
        if (const auto it = computed.find(wavelength_nm); it != computed.end()) return it->second;
    }
    // mm^-1 in the table, cm^-1 here.
    const double reflectance = semi_infinite_diffuse_reflectance(10.0 * mu_a(wavelength_nm), 10.0 * mu_s_reduced(wavelength_nm) / (1.0 - hypodermis_g),
                                                                 hypodermis_g);
    const std::lock_guard lock(mutex);
    computed.emplace(wavelength_nm, reflectance);
    return reflectance;
}

double bottom_reflectance(const LayerStack& stack, double wavelength_nm) {
    switch (stack.bottom) {
        case BottomBoundary::diffuse_reflector: return 1.0;
        case BottomBoundary::hypodermis: return hypodermis_reflectance(wavelength_nm);
        case BottomBoundary::exit: return 0.0;
    }
    return 0.0;
}

}  // namespace skinspec
