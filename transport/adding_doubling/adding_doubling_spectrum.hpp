#pragma once
// A material's spectrum by adding-doubling (transport/adding_doubling/adding_doubling.hpp), in the shared result
// type (model "adding-doubling"): R = specular + diffuse (or diffuse alone for geometry sce), R_specular, T,
// A per layer, deterministic; settings carry the quadrature, the stated error the largest accuracy estimate of the
// spectrum (with AdOptions::accuracy_check).
#include <functional>
#include <string>

#include "materials/layer_stack.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

SpectralResult solve_adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const AdOptions& options = {});

// One wavelength's solution for the loop below: the totals and what the surface lost (A_surface; 0 for most models).
struct AdWavelength {
    AdResult totals;
    double surface_absorbed = 0.0;
};
// The spectrum loop every adding-doubling model shares: `solve` per wavelength (with the accuracy check at the first,
// middle and last), the rows in the request's geometry (sci, sce), progress, a stop (partial), the stated error and
// the quadrature settings.
SpectralResult adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const AdOptions& options, std::string model,
                                        const std::function<AdWavelength(double wavelength_nm, const AdOptions& options)>& solve);

}  // namespace skinspec
