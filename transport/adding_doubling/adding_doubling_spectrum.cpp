#include "transport/adding_doubling/adding_doubling_spectrum.hpp"

#include <algorithm>

#include "spectral/input_error.hpp"

namespace skinspec {

SpectralResult adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const AdOptions& options, std::string model,
                                        const std::function<AdWavelength(double wavelength_nm, const AdOptions& options)>& solve) {
    if (request.geometry == MeasurementGeometry::zero_45) throw InputError(model + " computes hemispherical totals, not geometry 0-45");
    SpectralResult out;
    out.model = std::move(model);
    out.material = stack.name;
    out.has_uncertainty = false;
    for (const auto& l : stack.layers) out.layer_names.push_back(l.name);
    double accuracy = 0.0;
    const std::size_t total = request.wavelengths.size();
    auto ad = options;
    ad.cancel = request.cancel;
    out.quantities = Quantities{true, request.quantities.transmittance, request.quantities.absorptance, false};
    for (std::size_t w = 0; w < total; ++w) {
        if (request.cancel && request.cancel->load()) {
            out.partial = true;
            break;
        }
        const double nm = request.wavelengths[w];
        // The quadrature-doubling check at the first, middle and last wavelength (8x the work of one).
        ad.accuracy_check = options.accuracy_check && (w == 0 || w == total / 2 || w + 1 == total);
        const auto solved = solve(nm, ad);
        const auto& r = solved.totals;
        if (r.cancelled) {
            out.partial = true;
            break;
        }
        WavelengthResult row;
        row.wavelength_nm = nm;
        const bool excluded = request.geometry == MeasurementGeometry::sce;
        row.reflectance = {r.diffuse_reflectance + (excluded ? 0.0 : r.specular_reflectance), 0.0};
        row.specular_reflectance = {r.specular_reflectance, 0.0};
        row.transmittance = {r.transmittance, 0.0};
        row.absorptance_surface = {solved.surface_absorbed, 0.0};
        if (request.quantities.absorptance) {
            for (const double a : r.absorbed_layers) row.absorptance_layers.push_back({a, 0.0});
        }
        out.wavelengths.push_back(std::move(row));
        accuracy = std::max(accuracy, r.accuracy);
        if (request.on_progress) request.on_progress(Progress{0, 0, w + 1, total});
    }
    out.settings = {{"incidence_deg", request.incidence_deg},
                    {"geometry", std::string(to_string(request.geometry))},
                    {"bottom", std::string(to_string(stack.bottom))},
                    {"quadrature_channels", std::uint64_t{options.channels}}};
    if (options.accuracy_check) {
        static const auto meaning = std::make_shared<const std::string>(
            "twice the largest change of R_diffuse, T or A with every segment's channels doubled, at the first, middle and last wavelength");
        out.stated_error = StatedError{accuracy, meaning, {}};
    }
    return out;
}

SpectralResult solve_adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const AdOptions& options) {
    AdCache phases;
    return adding_doubling_spectrum(stack, request, options, "adding-doubling", [&](double nm, const AdOptions& ad) {
        return AdWavelength{solve_adding_doubling(rte_stack_from(stack, nm), AdIncidence{false, request.incidence_deg}, ad, &phases), 0.0};
    });
}

}  // namespace skinspec
