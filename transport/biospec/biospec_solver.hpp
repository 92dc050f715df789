#pragma once
// The BioSpec Monte Carlo solver: a layer stack and a request in, spectra with standard errors out.
#include "transport/biospec/biospec_options.hpp"
#include "transport/spectral_request.hpp"
#include <optional>
#include <vector>

#include "materials/layer_stack.hpp"
#include "transport/biospec/biospec_walk.hpp"

namespace skinspec {

// InputError for a request or stack the walk cannot run (naming the field, value and allowed range).
SpectralResult solve_biospec(const LayerStack& stack, const SpectralRequest& request, const BiospecOptions& options = {});

// Absorption replay: stacks that differ only in absorbers, traced once (transport/biospec/biospec_walk.hpp);
// one result per stack, each equal to its own solve_biospec run with the same rays to rounding. With a
// standard-error target every stack meets it (the worst decides the rays of a wavelength).
std::vector<SpectralResult> solve_biospec_sets(const std::vector<const LayerStack*>& stacks, const SpectralRequest& request,
                                               const BiospecOptions& options = {});

// Path recording (transport/biospec/biospec_walk.hpp, ExitPaths): max_rays_per_wavelength rays per wavelength of
// the request in batches of rays_per_batch, each batch its own stream (seed, wavelength, batch), absorption ignored;
// the same seed gives the same paths for any thread count; nullopt when the request's cancel flag was raised.
std::optional<std::vector<ExitPaths>> record_biospec_paths(const LayerStack& stack, const SpectralRequest& request, const BiospecOptions& options = {});

}  // namespace skinspec
