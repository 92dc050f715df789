#pragma once
// The parallel driver shared by the Monte Carlo solvers: rays are traced in fixed-size batches, each batch
// with its own random stream (seed, wavelength, batch index), all batches of a round in parallel with
// oneTBB, merged in batch order. A wavelength stops once the standard error of its target channels is
// below the request's target, or when its budget is spent. Because what is traced depends only on the
// results of earlier rounds, a seed gives identical numbers for any thread count.
#include <cstdint>
#include <functional>
#include <vector>

#include "layers/random_stream.hpp"
#include "layers/ray_tally.hpp"
#include "layers/spectral_request.hpp"

namespace skinspec {

// Traces `rays` rays at wavelength index `wavelength` into `tally`.
using BatchTracer = std::function<void(std::size_t wavelength, RandomStream& random, std::uint64_t rays, RayTally& tally)>;

struct DriverOutcome {
    std::vector<RayTally> tallies;   // per wavelength
    std::vector<bool> finished;      // target met or budget spent (false only when cancelled)
    std::vector<bool> converged;     // target met (true when there is no target)
    bool cancelled = false;
};

DriverOutcome run_batches(const SpectralRequest& request, std::size_t channels,
                          const std::vector<std::size_t>& target_channels, const BatchTracer& trace);

}  // namespace skinspec
