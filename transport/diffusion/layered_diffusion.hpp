#pragma once
// Diffusion through a stack of slabs (Donner & Jensen 2005, Sec. 2.3): each slab's multipole
// response is combined with the next in frequency space, where the convolutions of the inter-layer series
// become products (Eq. 19-22, Kubelka-Munk in frequency space):
//   R_ab = R_a + T_a(down) R_b T_a(up) / (1 - R_a(up) R_b),   T_ab = T_a T_b / (1 - R_a(up) R_b),
// applied recursively from the top. The paper uses one R_1 and T_1 for both directions; here a slab lit from
// below uses its own multipole with the faces swapped (they differ when the two faces' indices differ).
// The transforms of every multipole are exact (layers/diffusion/point_source.hpp), so totals (k = 0) are
// exact sums; profiles are transformed back numerically (a Hankel transform with glibc's j0), after removing
// the top slab's own reflectance, which is known in closed form in real space.
#include <atomic>
#include <cstddef>
#include <span>
#include <vector>

#include "transport/diffusion/multipole.hpp"

namespace skinspec {

enum class DiffusionBottom {
    open,       // light leaving the last slab is transmittance
    // A diffuse reflector returns its reflectance rho of what arrives, at the point where it arrives, and keeps the
    // rest (T): 1 for BioSpec's ideal hypodermis, below 1 for the measured one.
    reflector,
};

// The four responses of a stack at one spatial frequency.
struct StackResponse {
    double reflectance_down = 0.0;  // light entering from above, leaving at the top
    double reflectance_up = 0.0;    // light entering from below, leaving at the bottom
    double transmittance_down = 0.0;
    double transmittance_up = 0.0;
};

class LayeredDiffusion {
public:
    // InputError for an empty stack or a semi-infinite slab above another slab or above a reflector; `reflectance`
    // is the reflector's rho, in [0, 1].
    LayeredDiffusion(std::vector<Multipole> slabs, DiffusionBottom bottom, double reflectance = 1.0);

    const std::vector<Multipole>& slabs() const { return slabs_; }
    StackResponse response(double k) const;
    double total_reflectance() const { return response(0.0).reflectance_down; }
    double total_transmittance() const { return response(0.0).transmittance_down; }

    // Real-space profiles at the given radii. The inverse transform samples k uniformly with a step that
    // resolves max(radii) and up to where the integrand has decayed by 1e-10; `converged` is false when that
    // needed more than max_frequencies samples.
    // `cancel`: checked every 16 radii and 1024 frequencies of the transform (RadialProfile::cancelled).
    RadialProfile reflectance_profile(std::span<const double> radii, const std::atomic<bool>* cancel = nullptr) const;
    RadialProfile transmittance_profile(std::span<const double> radii, const std::atomic<bool>* cancel = nullptr) const;

    static constexpr std::size_t max_frequencies = 200'000;

private:
    RadialProfile inverse_transform(std::span<const double> radii, bool transmit, const std::atomic<bool>* cancel) const;

    std::vector<Multipole> slabs_;
    std::vector<Multipole> flipped_;
    DiffusionBottom bottom_;
    double reflectance_;
};

}  // namespace skinspec
