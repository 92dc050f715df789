#include "transport/ray_planner.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include <tbb/task_arena.h>

namespace skinspec {

RayPlanner::RayPlanner(const SpectralRequest& request, std::size_t channels, std::vector<std::size_t> target_channels, std::size_t sets)
    : request_(request),
      target_channels_(std::move(target_channels)),
      rays_per_batch_(std::max<std::uint64_t>(1, request.rays_per_batch)),
      adaptive_(request.stderr_target.has_value() || static_cast<bool>(request.stderr_targets)),
      sets_(std::max<std::size_t>(1, sets)),
      stride_(channels / std::max<std::size_t>(1, sets)) {
    const std::size_t n = request.wavelengths.size();
    const std::uint64_t budget = request.max_rays_per_wavelength;
    state_ = DriverOutcome{std::vector<RayTally>(n, RayTally(channels)), std::vector<bool>(n, false), std::vector<bool>(n, !adaptive_), false};
    next_batch_.assign(n, 0);
    broken_.assign(n, false);
    // All of the budget without a target, else a first estimate from a few batches.
    planned_.assign(n, adaptive_ ? std::min<std::uint64_t>(budget, std::max<std::uint64_t>(1, request.initial_batches) * rays_per_batch_)
                                 : budget);
    expected_ = planned_;
    estimated_ = !adaptive_;
    update_totals();
}

std::vector<BatchTask> RayPlanner::next_round() const {
    std::vector<BatchTask> tasks;
    for (std::size_t w = 0; w < planned_.size(); ++w) {
        if (state_.finished[w]) continue;
        std::uint64_t remaining = planned_[w];
        // A fixed budget runs in rounds of at most max_round_batches (--rays 2^50 asked for 2.7e11 tasks at once:
        // std::bad_alloc); an adaptive round is bounded by its plan (at most 8x the rays so far).
        const std::uint64_t batches = adaptive_ ? batches_for(planned_[w]) : std::min(batches_for(planned_[w]), max_round_batches);
        for (std::uint64_t b = 0; b < batches; ++b) {
            const std::uint64_t rays = std::min(rays_per_batch_, remaining);
            tasks.push_back({w, request_.wavelengths[w], next_batch_[w] + b, rays});
            remaining -= rays;
        }
    }
    return tasks;
}

void RayPlanner::absorb_part(const std::vector<BatchTask>& part, const RoundOutput& output) {
    // In task order, so the sums are the same however a round is cut into parts (bit-identical results).
    for (std::size_t i = 0; i < part.size(); ++i) {
        const auto w = part[i].wavelength;
        if (!output.done[i]) broken_[w] = true;
        if (!broken_[w]) state_.tallies[w].merge(output.tallies[i]);
    }
}

void RayPlanner::end_round(const std::vector<BatchTask>& tasks) {
    const std::size_t n = planned_.size();
    const std::uint64_t budget = request_.max_rays_per_wavelength;
    // A wavelength takes part in this round's decision only if all its batches of the round ran.
    std::vector<bool> complete(n, true);
    std::vector<bool> in_round(n, false);
    for (const auto& t : tasks) {
        complete[t.wavelength] = !broken_[t.wavelength];
        in_round[t.wavelength] = true;
    }
    broken_.assign(n, false);
    // Targets per set and wavelength: the fixed target, or the colour-driven ones from that set's estimates.
    std::vector<std::vector<double>> targets(sets_, std::vector<double>(n, request_.stderr_target.value_or(0.0)));
    if (request_.stderr_targets && !target_channels_.empty()) {
        for (std::size_t s = 0; s < sets_; ++s) {
            std::vector<Estimate> estimates(n);
            std::vector<std::uint64_t> rays(n);
            for (std::size_t w = 0; w < n; ++w) {
                estimates[w] = state_.tallies[w].estimate(s * stride_ + target_channels_.front());
                rays[w] = state_.tallies[w].rays();
            }
            targets[s] = request_.stderr_targets(estimates, rays);
        }
    }
    std::vector<std::uint64_t> ran(n, 0);
    for (const auto& t : tasks) ++ran[t.wavelength];
    for (std::size_t w = 0; w < n; ++w) {
        if (state_.finished[w] || !complete[w] || !in_round[w]) continue;
        next_batch_[w] += ran[w];
        const auto& tally = state_.tallies[w];
        const std::uint64_t used = tally.rays();
        if (!adaptive_ && used < budget) {  // the rest of a fixed budget in the next round
            planned_[w] = budget - used;
            continue;
        }
        bool met = true;
        double worst_ratio = 0.0;
        if (adaptive_) {
            for (std::size_t s = 0; s < sets_; ++s) {
                for (const auto c : target_channels_) {
                    const double se = tally.estimate(s * stride_ + c).stderr;
                    const double ratio = se == 0.0 ? 0.0 : se / targets[s][w];  // target inf: done; 0: needs se = 0
                    worst_ratio = std::max(worst_ratio, ratio);
                }
            }
            met = worst_ratio <= 1.0;
        }
        if (met || used >= budget) {
            state_.finished[w] = true;
            state_.converged[w] = met;
            expected_[w] = used;
            continue;
        }
        // stderr ~ 1/sqrt(N): rays needed for the target, with 10 % margin, at most 8x more per round.
        const double needed = static_cast<double>(used) * worst_ratio * worst_ratio * 1.1;
        const auto more = static_cast<std::uint64_t>(std::ceil(std::min(needed, 8.0 * static_cast<double>(used)))) - used;
        planned_[w] = std::clamp<std::uint64_t>(more, rays_per_batch_, budget - used);
        expected_[w] = static_cast<std::uint64_t>(std::min(std::ceil(needed), static_cast<double>(budget)));
    }
    estimated_ = true;
    update_totals();
}

std::uint64_t RayPlanner::rays_expected() const { return estimated_ ? rays_expected_ : 0; }

std::size_t RayPlanner::wavelengths_finished() const { return wavelengths_finished_; }

void RayPlanner::update_totals() {
    rays_expected_ = 0;
    for (std::size_t w = 0; w < expected_.size(); ++w) rays_expected_ += std::max(expected_[w], state_.tallies[w].rays());
    wavelengths_finished_ = static_cast<std::size_t>(std::count(state_.finished.begin(), state_.finished.end(), true));
}

DriverOutcome RayPlanner::outcome(bool cancelled) const {
    auto out = state_;
    out.cancelled = cancelled;
    return out;
}

DriverOutcome run_batches(const SpectralRequest& request, std::size_t channels, const std::vector<std::size_t>& target_channels,
                          const BatchTracer& trace, std::size_t sets, const BatchExecutor& executor) {
    RayPlanner planner(request, channels, target_channels, sets);
    const std::size_t n = request.wavelengths.size();
    std::atomic<std::uint64_t> rays_done{0};
    std::mutex progress_mutex;
    const auto report = [&] {
        if (!request.on_progress) return;
        std::lock_guard lock(progress_mutex);
        const auto finished = planner.wavelengths_finished();
        request.on_progress(Progress{rays_done.load(), planner.rays_expected(), finished, n, n - finished});
    };
    const auto cancelled = [&] { return request.cancel && request.cancel->load(); };
    // A round runs in parts of at most this many batches: memory for their tallies stays bounded (a billion photons
    // in one round allocated 244k grid tallies up front and took 95 s to notice SIGTERM), and a stopped run keeps
    // the batches it finished.
    const std::size_t part_size = 64 * static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
    while (true) {
        const auto tasks = planner.next_round();
        if (tasks.empty()) break;
        for (std::size_t from = 0; from < tasks.size(); from += part_size) {
            const std::vector<BatchTask> part(tasks.begin() + static_cast<std::ptrdiff_t>(from),
                                              tasks.begin() + static_cast<std::ptrdiff_t>(std::min(tasks.size(), from + part_size)));
            const auto output = executor.run(part, channels, request.seed, trace, [&](std::uint64_t rays) {
                rays_done += rays;
                report();
            }, request.cancel);
            planner.absorb_part(part, output);
            if (cancelled()) return planner.outcome(true);
        }
        planner.end_round(tasks);
        report();
    }
    return planner.outcome(false);
}

}  // namespace skinspec
