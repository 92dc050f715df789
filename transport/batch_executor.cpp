#include "transport/batch_executor.hpp"

#include <atomic>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace skinspec {
namespace {

class CpuBatchExecutor final : public BatchExecutor {
public:
    RoundOutput run(const std::vector<BatchTask>& tasks, std::size_t channels, std::uint64_t seed, const BatchTracer& trace,
                    const std::function<void(std::uint64_t)>& on_batch, const CancelFlag* cancel) const override {
        RoundOutput out{std::vector<RayTally>(tasks.size(), RayTally(channels)), std::vector<char>(tasks.size(), 0)};
        const auto cancelled = [&] { return cancel && cancel->load(); };
        // Workers claim tasks in order, so wavelengths complete front to back (what an interrupted run keeps).
        std::atomic<std::size_t> next_task{0};
        const auto workers = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
        tbb::parallel_for(std::size_t{0}, workers, [&](std::size_t) {
            for (std::size_t i = next_task++; i < tasks.size() && !cancelled(); i = next_task++) {
                const auto& task = tasks[i];
                auto random = RandomStream::for_batch(seed, task.stream_key_nm, task.batch);
                trace(task.wavelength, task.batch, random, task.rays, out.tallies[i]);
                out.done[i] = 1;
                if (on_batch) on_batch(task.rays);
            }
        }, tbb::static_partitioner());
        return out;
    }
};

}  // namespace

const BatchExecutor& cpu_batch_executor() {
    static const CpuBatchExecutor executor;
    return executor;
}

}  // namespace skinspec
