// Compiled with -ffast-math (CMakeLists.txt) so that the exponential of the re-weighting loop vectorises
// (glibc's libmvec); nothing here depends on IEEE corner cases: every input is finite and non-negative.
#include "transport/biospec/exit_paths.hpp"

#include <algorithm>
#include <cmath>

#include "transport/random_stream.hpp"

namespace skinspec {
namespace {

constexpr float max_optical_depth = 80.0f;

}  // namespace

void ExitPaths::append(const ExitPaths& other) {
    rays += other.rays;
    surface_exits += other.surface_exits;
    if (layer_path_cm.size() < other.layer_path_cm.size()) layer_path_cm.resize(other.layer_path_cm.size());
    for (std::size_t k = 0; k < other.layer_path_cm.size(); ++k) {
        layer_path_cm[k].insert(layer_path_cm[k].end(), other.layer_path_cm[k].begin(), other.layer_path_cm[k].end());
    }
}

void ExitPaths::thin(const std::vector<double>& floor_per_cm, std::uint64_t seed) {
    const std::size_t n = exits(), layers = layer_path_cm.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double tau = 0.0;
        for (std::size_t k = 0; k < layers; ++k) tau += floor_per_cm[k] * static_cast<double>(layer_path_cm[k][i]);
        if (RandomStream::keyed_uniform(seed, i) >= std::exp(-tau)) continue;
        for (std::size_t k = 0; k < layers; ++k) layer_path_cm[k][kept] = layer_path_cm[k][i];
        ++kept;
    }
    for (auto& l : layer_path_cm) {
        l.resize(kept);
        l.shrink_to_fit();
    }
    thinned_at_per_cm = floor_per_cm;
}

// Three versions chosen at load time by the CPU (GCC function multiversioning): AVX-512 (16-wide expf), AVX2 (8-wide)
// or the baseline.
__attribute__((target_clones("avx512f", "avx2", "default")))
Estimate ExitPaths::reflectance(const std::vector<double>& mu_a, const std::vector<double>& scale, std::vector<double>* gradient) const {
    const std::size_t layers = layer_path_cm.size();
    const bool with_gradient = gradient != nullptr;
    if (with_gradient) gradient->assign(layers, 0.0);  // any layer count: the sums accumulate in place
    if (rays == 0) return {};
    constexpr std::size_t chunk = 256;
    float tau[chunk], w[chunk];
    double sum = static_cast<double>(surface_exits), sum_sq = sum;
    const std::size_t n = exits();
    for (std::size_t start = 0; start < n; start += chunk) {
        const std::size_t m = std::min(chunk, n - start);
        std::fill(tau, tau + m, 0.0f);
        for (std::size_t k = 0; k < layers; ++k) {
            const float mu = static_cast<float>(mu_a[k] * scale[k] - (thinned_at_per_cm.empty() ? 0.0 : thinned_at_per_cm[k]));
            const float* p = layer_path_cm[k].data() + start;
            for (std::size_t i = 0; i < m; ++i) tau[i] += mu * p[i];
        }
        float s = 0.0f, s2 = 0.0f;
        for (std::size_t i = 0; i < m; ++i) {
            // Optical depths beyond 80 weigh below 2e-35 (nothing at float precision); glibc's vector expf sends every
            // lane past its range (~87) through a scalar fallback: 12 % of a fit's time went there.
            w[i] = std::exp(-std::min(tau[i], max_optical_depth));
            s += w[i];
            s2 += w[i] * w[i];
        }
        sum += s;
        sum_sq += s2;
        if (with_gradient) {
            for (std::size_t k = 0; k < layers; ++k) {
                const float* p = layer_path_cm[k].data() + start;
                float g = 0.0f;
                for (std::size_t i = 0; i < m; ++i) g += p[i] * w[i];
                (*gradient)[k] += g;
            }
        }
    }
    const double count = static_cast<double>(rays);
    const double mean = sum / count;
    const double variance = rays > 1 ? std::max(0.0, sum_sq / count - mean * mean) / (count - 1.0) : 0.0;
    if (with_gradient) {
        for (auto& g : *gradient) g = -g / count * factor;
    }
    return {mean * factor, std::sqrt(variance) * factor};
}

}  // namespace skinspec
