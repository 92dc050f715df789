// Lane-parallel building blocks of the Monte Carlo walks' SIMD packets (Google Highway; included once per
// instruction set by the walks' foreach_target translation units): per-lane random streams, reciprocals, the
// direction change of a scattering event, Henyey-Greenstein and Rayleigh sampling, Fresnel and Snell at an interface,
// per-layer constants by lane, a weight's exponential. Each formula is the one of the scalar code it mirrors (cited at each).

// Highway's per-target include guard: this header is compiled once for every instruction set.
#if defined(SKINSPEC_TRANSPORT_SIMD_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SKINSPEC_TRANSPORT_SIMD_LANES_INL_H_
#undef SKINSPEC_TRANSPORT_SIMD_LANES_INL_H_
#else
#define SKINSPEC_TRANSPORT_SIMD_LANES_INL_H_
#endif

#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include <cstdint>
#include <cstring>
#include <numbers>

HWY_BEFORE_NAMESPACE();
namespace skinspec {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using VU = hn::Vec<DU>;
using MF = hn::Mask<DF>;

HWY_INLINE MF FromInt(hn::Mask<DI> m) { return hn::RebindMask(DF(), m); }
HWY_INLINE hn::Mask<DI> ToInt(MF m) { return hn::RebindMask(DI(), m); }

// xoshiro128+ (Blackman & Vigna 2018), one stream per lane: uniform in [0, 1) from the top 24 bits.
struct LaneRandom {
    VU s0, s1, s2, s3;

    // The streams of lanes [base, base + Lanes) of a packet's rng[4][...] words.
    static LaneRandom load(const std::uint32_t* const words[4], std::size_t base) {
        const DU du;
        return {hn::LoadU(du, words[0] + base), hn::LoadU(du, words[1] + base), hn::LoadU(du, words[2] + base), hn::LoadU(du, words[3] + base)};
    }
    void store(std::uint32_t* const words[4], std::size_t base) const {
        const DU du;
        hn::StoreU(s0, du, words[0] + base);
        hn::StoreU(s1, du, words[1] + base);
        hn::StoreU(s2, du, words[2] + base);
        hn::StoreU(s3, du, words[3] + base);
    }

