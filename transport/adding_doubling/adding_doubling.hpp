#pragma once
// Deterministic radiative transfer in plane-parallel layers by adding and doubling (van de Hulst 1980, Multiple
// Light Scattering, ch. 4; Prahl 1995, "The adding-doubling method", in Optical-Thermal Response of
// Laser-Irradiated Tissue, ch. 5), on the same RteStack the volumetric walk traces (transport/rte/rte_model.hpp).
//
// Directions are discrete channels of the invariant s = n sin(theta) (Snell: a ray keeps s through every
// interface), so Fresnel interfaces are diagonal and one quadrature serves every layer: s is split at every
// refractive index of the stack (and at the incident beam's s), each segment carries Gauss-Legendre points in
// the cosine of its lowest covering medium (Radau where the incident beam's channel is an end point), and in a
// layer of index n the channels with s < n propagate with cos = sqrt(1 - s^2 / n^2) and weight d(s^2) / n^2.
// Light is carried as flux per channel (radiance scales with n^2 across an interface, the channel's measure with
// 1 / n^2). Each layer: delta-M scaling of its phase function (Wiscombe 1977, J. Atmos. Sci. 34:1408), a
// diamond-difference thin layer (Wiscombe 1976, JQSRT 16:637) of optical depth <= 2^-8 doubled to its
// thickness (at most max_optical_depth: beyond it T is 0 in doubles and R has converged); layers and interfaces are
// added; A per layer from the net fluxes between them.
#include <atomic>
#include <cstddef>
#include <memory>
#include <vector>

#include "transport/rte/rte_model.hpp"

namespace skinspec {

struct AdIncidence {
    bool diffuse = false;     // Lambertian incidence from above instead of a collimated beam
    double angle_deg = 0.0;   // collimated beam's polar angle in the medium above, [0, 90)
};

struct AdOptions {
    std::size_t channels = 24;        // quadrature channels per hemisphere in the densest medium (about)
    bool accuracy_check = true;       // also solve with every segment's channels doubled: AdResult::accuracy (~8x the work)
    const std::atomic<bool>* cancel = nullptr;  // checked at every doubling and adding step (256 channels: ~0.1 s apart)
};

struct AdResult {
    double specular_reflectance = 0.0;  // first-surface reflection
    double diffuse_reflectance = 0.0;   // everything else leaving the top
    double transmittance = 0.0;         // leaving the bottom, unscattered included (0 over a reflector)
    std::vector<double> absorbed_layers;  // per layer (vector solves on the factors the adding keeps: nearly free)
    double accuracy = 0.0;              // twice the largest change of R_d, T or A with every segment's channels doubled
    std::size_t channels = 0;
    bool cancelled = false;             // stopped by AdOptions::cancel: the values are no solution
};

// Work that repeats across calls. The layers' redistribution matrices depend on the phase function, the index and the
// channels only, not on mu_a or mu_s: a spectrum passes one cache through its wavelengths, so each distinct phase
// function is expanded once. A layer's reflection and transmission depend on those and its mu_a, mu_s and thickness:
// in a sweep the layers a member does not change (the dermis while the melanin varies) are reused, not doubled again.
// Both are least recently used out, with bounded sizes; entries compare by content, so a cache is never wrong.
struct AdCache {
    struct Entry;  // ad_elements.hpp
    struct Slab;   // adding_doubling.cpp
    struct TableMoments;  // biospec_adding_doubling.cpp: a measured profile's Legendre moments
    std::vector<std::shared_ptr<const Entry>> entries;
    std::vector<std::shared_ptr<const Slab>> slabs;
    std::vector<std::shared_ptr<const TableMoments>> table_moments;
};

// InputError for stacks the solver cannot take (validate(RteStack) plus the incidence).
AdResult solve_adding_doubling(const RteStack& stack, const AdIncidence& incidence, const AdOptions& options = {}, AdCache* cache = nullptr);

// Its totals as the walk's result type (standard errors 0, no grids): what `mcml --solver adding-doubling` writes.
RteResult rte_totals(const AdResult& result);

}  // namespace skinspec
