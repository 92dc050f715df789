#pragma once
// The convergence planner shared by the Monte Carlo solvers: which batches of rays each wavelength gets in
// the next round. A wavelength stops once the standard error of its target channels is below the request's
// target, or when its budget is spent. Because a round's plan depends only on the results of earlier rounds,
// a seed gives identical numbers for any thread count and any executor.
#include <cstdint>
#include <vector>

#include "transport/batch_executor.hpp"

namespace skinspec {

struct DriverOutcome {
    std::vector<RayTally> tallies;   // per wavelength
    std::vector<bool> finished;      // target met or budget spent (false only when cancelled)
    std::vector<bool> converged;     // target met (true when there is no target)
    bool cancelled = false;
};

// Absorption replay (several sets in one tally): `sets` blocks of channels/sets channels each; the target
// channels name set 0's, and a wavelength is finished once every set meets its target (the worst set decides
// how many rays it gets; colour targets are computed per set).
class RayPlanner {
public:
    RayPlanner(const SpectralRequest& request, std::size_t channels, std::vector<std::size_t> target_channels, std::size_t sets = 1);

    // The next round's batches, wavelengths in grid order; empty when every wavelength is finished.
    std::vector<BatchTask> next_round() const;
    // Takes the results of a part of the round (its tasks, in order): each wavelength's batches are merged in batch
    // order up to the first that did not run (stopped), after which its round is broken.
    void absorb_part(const std::vector<BatchTask>& part, const RoundOutput& output);
    // After every part of the round: re-plans each wavelength of `tasks` whose batches all ran.
    void end_round(const std::vector<BatchTask>& tasks);
    // Rays the whole request is expected to need, from the estimates so far (the budget without a target; 0,
    // unknown, with a target until the first round has been measured: its few batches are no estimate of the
    // whole), and the wavelengths finished: both as of the last round (cheap to ask after every batch).
    std::uint64_t rays_expected() const;
    std::size_t wavelengths_finished() const;
    DriverOutcome outcome(bool cancelled) const;

private:
    std::uint64_t batches_for(std::uint64_t rays) const { return (rays + rays_per_batch_ - 1) / rays_per_batch_; }
    static constexpr std::uint64_t max_round_batches = std::uint64_t{1} << 16;
    void update_totals();

    const SpectralRequest& request_;
    std::vector<std::size_t> target_channels_;
    std::uint64_t rays_per_batch_;
    bool adaptive_;
    std::size_t sets_;
    std::size_t stride_;
    DriverOutcome state_;
    std::vector<std::uint64_t> next_batch_;
    std::vector<bool> broken_;             // this round: a batch of the wavelength did not run
    std::vector<std::uint64_t> planned_;   // rays of the next round, per wavelength
    std::vector<std::uint64_t> expected_;  // rays each wavelength is expected to need in all
    std::uint64_t rays_expected_ = 0;
    bool estimated_ = false;  // rays_expected_ is an estimate of the whole (no target, or a round measured)
    std::size_t wavelengths_finished_ = 0;
};

// Plans rounds and runs them on `executor` until every wavelength is finished or the request is cancelled.
DriverOutcome run_batches(const SpectralRequest& request, std::size_t channels, const std::vector<std::size_t>& target_channels,
                          const BatchTracer& trace, std::size_t sets = 1, const BatchExecutor& executor = cpu_batch_executor());

}  // namespace skinspec
