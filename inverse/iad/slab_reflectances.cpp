#include "inverse/iad/slab_reflectances.hpp"

#include <cmath>
#include <numbers>

#include "transport/fresnel.hpp"

namespace skinspec {
namespace {

bool has_slides(const SlabSetup& s) { return s.slide_index != 1.0 && s.slide_thickness_mm > 0.0; }

// An incoherent stack of two faces (or face groups) with nothing absorbed between them: per face group
// R = r1 + t1^2 r2 / (1 - r1 r2), T = t1 t2 / (1 - r1 r2) (lossless faces: the same from either side).
Unscattered added(const Unscattered& upper, const Unscattered& lower, double attenuation) {
    const double bounce = 1.0 - upper.r * lower.r * attenuation * attenuation;
    return {upper.r + upper.t * upper.t * lower.r * attenuation * attenuation / bounce, upper.t * lower.t * attenuation / bounce};
}

}  // namespace

Unscattered unscattered(double optical_thickness, const SlabSetup& setup) {
    const double sin_air = std::sin(setup.incidence_deg * std::numbers::pi / 180.0);
    const auto face = [&](double n1, double n2) {
        const double cos1 = std::sqrt(1.0 - (sin_air / n1) * (sin_air / n1));  // Snell: n sin(theta) is kept
        const double r = fresnel_reflectance(cos1, n1, n2);
        return Unscattered{r, 1.0 - r};
    };
    const double n = setup.sample_index;
    Unscattered top = face(1.0, n), bottom = face(n, 1.0);
    if (has_slides(setup)) {
        const double ns = setup.slide_index;
        top = added(face(1.0, ns), face(ns, n), 1.0);
        bottom = added(face(n, ns), face(ns, 1.0), 1.0);
    }
    const double cos_sample = std::sqrt(1.0 - (sin_air / n) * (sin_air / n));
    return added(top, bottom, std::exp(-optical_thickness / cos_sample));
}

SlabReflectances slab_reflectances(const SlabOptics& optics, const SlabSetup& setup, std::size_t channels, AdCache& cache) {
    // Any thickness: the slab's transport depends on a, b and g alone. Clear slides are exact diagonal elements.
    constexpr double thickness_cm = 1.0;
    RteStack stack;
    const double mu_t = optics.optical_thickness / thickness_cm;
    const RteLayer sample{setup.sample_index, (1.0 - optics.albedo) * mu_t, optics.albedo * mu_t, thickness_cm,
                          PhaseFunction::henyey_greenstein(optics.g)};
    if (has_slides(setup)) {
        const RteLayer slide{setup.slide_index, 0.0, 0.0, setup.slide_thickness_mm / 10.0, PhaseFunction::isotropic()};
        stack.layers = {slide, sample, slide};
    } else {
        stack.layers = {sample};
    }
    AdOptions options;
    options.channels = channels;
    options.accuracy_check = false;
    const auto beam = solve_adding_doubling(stack, {false, setup.incidence_deg}, options, &cache);
    const auto diffuse = solve_adding_doubling(stack, {true, 0.0}, options, &cache);
    const auto u = unscattered(optics.optical_thickness, setup);
    return {beam.specular_reflectance + beam.diffuse_reflectance, beam.transmittance, diffuse.specular_reflectance + diffuse.diffuse_reflectance,
            diffuse.transmittance, u.r, u.t};
}

}  // namespace skinspec
