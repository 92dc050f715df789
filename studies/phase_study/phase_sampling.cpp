#include "studies/phase_study/phase_sampling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "transport/henyey_greenstein.hpp"

namespace skinspec {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

}  // namespace

AngleSampler hg_angle_sampler(double g) {
    return [g](RandomStream& random) { return std::acos(hg_sample_cos(g, random.uniform())) / deg; };
}

AngleSampler table_angle_sampler(InverseCdfTable table) {
    return [table = std::move(table)](RandomStream& random) { return table.theta_deg(table.index(random.uniform())); };
}

BinnedSamples bin_samples(const AngleSampler& sampler, std::span<const double> edges, std::uint64_t n, std::uint64_t seed,
                          double stream_key) {
    BinnedSamples out;
    std::vector<std::uint64_t> counts(edges.size() - 1, 0);
    auto random = RandomStream::for_batch(seed, stream_key, 0);
    for (std::uint64_t i = 0; i < n; ++i) {
        const double theta = sampler(random);
        ++out.drawn;
        if (theta > edges.back()) continue;
        // Bins are (lo, hi], the first [0, hi].
        const auto it = std::lower_bound(edges.begin() + 1, edges.end(), theta);
        ++counts[static_cast<std::size_t>(it - (edges.begin() + 1))];
        ++out.kept;
    }
    for (const auto c : counts) out.fractions.push_back(out.kept ? static_cast<double>(c) / static_cast<double>(out.kept) : 0.0);
    return out;
}

RelativeErrors relative_errors(std::span<const double> simulated, std::span<const double> measured) {
    RelativeErrors e;
    for (std::size_t i = 0; i < measured.size(); ++i) {
        const double r = 100.0 * std::abs(simulated[i] - measured[i]) / measured[i];
        e.max_percent = std::max(e.max_percent, r);
        e.average_percent += r / static_cast<double>(measured.size());
    }
    return e;
}

std::vector<double> goniometer_btdf_per_sr(std::span<const double> fractions, std::span<const double> edges) {
    std::vector<double> f;
    for (std::size_t i = 0; i < fractions.size(); ++i) {
        const double solid_angle = 2.0 * std::numbers::pi * (std::cos(edges[i] * deg) - std::cos(edges[i + 1] * deg));
        f.push_back(fractions[i] / (solid_angle * std::cos(0.5 * (edges[i] + edges[i + 1]) * deg)));
    }
    return f;
}

std::vector<double> seconds_per_sample(const std::vector<AngleSampler>& samplers, std::uint64_t n) {
    std::vector<double> out;
    for (std::size_t s = 0; s < samplers.size(); ++s) {
        auto random = RandomStream::for_batch(1, 0.0, s);
        double sink = 0.0;
        const auto start = std::chrono::steady_clock::now();
        for (std::uint64_t i = 0; i < n; ++i) sink += samplers[s](random);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out.push_back(seconds / static_cast<double>(n) + (sink < 0.0 ? 1.0 : 0.0));  // sink keeps the loop alive
    }
    return out;
}

}  // namespace skinspec
