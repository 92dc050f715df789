#include "transport/result_quantities.hpp"

#include <limits>

#include <fmt/format.h>

namespace skinspec {

const std::vector<ResultQuantity>& result_quantities() {
    using W = WavelengthResult;
    static const std::vector<ResultQuantity> table{
        {"R", "R", "1", "reflectance in the request's geometry (sci: specular included)", QuantityShape::scalar,
         [](const Quantities& q) { return q.reflectance; }, &W::reflectance},
        {"R_specular", "R_specular", "1", "first-surface reflection", QuantityShape::scalar, [](const Quantities& q) { return q.reflectance; },
         &W::specular_reflectance},
        {"T", "T", "1", "transmittance", QuantityShape::scalar, [](const Quantities& q) { return q.transmittance; }, &W::transmittance},
        {"A_layers", "A", "1", "absorptance per layer", QuantityShape::per_layer, [](const Quantities& q) { return q.absorptance; },
         &W::absorptance_layers},
        {"A_surface", "A_surface", "1", "absorbed at the surface (rays the fold behaviour drops)", QuantityShape::scalar,
         [](const Quantities& q) { return q.absorptance; }, &W::absorptance_surface},
        {"BRDF_per_sr", "brdf_per_sr", "1/sr", "reflected radiance per polar bin", QuantityShape::per_bin,
         [](const Quantities& q) { return q.angular; }, &W::brdf_per_sr},
        {"BTDF_per_sr", "btdf_per_sr", "1/sr", "transmitted radiance per polar bin", QuantityShape::per_bin,
         [](const Quantities& q) { return q.angular; }, &W::btdf_per_sr},
    };
    return table;
}

std::span<const Estimate> ResultQuantity::values(const WavelengthResult& w) const {
    if (const auto* one = std::get_if<Estimate WavelengthResult::*>(&member)) return {&(w.*(*one)), 1};
    const auto& many = w.*std::get<std::vector<Estimate> WavelengthResult::*>(member);
    return {many.data(), many.size()};
}

double ResultQuantity::upper_bound() const { return unit == "1" ? 1.0 : std::numeric_limits<double>::infinity(); }

std::size_t ResultQuantity::count(const SpectralResult& result) const {
    switch (shape) {
        case QuantityShape::scalar: return 1;
        case QuantityShape::per_layer: return result.layer_names.size();
        case QuantityShape::per_bin: return result.angular_bin_edges_deg.empty() ? 0 : result.angular_bin_edges_deg.size() - 1;
    }
    return 0;
}

std::string ResultQuantity::column(const SpectralResult& result, std::size_t i) const {
    switch (shape) {
        case QuantityShape::scalar: return std::string(key);
        case QuantityShape::per_layer: return std::string(key.substr(0, key.find('_') + 1)) + result.layer_names[i];
        case QuantityShape::per_bin: {
            const auto& e = result.angular_bin_edges_deg;
            const auto split = key.find('_');
            return fmt::format("{}_{:g}-{:g}deg{}", key.substr(0, split), e[i], e[i + 1], key.substr(split));
        }
    }
    return {};
}

std::vector<const ResultQuantity*> quantities_of(const SpectralResult& result) {
    std::vector<const ResultQuantity*> out;
    for (const auto& q : result_quantities()) {
        if (q.requested(result.quantities)) out.push_back(&q);
    }
    return out;
}

}  // namespace skinspec
