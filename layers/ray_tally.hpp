#pragma once
// Per-channel sums of per-ray contributions and of their squares: the mean over rays and its standard
// error sqrt((E[x^2] - E[x]^2) / (N - 1)) for every tallied quantity.
#include <cmath>
#include <cstdint>
#include <vector>

#include "layers/spectral_request.hpp"

namespace skinspec {

class RayTally {
public:
    explicit RayTally(std::size_t channels = 0) : sum_(channels, 0.0), sum_sq_(channels, 0.0) {}

    // One finished ray's contributions to every channel.
    void add_ray(const std::vector<double>& contributions) {
        for (std::size_t c = 0; c < sum_.size(); ++c) {
            sum_[c] += contributions[c];
            sum_sq_[c] += contributions[c] * contributions[c];
        }
        ++rays_;
    }

    void merge(const RayTally& other) {
        for (std::size_t c = 0; c < sum_.size(); ++c) {
            sum_[c] += other.sum_[c];
            sum_sq_[c] += other.sum_sq_[c];
        }
        rays_ += other.rays_;
        truncated_ += other.truncated_;
    }

    // Rays stopped at the event limit (reported, not a channel).
    void add_truncated(std::uint64_t rays) { truncated_ += rays; }
    std::uint64_t truncated() const { return truncated_; }

    Estimate estimate(std::size_t channel) const {
        if (rays_ == 0) return {};
        const double n = static_cast<double>(rays_);
        const double mean = sum_[channel] / n;
        const double variance = rays_ > 1 ? std::max(0.0, sum_sq_[channel] / n - mean * mean) / (n - 1.0) : 0.0;
        return {mean, std::sqrt(variance)};
    }

    std::uint64_t rays() const { return rays_; }
    std::size_t channels() const { return sum_.size(); }

private:
    std::vector<double> sum_;
    std::vector<double> sum_sq_;
    std::uint64_t rays_ = 0;
    std::uint64_t truncated_ = 0;
};

}  // namespace skinspec
