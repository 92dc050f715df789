#include "transport/diffusion/layered_diffusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <math.h>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

// Eq. 21-22 and their mirror images: stack `a` above stack `b`. The series sum 1 / (1 - R_a(up) R_b(down)) is
// finite whenever light can be absorbed or transmitted; with neither, its numerators vanish too.
StackResponse compose(const StackResponse& a, const StackResponse& b) {
    const double loop = 1.0 - a.reflectance_up * b.reflectance_down;
    const auto over = [loop](double numerator) { return numerator == 0.0 ? 0.0 : numerator / std::max(loop, 1e-300); };
    return {a.reflectance_down + over(a.transmittance_down * b.reflectance_down * a.transmittance_up),
            b.reflectance_up + over(b.transmittance_up * a.reflectance_up * b.transmittance_down),
            over(a.transmittance_down * b.transmittance_down), over(b.transmittance_up * a.transmittance_up)};
}

StackResponse slab_response(const Multipole& down, const Multipole& up, double k) {
    return {down.reflectance_transform(k), up.reflectance_transform(k), down.transmittance_transform(k),
            up.transmittance_transform(k)};
}

}  // namespace

LayeredDiffusion::LayeredDiffusion(std::vector<Multipole> slabs, DiffusionBottom bottom, double reflectance)
    : slabs_(std::move(slabs)), bottom_(bottom), reflectance_(reflectance) {
    if (slabs_.empty()) throw InputError("layered diffusion: the stack has no slabs");
    for (std::size_t i = 0; i < slabs_.size(); ++i) {
        const bool last = i + 1 == slabs_.size();
        if (slabs_[i].semi_infinite() && (!last || bottom_ == DiffusionBottom::reflector)) {
            throw InputError("layered diffusion: slab " + std::to_string(i + 1) + " is semi-infinite but has " +
                             (last ? "a reflector" : "slabs") + " below it");
        }
        flipped_.push_back(slabs_[i].flipped());
    }
}

StackResponse LayeredDiffusion::response(double k) const {
    StackResponse stack = slab_response(slabs_[0], flipped_[0], k);
    for (std::size_t i = 1; i < slabs_.size(); ++i) stack = compose(stack, slab_response(slabs_[i], flipped_[i], k));
    // The reflector returns rho locally (its transform is rho at every frequency) and keeps 1 - rho, counted as T.
    if (bottom_ == DiffusionBottom::reflector) stack = compose(stack, {reflectance_, 0.0, 1.0 - reflectance_, 0.0});
    return stack;
}

RadialProfile LayeredDiffusion::reflectance_profile(std::span<const double> radii, const std::atomic<bool>* cancel) const {
    auto out = slabs_[0].reflectance_profile(radii);
    if (slabs_.size() == 1 && bottom_ == DiffusionBottom::open) return out;
    const auto rest = inverse_transform(radii, false, cancel);
    out.cancelled = rest.cancelled;
    for (std::size_t i = 0; i < radii.size(); ++i) out.values[i] += rest.values[i];
    out.frequencies = rest.frequencies;
    out.converged = out.converged && rest.converged;
    return out;
}

RadialProfile LayeredDiffusion::transmittance_profile(std::span<const double> radii, const std::atomic<bool>* cancel) const {
    if (bottom_ == DiffusionBottom::reflector && reflectance_ == 1.0) return {std::vector<double>(radii.size(), 0.0), 0, 0, true};
    if (slabs_.size() == 1 && bottom_ == DiffusionBottom::open) return slabs_[0].transmittance_profile(radii);
    return inverse_transform(radii, true, cancel);
}

RadialProfile LayeredDiffusion::inverse_transform(std::span<const double> radii, bool transmit, const std::atomic<bool>* cancel) const {
    const auto stopped = [cancel] { return cancel && cancel->load(std::memory_order_relaxed); };
    // f(r) = (1 / 2 pi) int_0^inf F(k) J0(k r) k dk, F = T(k), or R(k) minus the top slab's own R_1(k).
    const auto integrand = [&](double k) {
        const auto s = response(k);
        return transmit ? s.transmittance_down : s.reflectance_down - slabs_[0].reflectance_transform(k);
    };
    double r_max = 0.0;
    double sigma_tr_min = std::numeric_limits<double>::infinity();
    double depth = 0.0;
    for (const auto& s : slabs_) {
        sigma_tr_min = std::min(sigma_tr_min, s.effective_transport());
        depth += s.semi_infinite() ? s.mean_free_path() : s.slab().thickness;
    }
    for (const double r : radii) r_max = std::max(r_max, r);
    // The uniform k step puts the first alias of the profile beyond where it has decayed (30 / sigma_tr) and
    // beyond 8 r_max, which also resolves J0 at r_max with at least 8 samples per period.
    const double reach = std::max({8.0 * r_max, sigma_tr_min > 0.0 ? std::min(30.0 / sigma_tr_min, 1e3 * depth) : 1e3 * depth, 30.0 * depth});
    const double dk = 2.0 * std::numbers::pi / reach;
    std::vector<double> weights;  // F(k_j) k_j dk / (2 pi), j = 1, 2, ...
    double peak = 0.0;
    bool converged = false;
    for (std::size_t j = 1; j <= max_frequencies && !converged; ++j) {
        if (j % 1024 == 0 && stopped()) return {std::vector<double>(radii.size(), 0.0), 0, 0, false, true};
        const double k = j * dk;
        const double w = integrand(k) * k * dk / (2.0 * std::numbers::pi);
        weights.push_back(w);
        peak = std::max(peak, std::abs(w));
        converged = j > 16 && std::abs(w) <= 1e-12 * peak;
    }
    // The integrand g(k) = F(k) k J0(k r) is odd in k, so the trapezoid rule needs the Euler-Maclaurin end
    // corrections at k = 0: + h^2 g1 / 12 - h^4 g3 / 720, with g1 = g'(0) = F0 and g3 = g'''(0) = 6 (F2 - F0 r^2 / 4)
    // for F(k) = F0 + F2 k^2 + ...
    const double f0 = integrand(0.0);
    const double f2 = (integrand(dk) - f0) / (dk * dk);
    RadialProfile out{std::vector<double>(radii.size(), 0.0), 0, weights.size(), converged};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, radii.size(), 16), [&](const tbb::blocked_range<std::size_t>& range) {
        if (stopped()) return;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const double r = radii[i];
            double sum = 0.0;
            for (std::size_t j = 0; j < weights.size(); ++j) sum += weights[j] * ::j0(static_cast<double>(j + 1) * dk * r);
            const double end_correction = dk * dk * f0 / 12.0 - std::pow(dk, 4) * (f2 - 0.25 * f0 * r * r) / 120.0;
            out.values[i] = sum + end_correction / (2.0 * std::numbers::pi);
        }
    });
    out.cancelled = stopped();
    return out;
}

}  // namespace skinspec
