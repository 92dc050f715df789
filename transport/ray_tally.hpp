#pragma once
// Per-channel sums of per-ray contributions and of their squares: the mean over rays and its standard
// error sqrt((E[x^2] - E[x]^2) / (N - 1)) for every tallied quantity. Channels a ray reaches very often at
// many places (MCML's grids of absorption and exits) are tallied by batch means instead: per batch of rays
// only their sum, and the standard error from the spread of the batches' means.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "transport/spectral_request.hpp"

namespace skinspec {

// Whole cache lines (64 bytes, aligned) for the sums a batch's thread writes ray after ray: the tallies of batches
// traced at once are allocated together, and arrays sharing a line made each thread's adds wait for the other's
// (false sharing: tally_exit was 12 % of a BioSpec walk instead of 3 % with an allocator that packs them tightly).
template <class T>
struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::size_t line = 64;
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}
    static std::size_t bytes(std::size_t n) { return (n * sizeof(T) + line - 1) / line * line; }
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(bytes(n), std::align_val_t{line})); }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t{line}); }
    template <class U>
    bool operator==(const CacheLineAllocator<U>&) const noexcept { return true; }
};

// One ray's contributions, per channel; only the channels it touched are visited when it is tallied, so
// large grids (A(r, z), R(r, alpha)) cost per ray what the ray did, not the grid size.
class RayScore {
public:
    explicit RayScore(std::size_t channels) : value_(channels, 0.0), marked_(channels, 0) {}
    void add(std::size_t channel, double v) {
        if (!marked_[channel]) {
            marked_[channel] = 1;
            touched_.push_back(channel);
        }
        value_[channel] += v;
    }

private:
    friend class RayTally;
    std::vector<double> value_;
    std::vector<unsigned char> marked_;
    std::vector<std::size_t> touched_;
};

class alignas(CacheLineAllocator<double>::line) RayTally {
public:
    explicit RayTally(std::size_t channels = 0) : sum_(channels, 0.0), sum_sq_(channels, 0.0), batched_(channels, 0) {}

    // One finished ray: its contributions are added (and squared) and the score is cleared for the next ray.
    void add_ray(RayScore& score) {
        for (const auto c : score.touched_) {
            const double v = score.value_[c];
            sum_[c] += v;
            sum_sq_[c] += v * v;
            score.value_[c] = 0.0;
            score.marked_[c] = 0;
        }
        score.touched_.clear();
        ++rays_;
    }

    // Adds one batch's tally (its rays, sums and squares; for batch-mean channels S^2 / n of its sum S over its n
    // rays).
    void merge(const RayTally& batch) {
        const double n = static_cast<double>(std::max<std::uint64_t>(1, batch.rays_));
        for (std::size_t c = 0; c < sum_.size(); ++c) {
            sum_[c] += batch.sum_[c];
            if (batch.batched_[c]) {
                sum_sq_[c] += batch.sum_[c] * batch.sum_[c] / n;
                batched_[c] = 1;
            } else {
                sum_sq_[c] += batch.sum_sq_[c];
            }
        }
        rays_ += batch.rays_;
        truncated_ += batch.truncated_;
        ++batches_;
    }

    // Channels [first, first + count) are tallied by batch means: add_to_batch adds to their sum, no per-ray square.
    void use_batch_means(std::size_t first, std::size_t count) { std::fill_n(batched_.begin() + static_cast<std::ptrdiff_t>(first), count, 1); }
    void add_to_batch(std::size_t channel, double v) { sum_[channel] += v; }

    // A contribution to a channel that a ray reaches at most once (an exit: R, T, an angular bin), added straight
    // into the sums: the same as going through the ray's RayScore, without its bookkeeping. The ray itself is
    // still counted by add_ray.
    void add_single(std::size_t channel, double v) {
        sum_[channel] += v;
        sum_sq_[channel] += v * v;
    }

    // Many rays' contributions to a channel each reaches at most once, as their sum and sum of squares (e.g. recorded
    // exits re-weighted for an absorption: ExitPaths::weight_sums); the rays are counted by add_rays.
    void add_exits(std::size_t channel, double sum, double sum_of_squares) {
        sum_[channel] += sum;
        sum_sq_[channel] += sum_of_squares;
    }
    // Rays tallied through add_exits alone (no RayScore).
    void add_rays(std::uint64_t rays) { rays_ += rays; }
    // Rays stopped at the event limit (reported, not a channel).
    void add_truncated(std::uint64_t rays) { truncated_ += rays; }
    std::uint64_t truncated() const { return truncated_; }

    Estimate estimate(std::size_t channel) const {
        if (rays_ == 0) return {};
        const double n = static_cast<double>(rays_);
        const double mean = sum_[channel] / n;
        if (batched_[channel]) {
            // Batch means (e.g. Law & Kelton, Simulation Modeling and Analysis, Sec. 9.5.3), weighted by batch size:
            // per-ray variance (sum_b S_b^2 / n_b - N mean^2) / (B - 1), its mean's variance that over N; 0 below two
            // batches.
            const double b = static_cast<double>(batches_);
            const double variance = batches_ > 1 ? std::max(0.0, sum_sq_[channel] - n * mean * mean) / (b - 1.0) / n : 0.0;
            return {mean, std::sqrt(variance)};
        }
        const double variance = rays_ > 1 ? std::max(0.0, sum_sq_[channel] / n - mean * mean) / (n - 1.0) : 0.0;
        return {mean, std::sqrt(variance)};
    }

    std::uint64_t rays() const { return rays_; }
    double sum(std::size_t channel) const { return sum_[channel]; }
    std::size_t channels() const { return sum_.size(); }

private:
    std::vector<double, CacheLineAllocator<double>> sum_;
    std::vector<double, CacheLineAllocator<double>> sum_sq_;
    std::vector<unsigned char> batched_;  // 1: a batch-mean channel (sum_sq_ holds sum over batches of S_b^2 / n_b)
    std::uint64_t rays_ = 0;
    std::uint64_t truncated_ = 0;
    std::uint64_t batches_ = 0;
};

}  // namespace skinspec