    // Every lane draws (the streams of lanes without a ray are re-seeded before use).
    VF uniform() {
        const VU result = hn::Add(s0, s3);
        const VU t = hn::ShiftLeft<9>(s1);
        s2 = hn::Xor(s2, s0);
        s3 = hn::Xor(s3, s1);
        s1 = hn::Xor(s1, s2);
        s0 = hn::Xor(s0, s3);
        s2 = hn::Xor(s2, t);
        s3 = hn::RotateRight<21>(s3);  // rotl(., 11)
        return to_unit(result);
    }
    // Only the lanes of `draw` draw.
    VF uniform(MF draw) {
        const auto m = hn::RebindMask(DU(), draw);
        const LaneRandom before = *this;
        const VF u = uniform();
        s0 = hn::IfThenElse(m, s0, before.s0);
        s1 = hn::IfThenElse(m, s1, before.s1);
        s2 = hn::IfThenElse(m, s2, before.s2);
        s3 = hn::IfThenElse(m, s3, before.s3);
        return u;
    }
    static VF to_unit(VU bits) {
        const DF df;
        return hn::Mul(hn::ConvertTo(df, hn::BitCast(DI(), hn::ShiftRight<8>(bits))), hn::Set(df, 0x1.0p-24f));
    }
};

// A uniform azimuth as (cos phi, sin phi) from u in [0, 1), with one range reduction for both: 4u = q + f splits
// the circle into quarter turns q (0..3) and theta = (f - 1/2) pi / 2 in [-pi/4, pi/4); phi = theta + q pi / 2, so
// (cos, sin) of phi are those of theta turned by q quarters. sin and cos of theta by Cephes' single-precision
// minimax polynomials on [-pi/4, pi/4] (Moshier 1989, sinf.c / cosf.c; within 1 ulp there).
HWY_INLINE void Azimuth(VF u, VF& cos_phi, VF& sin_phi) {
    const DF df;
    const DI di;
    const VF v = hn::Mul(u, hn::Set(df, 4.0f));
    const VF whole = hn::Floor(v);
    const VF x = hn::Mul(hn::Sub(hn::Sub(v, whole), hn::Set(df, 0.5f)), hn::Set(df, static_cast<float>(std::numbers::pi / 2.0)));
    const VF x2 = hn::Mul(x, x);
    const VF sin_poly = hn::MulAdd(hn::MulAdd(hn::Set(df, -1.9515295891e-4f), x2, hn::Set(df, 8.3321608736e-3f)), x2, hn::Set(df, -1.6666654611e-1f));
    const VF s = hn::MulAdd(hn::Mul(sin_poly, x2), x, x);
    const VF cos_poly =
        hn::MulAdd(hn::MulAdd(hn::Set(df, 2.443315711809948e-5f), x2, hn::Set(df, -1.388731625493765e-3f)), x2, hn::Set(df, 4.166664568298827e-2f));
    const VF c = hn::MulAdd(hn::Mul(cos_poly, x2), x2, hn::NegMulAdd(hn::Set(df, 0.5f), x2, hn::Set(df, 1.0f)));
    // Quarter q: (cos, sin) = (c, s), (-s, c), (-c, -s), (s, -c).
    const VI q = hn::ConvertTo(di, whole);
    const MF odd = FromInt(hn::Ne(hn::And(q, hn::Set(di, 1)), hn::Zero(di)));
    const MF cos_negative = FromInt(hn::Ne(hn::And(hn::Add(q, hn::Set(di, 1)), hn::Set(di, 2)), hn::Zero(di)));
    const MF sin_negative = FromInt(hn::Ne(hn::And(q, hn::Set(di, 2)), hn::Zero(di)));
    const VF a = hn::IfThenElse(odd, s, c);
    const VF b = hn::IfThenElse(odd, c, s);
    cos_phi = hn::IfThenElse(cos_negative, hn::Neg(a), a);
    sin_phi = hn::IfThenElse(sin_negative, hn::Neg(b), b);
}

// 1/x and 1/sqrt(x) to about 1 ulp: the hardware estimate and one Newton-Raphson step (x > 0, finite).
HWY_INLINE VF Inverse(VF x) {
    const DF df;
    const VF r = hn::ApproximateReciprocal(x);
    return hn::Mul(r, hn::NegMulAdd(x, r, hn::Set(df, 2.0f)));
}
HWY_INLINE VF InverseSqrt(VF x) {
    const DF df;
    const VF r = hn::ApproximateReciprocalSqrt(x);
    return hn::Mul(hn::Mul(r, hn::Set(df, 0.5f)), hn::NegMulAdd(hn::Mul(x, r), r, hn::Set(df, 3.0f)));
}

// `d` turned by theta (cos c, sin s) at azimuth phi about itself (Witt 1977; MCML's SpinTheta, Wang, Jacques &
// Zheng 1995 Eq. 3.24-3.26), with sqrt(1 - d_z^2) taken as |(d_x, d_y)|, which single precision keeps accurate
// near the normal.
HWY_INLINE void Deflect(VF dx, VF dy, VF dz, VF c, VF s, VF cos_phi, VF sin_phi, VF& ox, VF& oy, VF& oz) {
    const DF df;
    const VF t2 = hn::MulAdd(dx, dx, hn::Mul(dy, dy));
    const MF axial = t2 < hn::Set(df, 1e-10f);
    const VF inv_t = InverseSqrt(hn::Max(t2, hn::Set(df, 1e-10f)));
    const VF t = hn::Mul(t2, inv_t);
    const VF a = hn::Mul(s, cos_phi);
    const VF b = hn::Mul(s, sin_phi);
    const VF x = hn::MulAdd(hn::MulSub(hn::Mul(a, dz), dx, hn::Mul(b, dy)), inv_t, hn::Mul(dx, c));
    const VF y = hn::MulAdd(hn::MulAdd(hn::Mul(a, dz), dy, hn::Mul(b, dx)), inv_t, hn::Mul(dy, c));
    const VF z = hn::MulAdd(dz, c, hn::Neg(hn::Mul(a, t)));
    ox = hn::IfThenElse(axial, a, x);
    oy = hn::IfThenElse(axial, b, y);
    oz = hn::IfThenElse(axial, hn::Mul(c, hn::CopySign(hn::Set(df, 1.0f), dz)), z);
}

// Henyey-Greenstein cos theta (Baranoski et al. 2005 Eq. 5; henyey_greenstein.hpp), 1 - 2u near g = 0.
HWY_INLINE VF HgCos(VF g, VF u) {
    const DF df;
    const VF one = hn::Set(df, 1.0f);
    const VF g2 = hn::Mul(g, g);
    // The denominator 1 - g + 2 g u vanishes only for g = 1 (in single precision) and u = 0, where cos = 1.
    const VF q = hn::Div(hn::Sub(one, g2), hn::Max(hn::MulAdd(hn::Add(g, g), u, hn::Sub(one, g)), hn::Set(df, 1e-30f)));
    const VF c = hn::Div(hn::NegMulAdd(q, q, hn::Add(one, g2)), hn::Add(g, g));
    const VF isotropic = hn::NegMulAdd(hn::Set(df, 2.0f), u, one);
    const VF clamped = hn::Min(hn::Max(c, hn::Set(df, -1.0f)), one);
    return hn::IfThenElse(hn::Abs(g) < hn::Set(df, 1e-6f), isotropic, clamped);
}

// Rayleigh cos theta: the root mu of the CDF (3 mu + mu^3 + 4) / 8 = u (Chandrasekhar 1960 Eq. I.(26);
// rayleigh_phase.hpp), i.e. mu^3 + 3 mu = y with y = 8u - 4 (exact in single precision for u on the 2^-24 grid).
// A first guess by an odd quintic fitted to the exact root over y in [-4, 4] (max error 2.8e-3), then one Halley
// step on f(mu) = mu^3 + 3 mu - y, whose f' = 3 mu^2 + 3 >= 3 never vanishes: 6e-9 in exact arithmetic, single-
// precision rounding (~1e-7) in practice.
HWY_INLINE VF RayleighCos(VF u) {
    const DF df;
    const VF y = hn::MulAdd(u, hn::Set(df, 8.0f), hn::Set(df, -4.0f));
    const VF y2 = hn::Mul(y, y);
    const VF guess = hn::Mul(y, hn::MulAdd(hn::MulAdd(hn::Set(df, 1.87631021e-4f), y2, hn::Set(df, -7.79710490e-3f)), y2, hn::Set(df, 3.27420594e-1f)));
    const VF m2 = hn::Mul(guess, guess);
    const VF f = hn::MulSub(guess, hn::Add(m2, hn::Set(df, 3.0f)), y);
    const VF f1 = hn::MulAdd(m2, hn::Set(df, 3.0f), hn::Set(df, 3.0f));
    const VF f2 = hn::Mul(guess, hn::Set(df, 6.0f));
    // Halley: mu - 2 f f' / (2 f'^2 - f f'').
    const VF step = hn::Div(hn::Mul(hn::Add(f, f), f1), hn::MulSub(hn::Add(f1, f1), f1, hn::Mul(f, f2)));
    return hn::Min(hn::Max(hn::Sub(guess, step), hn::Set(df, -1.0f)), hn::Set(df, 1.0f));
}

// Fresnel's unpolarised reflectance (Born & Wolf Sec. 1.5.2; fresnel.cpp) for |cos_i| at an interface of relative
// index eta = n_from / n_to (m = n_to / n_from), numerators and denominators divided by n_from, with Snell's cos of
// the refracted ray in cos_t; `total` marks total internal reflection (reflectance 1 there).
HWY_INLINE VF FresnelReflectance(VF cos_incident, VF eta, VF m, VF& cos_t, MF& total) {
    const DF df;
    const VF zero = hn::Zero(df);
    const VF one = hn::Set(df, 1.0f);
    const VF cos_i = hn::Min(cos_incident, one);
    const VF sin2_t = hn::Mul(hn::Mul(eta, eta), hn::Mul(hn::Sub(one, cos_i), hn::Add(one, cos_i)));
    total = sin2_t >= one;
    cos_t = hn::Sqrt(hn::Max(zero, hn::Sub(one, sin2_t)));
    const VF s_den = hn::MulAdd(m, cos_t, cos_i);
    const VF p_den = hn::MulAdd(m, cos_i, cos_t);
    const VF inverse_den = Inverse(hn::Max(hn::Mul(s_den, p_den), hn::Set(df, 1e-30f)));
    const VF rs = hn::Mul(hn::Mul(hn::NegMulAdd(m, cos_t, cos_i), p_den), inverse_den);
    const VF rp = hn::Mul(hn::Mul(hn::NegMulAdd(m, cos_i, cos_t), s_den), inverse_den);
    return hn::IfThenElse(total, one, hn::Mul(hn::Set(df, 0.5f), hn::MulAdd(rs, rs, hn::Mul(rp, rp))));
}

// A per-layer constant for each lane's layer k: a lane permute when the layers fit in one vector (the walks pad
// their per-layer arrays to a multiple of the widest vector), else a gather.
template <class D>
struct PerLayer {
    using T = hn::TFromD<D>;
    hn::Vec<D> at(VI k) const {
        const D d;
        if (permute) return hn::TableLookupLanes(hn::LoadU(d, data), hn::IndicesFromVec(d, k));
        return hn::GatherIndex(d, data, k);
    }
    const T* data;
    bool permute;
};

// exp(-tau) for an optical depth tau in [0, 80] (the caller caps it: beyond, a weight is below 2e-35): e^r 2^n with
// n = round(-tau log2(e)) (2^n >= 2^-116 built in the exponent field, a normal float) and r = -tau - n ln 2 in
// [-ln2 / 2, ln2 / 2], reduced with ln 2 split in two parts (Cody & Waite 1980, Software Manual for the Elementary
// Functions, ch. 6) so that r carries no more error than tau; e^r by its Taylor series to degree 6 (remainder below
// (ln2 / 2)^7 / 7! = 1.2e-7 relative, a float's precision; tests/test_simd_lanes.cpp checks it against std::exp over
// the range on every instruction set). The range has no overflow, NaN or subnormal cases, so none is handled.
template <class D, class V>
HWY_INLINE V ExpOfNegativeDepth(D d, V tau) {
    const hn::RebindToSigned<D> di;
    const auto n = hn::Round(hn::Mul(tau, hn::Set(d, -1.44269504088896341f)));
    auto r = hn::MulAdd(n, hn::Set(d, -0.693145751953125f), hn::Neg(tau));  // ln 2's leading bits: n times it is exact
    r = hn::MulAdd(n, hn::Set(d, -1.4286068202862268e-6f), r);
    auto p = hn::Set(d, 1.0f / 720.0f);
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f / 120.0f));
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f / 24.0f));
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f / 6.0f));
    p = hn::MulAdd(p, r, hn::Set(d, 0.5f));
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f));
    p = hn::MulAdd(p, r, hn::Set(d, 1.0f));
    const auto scale = hn::ShiftLeft<23>(hn::ConvertTo(di, n));  // n added to e^r's exponent field
    return hn::BitCast(d, hn::Add(hn::BitCast(di, p), scale));
}

// The lanes of `m` as bits of a packet's 64-bit lane mask, for the vector starting at lane `base`.
HWY_INLINE std::uint64_t MaskBits(MF m, std::size_t base) {
    const DF df;
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(df, m, bits);
    std::uint64_t chunk = 0;
    std::memcpy(&chunk, bits, sizeof(bits));
    const std::size_t n = hn::Lanes(df);
    if (n < 64) chunk &= (std::uint64_t{1} << n) - 1;
    return chunk << base;
}

}  // namespace HWY_NAMESPACE
}  // namespace skinspec
HWY_AFTER_NAMESPACE();

#endif  // SKINSPEC_TRANSPORT_SIMD_LANES_INL_H_
