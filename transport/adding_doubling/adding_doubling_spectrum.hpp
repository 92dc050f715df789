#pragma once
// A material's spectrum by adding-doubling (transport/adding_doubling/adding_doubling.hpp), in the shared result
// type (model "adding-doubling"): R = specular + diffuse (or diffuse alone for geometry sce), R_specular, T,
// A per layer, deterministic; settings carry the quadrature, the stated error the largest accuracy estimate of the
// spectrum (with AdOptions::accuracy_check).
#include "materials/layer_stack.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

SpectralResult solve_adding_doubling_spectrum(const LayerStack& stack, const SpectralRequest& request, const AdOptions& options = {});

}  // namespace skinspec
