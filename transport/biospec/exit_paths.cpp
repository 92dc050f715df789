// The re-weighting kernel is compiled once per instruction set by Highway's foreach_target and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "transport/biospec/exit_paths.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/aligned_allocator.h>
#include <hwy/highway.h>

#include "transport/simd_lanes-inl.h"

#include <algorithm>
#include <cmath>

#include "transport/biospec/exit_paths.hpp"
#include "transport/random_stream.hpp"

HWY_BEFORE_NAMESPACE();
namespace skinspec {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Optical depths beyond 80 weigh below 2e-35 (nothing at float precision).
constexpr float max_optical_depth = 80.0f;

// Partial sums in float over this many exits, then in double.
constexpr std::size_t chunk = 256;

// The weights' sum and sum of squares over the exits and, with `gradient` (one per entry of `gradient_paths`), the
// sums of path times weight, in one pass: each exit's optical depth sum_k mu_k L_k over the `layers` entries of
// `paths` and `mu` in a register, its weight exp(-depth), four vectors at a time (their exponentials' chains of
// multiply-adds interleave).
void ReweighImpl(const float* const* paths, const float* mu, std::size_t layers, const float* const* gradient_paths, std::size_t gradient_layers,
                 std::size_t n, double* sums, double* gradient) {
    const hn::ScalableTag<float> df;
    const std::size_t lanes = hn::Lanes(df);
    const auto cap = hn::Set(df, max_optical_depth);
    const std::size_t padded_layers = std::max(layers, gradient_layers);
    const auto layer_sums = hwy::AllocateAligned<float>(std::max<std::size_t>(1, gradient_layers) * lanes);  // a vector of sums per gradient entry
    const auto tail = hwy::AllocateAligned<float>(std::max<std::size_t>(1, padded_layers) * lanes);  // the last exits, zero-padded
    for (std::size_t start = 0; start < n; start += chunk) {
        const std::size_t m = std::min(chunk, n - start);
        auto s = hn::Zero(df), s2 = hn::Zero(df);
        std::fill_n(layer_sums.get(), gradient_layers * lanes, 0.0f);
        std::size_t i = 0;
        for (; i + 4 * lanes <= m; i += 4 * lanes) {
            auto t0 = hn::Zero(df), t1 = hn::Zero(df), t2 = hn::Zero(df), t3 = hn::Zero(df);
            for (std::size_t k = 0; k < layers; ++k) {
                const float* p = paths[k] + start + i;
                const auto mu_k = hn::Set(df, mu[k]);
                t0 = hn::MulAdd(mu_k, hn::LoadU(df, p), t0);
                t1 = hn::MulAdd(mu_k, hn::LoadU(df, p + lanes), t1);
                t2 = hn::MulAdd(mu_k, hn::LoadU(df, p + 2 * lanes), t2);
                t3 = hn::MulAdd(mu_k, hn::LoadU(df, p + 3 * lanes), t3);
            }
            const auto w0 = ExpOfNegativeDepth(df, hn::Min(t0, cap)), w1 = ExpOfNegativeDepth(df, hn::Min(t1, cap));
            const auto w2 = ExpOfNegativeDepth(df, hn::Min(t2, cap)), w3 = ExpOfNegativeDepth(df, hn::Min(t3, cap));
            s = hn::Add(s, hn::Add(hn::Add(w0, w1), hn::Add(w2, w3)));
            s2 = hn::MulAdd(w0, w0, hn::MulAdd(w1, w1, hn::MulAdd(w2, w2, hn::MulAdd(w3, w3, s2))));
            if (!gradient) continue;
            for (std::size_t k = 0; k < gradient_layers; ++k) {
                const float* p = gradient_paths[k] + start + i;
                float* g = layer_sums.get() + k * lanes;
                auto acc = hn::MulAdd(hn::LoadU(df, p), w0, hn::Load(df, g));
                acc = hn::MulAdd(hn::LoadU(df, p + lanes), w1, acc);
                acc = hn::MulAdd(hn::LoadU(df, p + 2 * lanes), w2, acc);
                hn::Store(hn::MulAdd(hn::LoadU(df, p + 3 * lanes), w3, acc), df, g);
            }
        }
        // The rest a vector at a time; the last one (fewer exits than lanes) through zero-padded copies (no read past
        // the end), its empty lanes weighing 0.
        for (; i < m; i += lanes) {
            const std::size_t here = std::min(lanes, m - i);
            const auto at = [&](const float* const* from, std::size_t k) {
                const float* p = from[k] + start + i;
                if (here == lanes) return p;
                float* padded = tail.get() + k * lanes;
                std::fill_n(padded, lanes, 0.0f);
                std::copy_n(p, here, padded);
                return static_cast<const float*>(padded);
            };
            auto tau = hn::Zero(df);
            for (std::size_t k = 0; k < layers; ++k) tau = hn::MulAdd(hn::Set(df, mu[k]), hn::LoadU(df, at(paths, k)), tau);
            const auto w = hn::IfThenElseZero(hn::FirstN(df, here), ExpOfNegativeDepth(df, hn::Min(tau, cap)));
            s = hn::Add(s, w);
            s2 = hn::MulAdd(w, w, s2);
            if (!gradient) continue;
            for (std::size_t k = 0; k < gradient_layers; ++k) {
                float* g = layer_sums.get() + k * lanes;
                hn::Store(hn::MulAdd(hn::LoadU(df, at(gradient_paths, k)), w, hn::Load(df, g)), df, g);
            }
        }
        sums[0] += static_cast<double>(hn::GetLane(hn::SumOfLanes(df, s)));
        sums[1] += static_cast<double>(hn::GetLane(hn::SumOfLanes(df, s2)));
        if (!gradient) continue;
        for (std::size_t k = 0; k < gradient_layers; ++k) gradient[k] += static_cast<double>(hn::GetLane(hn::SumOfLanes(df, hn::Load(df, layer_sums.get() + k * lanes))));
    }
}

// Each exit's weight exp(-sum_k mu_k L_k) over the `layers` entries of `paths` and `mu`, into `out` (n of them); the
// last vector through zero-padded copies, as ReweighImpl.
void WeighEachImpl(const float* const* paths, const float* mu, std::size_t layers, std::size_t n, float* out) {
    const hn::ScalableTag<float> df;
    const std::size_t lanes = hn::Lanes(df);
    const auto cap = hn::Set(df, max_optical_depth);
    const auto tail = hwy::AllocateAligned<float>(std::max<std::size_t>(1, layers) * lanes);
    const auto last = hwy::AllocateAligned<float>(lanes);
    for (std::size_t i = 0; i < n; i += lanes) {
        const std::size_t here = std::min(lanes, n - i);
        auto tau = hn::Zero(df);
        for (std::size_t k = 0; k < layers; ++k) {
            const float* p = paths[k] + i;
            if (here < lanes) {
                float* padded = tail.get() + k * lanes;
                std::fill_n(padded, lanes, 0.0f);
                std::copy_n(p, here, padded);
                p = padded;
            }
            tau = hn::MulAdd(hn::Set(df, mu[k]), hn::LoadU(df, p), tau);
        }
        const auto w = ExpOfNegativeDepth(df, hn::Min(tau, cap));
        if (here == lanes) {
            hn::StoreU(w, df, out + i);
        } else {
            hn::Store(w, df, last.get());
            std::copy_n(last.get(), here, out + i);
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace skinspec
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skinspec {

HWY_EXPORT(ReweighImpl);
HWY_EXPORT(WeighEachImpl);

void ExitPaths::append(const ExitPaths& other) {
    rays += other.rays;
    surface_exits += other.surface_exits;
    surface_reflections += other.surface_reflections;
    truncated_rays += other.truncated_rays;
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

namespace {

// The optical depth's terms for mu_a * scale (less the thinning floor): the layers whose effective absorption is not 0
// (a layer at the floor adds nothing), their coefficients and paths.
std::pair<std::vector<float>, std::vector<const float*>> depth_terms(const ExitPaths& paths, const std::vector<double>& mu_a, const std::vector<double>& scale) {
    std::vector<float> mu;
    std::vector<const float*> depth_paths;
    for (std::size_t k = 0; k < paths.layers(); ++k) {
        const double floor = paths.thinned_at_per_cm.empty() ? 0.0 : paths.thinned_at_per_cm[k];
        const auto effective = static_cast<float>(mu_a[k] * (scale.empty() ? 1.0 : scale[k]) - floor);
        if (effective != 0.0f) {
            mu.push_back(effective);
            depth_paths.push_back(paths.layer_path_cm[k].data());
        }
    }
    return {mu, depth_paths};
}

// The kernel's sums for `paths` at mu_a * scale (less the thinning floor), with the gradient's sums for the layers
// flagged in `gradient_layers` (empty: all) when `gradient` is given (its entries for the others 0).
ExitPaths::WeightSums reweigh(const ExitPaths& paths, const std::vector<double>& mu_a, const std::vector<double>& scale, std::vector<double>* gradient,
                              const std::vector<bool>& gradient_layers) {
    const std::size_t layers = paths.layers();
    if (gradient) gradient->assign(layers, 0.0);
    const auto [mu, depth_paths] = depth_terms(paths, mu_a, scale);
    std::vector<const float*> gradient_paths;
    std::vector<std::size_t> gradient_of;
    for (std::size_t k = 0; k < layers; ++k) {
        if (gradient && (gradient_layers.empty() || gradient_layers[k])) {
            gradient_paths.push_back(paths.layer_path_cm[k].data());
            gradient_of.push_back(k);
        }
    }
    double sums[2] = {static_cast<double>(paths.surface_exits), static_cast<double>(paths.surface_exits)};
    std::vector<double> gradient_sums(gradient_of.size(), 0.0);
    HWY_DYNAMIC_DISPATCH(ReweighImpl)(depth_paths.data(), mu.data(), depth_paths.size(), gradient_paths.data(), gradient_paths.size(), paths.exits(),
                                      sums, gradient ? gradient_sums.data() : nullptr);
    for (std::size_t g = 0; g < gradient_of.size(); ++g) (*gradient)[gradient_of[g]] = gradient_sums[g];
    return {sums[0], sums[1]};
}

}  // namespace

ExitPaths::WeightSums ExitPaths::weight_sums(const std::vector<double>& mu_a, const std::vector<double>& scale) const {
    return reweigh(*this, mu_a, scale, nullptr, {});
}

void ExitPaths::weights(const std::vector<double>& mu_a, std::vector<float>& out) const {
    const auto [mu, depth_paths] = depth_terms(*this, mu_a, {});
    out.resize(exits());
    HWY_DYNAMIC_DISPATCH(WeighEachImpl)(depth_paths.data(), mu.data(), depth_paths.size(), exits(), out.data());
}

Estimate ExitPaths::reflectance(const std::vector<double>& mu_a, const std::vector<double>& scale, std::vector<double>* gradient,
                                const std::vector<bool>& gradient_layers) const {
    if (rays == 0) {
        if (gradient) gradient->assign(layers(), 0.0);
        return {};
    }
    const auto sums = reweigh(*this, mu_a, scale, gradient, gradient_layers);
    const double count = static_cast<double>(rays);
    const double mean = sums.sum / count;
    const double variance = rays > 1 ? std::max(0.0, sums.sum_of_squares / count - mean * mean) / (count - 1.0) : 0.0;
    if (gradient) {
        for (auto& g : *gradient) g = -g / count * factor;
    }
    return {mean * factor, std::sqrt(variance) * factor};
}

}  // namespace skinspec
#endif  // HWY_ONCE
