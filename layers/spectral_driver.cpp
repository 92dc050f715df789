#include "layers/spectral_driver.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace skinspec {
namespace {

struct Task {
    std::size_t wavelength;
    std::uint64_t batch;
    std::uint64_t rays;
};

}  // namespace

DriverOutcome run_batches(const SpectralRequest& request, std::size_t channels,
                          const std::vector<std::size_t>& target_channels, const BatchTracer& trace) {
    const std::size_t n = request.wavelengths.size();
    const std::uint64_t budget = request.max_rays_per_wavelength;
    const std::uint64_t rays_per_batch = std::max<std::uint64_t>(1, request.rays_per_batch);
    const auto batches_for = [&](std::uint64_t rays) { return (rays + rays_per_batch - 1) / rays_per_batch; };
    const bool adaptive = request.stderr_target.has_value() || static_cast<bool>(request.stderr_targets);
    DriverOutcome out{std::vector<RayTally>(n, RayTally(channels)), std::vector<bool>(n, false),
                      std::vector<bool>(n, !adaptive), false};
    std::vector<std::uint64_t> next_batch(n, 0);
    // Rays planned for the next round, per wavelength: all of the budget without a target, else a first
    // estimate of 8 batches.
    std::vector<std::uint64_t> planned(
        n, adaptive ? std::min<std::uint64_t>(budget, std::max<std::uint64_t>(1, request.initial_batches) * rays_per_batch) : budget);
    std::atomic<std::uint64_t> rays_done{0};
    std::size_t wavelengths_done = 0;
    std::mutex progress_mutex;
    const auto report = [&] {
        if (!request.on_progress) return;
        std::lock_guard lock(progress_mutex);
        request.on_progress(Progress{rays_done.load(), wavelengths_done, n});
    };
    const auto cancelled = [&] { return request.cancel && request.cancel->load(); };

    while (true) {
        std::vector<Task> tasks;
        for (std::size_t w = 0; w < n; ++w) {
            if (out.finished[w]) continue;
            std::uint64_t remaining = planned[w];
            for (std::uint64_t b = 0; b < batches_for(planned[w]); ++b) {
                const std::uint64_t rays = std::min(rays_per_batch, remaining);
                tasks.push_back({w, next_batch[w] + b, rays});
                remaining -= rays;
            }
        }
        if (tasks.empty()) break;
        std::vector<RayTally> results(tasks.size(), RayTally(channels));
        std::vector<char> done(tasks.size(), 0);
        // Workers claim tasks in order, so wavelengths complete front to back (what an interrupted run keeps).
        std::atomic<std::size_t> next_task{0};
        const auto workers = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
        tbb::parallel_for(std::size_t{0}, workers, [&](std::size_t) {
            for (std::size_t i = next_task++; i < tasks.size() && !cancelled(); i = next_task++) {
                const auto& task = tasks[i];
                auto random = RandomStream::for_batch(request.seed, request.wavelengths[task.wavelength], task.batch);
                trace(task.wavelength, random, task.rays, results[i]);
                done[i] = 1;
                rays_done += task.rays;
                report();
            }
        }, tbb::static_partitioner());
        out.cancelled = cancelled();
        // A wavelength takes part in this round's decision only if all its batches of the round ran.
        std::vector<bool> complete(n, true);
        for (std::size_t i = 0; i < tasks.size(); ++i) complete[tasks[i].wavelength] = complete[tasks[i].wavelength] && done[i];
        for (std::size_t i = 0; i < tasks.size(); ++i) {
            if (complete[tasks[i].wavelength]) out.tallies[tasks[i].wavelength].merge(results[i]);
        }
        std::vector<double> targets(n, request.stderr_target.value_or(0.0));
        if (request.stderr_targets && !target_channels.empty()) {
            std::vector<Estimate> estimates(n);
            std::vector<std::uint64_t> rays(n);
            for (std::size_t w = 0; w < n; ++w) {
                estimates[w] = out.tallies[w].estimate(target_channels.front());
                rays[w] = out.tallies[w].rays();
            }
            targets = request.stderr_targets(estimates, rays);
        }
        for (std::size_t w = 0; w < n; ++w) {
            if (out.finished[w] || !complete[w]) continue;
            next_batch[w] += batches_for(planned[w]);
            const auto& tally = out.tallies[w];
            const std::uint64_t used = tally.rays();
            bool met = true;
            double worst_ratio = 0.0;
            if (adaptive) {
                for (const auto c : target_channels) {
                    const double se = tally.estimate(c).stderr;
                    const double ratio = se == 0.0 ? 0.0 : se / targets[w];  // target inf: done; 0: needs se = 0
                    worst_ratio = std::max(worst_ratio, ratio);
                }
                met = worst_ratio <= 1.0;
            }
            if (met || used >= budget) {
                out.finished[w] = true;
                out.converged[w] = met;
                ++wavelengths_done;
                continue;
            }
            // stderr ~ 1/sqrt(N): rays needed for the target, with 10 % margin, at most 8x more per round.
            const double needed = static_cast<double>(used) * worst_ratio * worst_ratio * 1.1;
            const auto more = static_cast<std::uint64_t>(std::ceil(std::min(needed, 8.0 * static_cast<double>(used)))) - used;
            planned[w] = std::clamp<std::uint64_t>(more, rays_per_batch, budget - used);
        }
        report();
        if (out.cancelled) break;
    }
    return out;
}

}  // namespace skinspec
