// A driver for the BioSpec model authors' own code (BioSpecSkinSPF of their RISE renderer) as a speed and agreement peer
// of skinspec's BioSpec walk (bench/peers/side_by_side.py --rise). Not part of skinspec's build: it is compiled against a
// RISE checkout outside this repository (docs/PERFORMANCE.md, "Side by side with the peers", says how) and contains no
// RISE code, only calls to it.
//
//     rise_biospec NM RAYS MELANOSOME_FRACTION [SEED]
//
// sends RAYS rays at normal incidence into the skin of the 2004 paper's parameters (those of RISE's biospecbsdfmaker,
// the same as skinspec's biospec-* presets) with the given epidermal melanosome fraction, at NM nanometres, and prints
// "R <re-emitted fraction> +- <its binomial standard error> rays/s <rays per second of the walk alone>".
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "pch.h"
#include "Interfaces/IOptions.h"
#include "Interfaces/IScalarPainter.h"
#include "Materials/BioSpecSkinSPF.h"
#include "RISE_API.h"
#include "Utilities/IndependentSampler.h"
#include "Utilities/PiecewiseLinearFunction.h"
#include "Utilities/Reference.h"

namespace RISE {
// The two library entry points the skin model calls, without the rest of RISE_API.cpp (and of the library).
bool RISE_API_CreatePiecewiseLinearFunction1D(IPiecewiseFunction1D** f) {
    *f = new Implementation::PiecewiseLinearFunction1D();
    return true;
}
bool RISE_API_CreatePiecewiseLinearFunction2D(IPiecewiseFunction2D** f) {
    *f = new Implementation::PiecewiseLinearFunction2D();
    return true;
}
// RISE's thread helpers read their options here: every option its default (no global.options file).
struct DefaultOptions : public virtual IOptions, public virtual Implementation::Reference {
    int ReadInt(const char*, int d) override { return d; }
    double ReadDouble(const char*, double d) override { return d; }
    bool ReadBool(const char*, bool d) override { return d; }
    String ReadString(const char*, String d) override { return d; }
};
IOptions& GlobalOptions() {
    static DefaultOptions options;
    return options;
}
}  // namespace RISE

namespace {
struct Constant : public virtual RISE::IScalarPainter, public virtual RISE::Implementation::Reference {
    RISE::Scalar value;
    explicit Constant(RISE::Scalar v) : value(v) {}
    RISE::ScalarTriple GetValuesAt(const RISE::RayIntersectionGeometric&) const override {
        RISE::ScalarTriple t;
        t.v[0] = t.v[1] = t.v[2] = value;
        return t;
    }
};
const RISE::IScalarPainter& constant(RISE::Scalar v) { return *new Constant(v); }
}  // namespace

int main(int argc, char** argv) {
    using namespace RISE;
    if (argc < 4) {
        std::fprintf(stderr, "usage: rise_biospec NM RAYS MELANOSOME_FRACTION [SEED]\n");
        return 1;
    }
    const double nm = std::atof(argv[1]);
    const long rays = std::atol(argv[2]);
    const double melanosomes = std::atof(argv[3]);
    const unsigned seed = argc > 4 ? static_cast<unsigned>(std::atol(argv[4])) : 1u;
    if (!(nm > 0) || rays < 1 || !(melanosomes >= 0 && melanosomes <= 1)) {
        std::fprintf(stderr, "rise_biospec: NM > 0, RAYS >= 1 and MELANOSOME_FRACTION in [0, 1]\n");
        return 1;
    }
    // Thicknesses (cm), indices, melanin (g/L), haemoglobin ratio, blood fractions, bilirubin and beta-carotene (g/L),
    // fold aspect ratio: biospecbsdfmaker's values; the reflecting hypodermis on.
    const auto* skin = new Implementation::BioSpecSkinSPF(
        constant(0.001), constant(0.01), constant(0.02), constant(0.18), constant(1.55), constant(1.4), constant(1.36), constant(1.38),
        constant(80.0), constant(12.0), constant(melanosomes), constant(0.75), constant(0.012), constant(0.0091), constant(0.005),
        constant(2.1e-4), constant(2.1e-4), constant(7.0e-5), constant(0.75), true);
    RandomNumberGenerator random(seed);
    Implementation::IndependentSampler sampler(random);
    RayIntersectionGeometric hit(Ray(Point3(0, 0, 1), Vector3(0, 0, -1)), nullRasterizerState);
    hit.onb.CreateFromW(Vector3(0, 0, 1));
    const IORStack ior(1.0);
    long reemitted = 0;
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < rays; ++i) {
        ScatteredRayContainer scattered;
        skin->ScatterNM(hit, sampler, nm, scattered, ior);
        reemitted += scattered.Count();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double r = static_cast<double>(reemitted) / static_cast<double>(rays);
    std::printf("R %.6f +- %.6f rays/s %.4g\n", r, std::sqrt(r * (1.0 - r) / static_cast<double>(rays)), static_cast<double>(rays) / seconds);
    return 0;
}
