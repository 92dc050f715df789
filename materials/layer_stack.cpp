#include "materials/layer_stack.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"
#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"

namespace skinspec {
namespace {

// Measured reduced-scattering tables (data/tissue), loaded once.
const TabulatedSpectrum& reduced_scattering_table(const std::string& table) {
    static const std::map<std::string, TabulatedSpectrum, std::less<>> loaded = [] {
        std::map<std::string, TabulatedSpectrum, std::less<>> all;
        for (const auto name : reduced_scattering_tables()) {
            const std::string file = "tissue/" + std::string(name) + ".csv";
            all.emplace(name, DataTable::read(data_file(file)).spectrum("mu_s_reduced_per_mm", std::string(name)));
        }
        return all;
    }();
    const auto it = loaded.find(table);
    if (it == loaded.end()) throw InputError("reduced scattering table '" + table + "' is not known");
    return it->second;
}

double power_law(double at_500nm, double power, double wavelength_nm) {
    return at_500nm * std::pow(wavelength_nm / 500.0, -power);
}

}  // namespace

std::string_view to_string(BottomBoundary kind) {
    switch (kind) {
        case BottomBoundary::diffuse_reflector: return "diffuse_reflector";
        case BottomBoundary::hypodermis: return "hypodermis";
        case BottomBoundary::exit: return "exit";
    }
    return "exit";
}

BottomBoundary parse_bottom_boundary(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what, std::array{BottomBoundary::diffuse_reflector, BottomBoundary::hypodermis, BottomBoundary::exit},
                              "a bottom boundary");
}

CrossingScattering crossing_in_effect(const TissueLayer& layer, const ModelOptions& model) {
    return layer.crossing == CrossingScattering::rayleigh_cosine && !model.dermal_rayleigh ? CrossingScattering::cosine : layer.crossing;
}

LayerOptics LayerStack::optics(std::size_t index, double wavelength_nm, OpticsScope scope) const {
    const auto& layer = layers.at(index);
    LayerOptics o{layer.thickness_cm, layer.refractive_index, absorption_per_cm(layer, wavelength_nm, model),
                  crossing_in_effect(layer, model), layer.hg_g, 0.0, 0.0, std::nullopt, std::nullopt, std::nullopt, std::nullopt, nullptr};
    if (o.crossing == CrossingScattering::rayleigh_cosine) {
        o.rayleigh_per_cm = rayleigh_coefficient_per_cm(layer, wavelength_nm);
        o.mie_reduced_per_cm = mie_reduced_scattering_per_cm(layer, wavelength_nm);
    }
    const auto reduced = [&] {
        return layer.reduced->table.empty() ? power_law(layer.reduced->per_cm_at_500nm, layer.reduced->power, wavelength_nm)
                                            : per_cm_from_per_mm(reduced_scattering_table(layer.reduced->table)(wavelength_nm));
    };
    if (scope.volumetric && layer.volumetric) {
        const auto& v = *layer.volumetric;
        // mu_s = mu_s' / (1 - g) (the similarity relation, e.g. Jacques 2013, Phys. Med. Biol. 58:R37, Eq. 2).
        double g = v.g;
        if (is_measured(v.phase)) {
            const auto& profile = v.phase == PhaseFunctionKind::measured_stratum_corneum ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis();
            o.phase_table = profile.shared_inverse_table(wavelength_nm);
            g = o.phase_table->mean_cos();
        }
        o.mu_s_per_cm = v.source == VolumetricSource::power_law ? power_law(v.mu_s_per_cm_at_500nm, v.power, wavelength_nm)
                                                                : reduced() / (1.0 - g);
        o.phase = v.phase;
        o.g = g;
    }
    if (scope.reduced && layer.reduced) o.mu_s_reduced_per_cm = reduced();
    return o;
}

LayerStack LayerStack::sub_stack(const std::vector<std::string>& layer_names) const {
    std::string known;
    for (const auto& l : layers) known += (known.empty() ? "" : ", ") + l.name;
    for (const auto& name : layer_names) {
        if (std::none_of(layers.begin(), layers.end(), [&](const TissueLayer& l) { return l.name == name; })) {
            throw InputError("--layers: '" + name + "' is not a layer of '" + this->name + "' (allowed: " + known + ")");
        }
    }
    if (layer_names.empty()) throw InputError("--layers: no layer named (allowed: " + known + ")");
    LayerStack out = *this;
    out.layers.clear();
    for (const auto& l : layers) {
        if (std::find(layer_names.begin(), layer_names.end(), l.name) != layer_names.end()) out.layers.push_back(l);
    }
    return out;
}

std::vector<LayerOptics> LayerStack::optics(double wavelength_nm, OpticsScope scope) const {
    std::vector<LayerOptics> out;
    out.reserve(layers.size());
    for (std::size_t i = 0; i < layers.size(); ++i) out.push_back(optics(i, wavelength_nm, scope));
    return out;
}

}  // namespace skinspec
