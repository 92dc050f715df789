#pragma once
// The BioSpec Monte Carlo solver: a layer stack and a request in, spectra with standard errors out.
#include "transport/biospec/biospec_options.hpp"
#include "transport/spectral_request.hpp"
#include "materials/layer_stack.hpp"

namespace skinspec {

// InputError for a request or stack the walk cannot run (naming the field, value and allowed range).
SpectralResult solve_biospec(const LayerStack& stack, const SpectralRequest& request, const BiospecOptions& options = {});

}  // namespace skinspec
