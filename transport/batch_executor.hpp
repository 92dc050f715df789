#pragma once
// Executors run one round of ray batches for the planner (transport/ray_planner.hpp). Each batch is traced
// into its own tally with its own random stream (seed, wavelength, batch index), so what a round yields
// does not depend on how, where or in which order an executor runs its batches. The CPU executor uses the
// oneTBB workers; another executor (e.g. vectorised packets, other processes) plugs in through this interface.
#include <cstdint>
#include <functional>
#include <vector>

#include "transport/random_stream.hpp"
#include "transport/ray_tally.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

struct BatchTask {
    std::size_t wavelength = 0;    // index into the request's grid
    double stream_key_nm = 0.0;    // the wavelength's value, which keys the random stream
    std::uint64_t batch = 0;       // batch index within the wavelength
    std::uint64_t rays = 0;
};

// Traces `rays` rays of batch `batch` at wavelength index `wavelength` into `tally`.
using BatchTracer = std::function<void(std::size_t wavelength, std::uint64_t batch, RandomStream& random, std::uint64_t rays, RayTally& tally)>;

struct RoundOutput {
    std::vector<RayTally> tallies;  // per task
    std::vector<char> done;         // 1 where the task ran to its end (0 only when cancelled)
};

class BatchExecutor {
public:
    virtual ~BatchExecutor() = default;
    // Runs the tasks (in order of claim, so an interrupted round has finished its front tasks); `on_batch` is
    // called after each finished task with its ray count, possibly from several threads at once.
    virtual RoundOutput run(const std::vector<BatchTask>& tasks, std::size_t channels, std::uint64_t seed, const BatchTracer& trace,
                            const std::function<void(std::uint64_t rays)>& on_batch, const CancelFlag* cancel) const = 0;
};

// All tasks of a round on the oneTBB worker threads.
const BatchExecutor& cpu_batch_executor();

}  // namespace skinspec
