#pragma once
// Multipole diffusion for a slab (Donner & Jensen 2005, Sec. 2.1-2.2): dipole pairs mirrored about
// both extrapolated boundaries (Eq. 16), diffuse reflectance R(r) (Eq. 12) and transmittance T(r) (Eq. 13),
// with different index mismatches (or a rough top, Sec. 2.4) at the two faces. A semi-infinite slab is the
// dipole of Jensen et al. 2001. Lengths in any one unit (mm for the presets): coefficients per unit, radii in the unit.
//
// Profiles sum pairs i = 0, +-1, +-2, ... until the next pair changes the sum by less than the relative
// tolerance (and the pairs lie beyond r); totals and transforms sum the infinite series in closed form
// (each source integrates to sgn(w) exp(-s|w|)/2, and the far pairs form geometric series), so they need no
// truncation at all and stay exact for sigma_a = 0.
#include <cstddef>
#include <span>
#include <vector>

namespace skinspec {

struct DiffusionSlab {
    double reduced_scattering = 0.0;  // sigma_s' per unit length
    double absorption = 0.0;          // sigma_a per unit length
    double thickness = 1.0;           // in the unit; infinity for a semi-infinite medium (the dipole)
    // Diffuse reflectance, seen from inside, of the top and bottom faces: F_dr(eta) of a smooth interface
    // (diffuse_fresnel_reflectance, Donner & Jensen 2005 Eq. 8) or rho_d of a rough one (Donner & Jensen 2005 Sec. 2.4).
    double top_internal_reflectance = 0.0;
    double bottom_internal_reflectance = 0.0;
};

// Profile values with the largest number of pairs any radius needed.
struct RadialProfile {
    std::vector<double> values;
    std::size_t max_pairs = 0;
    std::size_t frequencies = 0;  // samples of the inverse transform (layered profiles only)
    bool converged = true;        // false when some radius hit max_pairs (or the transform its sample cap)
    bool cancelled = false;       // stopped by a stop request: the values are no profile
};

class Multipole {
public:
    static constexpr std::size_t max_pairs = 100'000;

    // InputError naming the field for negative or non-finite coefficients, sigma_t' = 0, a non-positive
    // thickness or a face reflectance outside [0, 1).
    explicit Multipole(const DiffusionSlab& slab, double relative_tolerance = 1e-10);

    const DiffusionSlab& slab() const { return slab_; }
    double reduced_albedo() const { return alpha_prime_; }
    double effective_transport() const { return sigma_tr_; }  // sigma_tr = sqrt(3 sigma_a sigma_t')
    double mean_free_path() const { return l_; }             // l = 1 / sigma_t', the source depth
    // The source depth used: l, or the slab thickness when the slab is thinner than l (outside diffusion's
    // range; see docs/DIFFUSION.md).
    double source_depth() const { return z_s_; }
    bool semi_infinite() const { return !finite_; }

    // Eq. 12 and 13 at one radius (per unit area).
    double radial_reflectance(double r) const;
    double radial_transmittance(double r) const;
    RadialProfile reflectance_profile(std::span<const double> radii) const;
    RadialProfile transmittance_profile(std::span<const double> radii) const;

    // Totals: 2 pi int R(r) r dr and likewise for T, summed over all pairs in closed form.
    double total_reflectance() const { return reflectance_transform(0.0); }
    double total_transmittance() const { return transmittance_transform(0.0); }
    // 2-D Fourier transforms at spatial frequency k (radians per unit length): 2 pi int R(r) J0(k r) r dr.
    double reflectance_transform(double k) const;
    double transmittance_transform(double k) const;

    // The same slab lit from below (faces swapped), for layer composition.
    Multipole flipped() const;

private:
    struct Sum {
        double value;
        std::size_t pairs;
        bool converged;
    };
    Sum profile_sum(double r, bool transmit) const;
    double transform(double k, bool transmit) const;

    DiffusionSlab slab_;
    double tolerance_;
    bool finite_;
    double alpha_prime_, sigma_tr_, l_, z_s_, zb_top_, zb_bottom_, period_;
    int explicit_pairs_;  // |i| < this are summed term by term in the transforms; the rest in closed form
};

}  // namespace skinspec
