#pragma once
// R + T + A_surface + the layers' A of one wavelength's result: 1 when energy is conserved.
#include "transport/spectral_request.hpp"

namespace skinspec::testing {

inline double energy(const WavelengthResult& w) {
    double sum = w.reflectance.value + w.transmittance.value + w.absorptance_surface.value;
    for (const auto& a : w.absorptance_layers) sum += a.value;
    return sum;
}

}  // namespace skinspec::testing
