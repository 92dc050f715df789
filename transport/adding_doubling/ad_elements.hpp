#pragma once
// The building blocks every adding-doubling solver shares (transport/adding_doubling/adding_doubling.hpp for the
// method): the direction channels, a stack's elements as flux operators (Fresnel interfaces, layers, the Lambertian
// reflector), the phase functions' redistribution matrices, and the adding of elements into totals and A per layer.
// A layer is any linear operator on the channels' fluxes: a homogeneous slab doubled from a thin layer
// (adding_doubling.cpp), or the BioSpec model's per-crossing rules (biospec_adding_doubling.cpp).
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/phase_function.hpp"

namespace skinspec {

using AdMatrix = Eigen::MatrixXd;
using AdVector = Eigen::VectorXd;

// The channels: s = n sin(theta) per channel (increasing) and its measure d(s^2).
struct AdChannels {
    std::vector<double> s;
    std::vector<double> measure;
    std::size_t incident = 0;  // the collimated beam's channel
    std::size_t size() const { return s.size(); }
    // cos(theta) in a medium of index n (0 where the channel does not propagate) and the flux weight d(s^2) / n^2
    // (the share of a cosine-distributed flux in the channel).
    double cosine(std::size_t k, double n) const;
    double weight(std::size_t k, double n) const { return s[k] < n ? measure[k] / (n * n) : 0.0; }
};

// One element of the stack in flux channels. Fresnel interfaces are diagonal in s (vectors); a layer has r, t for
// light from above (t: down) and r_up, t_up for light from below (empty: the same as r, t, a homogeneous slab); the
// Lambertian reflector only reflects (r from above).
struct AdElement {
    enum class Kind { interface, layer, reflector } kind = Kind::interface;
    AdVector r_top_diagonal, r_bottom_diagonal, t_diagonal;  // interface
    AdMatrix r, t;                                           // layer: from above; reflector: r
    AdMatrix r_up, t_up;                                     // layer from below, when it differs
    const AdMatrix& reflection_from_below() const { return r_up.size() ? r_up : r; }
    const AdMatrix& transmission_up() const { return t_up.size() ? t_up : t; }
};

// Fresnel interface from index n1 (above) to n2 (below).
AdElement fresnel_interface(const AdChannels& c, double n1, double n2);

// A phase function's redistribution in the channels a layer of index n propagates in: delta-M scaled (its truncated
// forward fraction f) and, for i, j in `live` (H: the density in mu of the scattered direction),
// same(i, j) = H(mu_i | mu_j), opposite(i, j) = H(-mu_i | mu_j), with sum_i (same + opposite)(i, j) w_i = 1.
// They depend on the phase function, the index and the channels only (not on mu_a, mu_s).
struct AdCache::Entry {
    PhaseFunction phase;
    std::vector<double> table_cosines;  // tabulated phases compare by content (each wavelength has its own table)
    std::vector<double> moments;        // an entry made from Legendre moments: compared by them (phase unused)
    double n = 0.0;
    std::vector<double> channel_s;
    std::vector<std::size_t> live;
    double f = 0.0;
    AdVector mu, w, cw;  // cosine, dmu weight, flux weight per live channel
    AdMatrix same, opposite;
};
const std::shared_ptr<const AdCache::Entry>& cached_redistribution(const AdChannels& c, double n, const PhaseFunction& phase, AdCache& cache);
// The same from the phase function's Legendre moments chi_0, chi_1, ... (redistribution_moment_count of them), e.g. a
// mixture of tabulated phases (moments are linear in the distribution).
std::size_t redistribution_moment_count(const AdChannels& c, double n);
const std::shared_ptr<const AdCache::Entry>& cached_redistribution(const AdChannels& c, double n, const std::vector<double>& moments, AdCache& cache);

// The media of a stack: what the channels and the interfaces are built from.
struct AdStackShape {
    double above_refractive_index = 1.0;
    std::vector<double> layer_indices;
    std::vector<bool> absorbing;  // per layer: false gives exactly A = 0
    bool bottom_reflector = false;
    double below_refractive_index = 1.0;
    // Per layer (empty: none): neither absorbs nor scatters (a glass slide). Such a layer between two interfaces is
    // added with them into one diagonal interface (exact): kept as a layer, the channels it traps by total internal
    // reflection on both sides (s between its neighbours' indices and its own) never lose flux, and adding divided
    // by zero there (NaN for a slide of index 1.5 between air and a sample of 1.4).
    std::vector<bool> transparent;
    double bottom_reflectance = 1.0;  // the reflector's (1: BioSpec's ideal one; the hypodermis' below 1)
};

// Layer k's element for the channels, given the collimated beam's cosine in it (1 for diffuse incidence).
using AdLayerMaker = std::function<AdElement(const AdChannels& channels, std::size_t layer, double beam_cosine)>;

// The stack solved with `options.channels` channels per hemisphere (and twice as many for the accuracy check):
// interfaces between the media, make_layer's layers, the reflector or the exit at the bottom.
AdResult solve_stack(const AdStackShape& shape, const AdIncidence& incidence, const AdOptions& options, const AdLayerMaker& make_layer);

}  // namespace skinspec
