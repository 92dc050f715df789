#pragma once
// The recorded exits of one wavelength of the BioSpec walk's path recording (transport/biospec/biospec_walk.hpp):
// per ray that left the top into the measurement geometry (first-surface reflections apart), its path length in
// each layer; the volumetric walk's exit replay records its exits the same way (rte_solver.cpp). R for any
// absorption is then the mean over the traced rays of exp(-sum_k mu_a,k L_k) (white Monte Carlo, Alerstam et al.
// 2008, J. Biomed. Opt. 13:060504), a smooth function of mu_a.
#include <cstdint>
#include <vector>

#include "transport/spectral_request.hpp"

namespace skinspec {

struct ExitPaths {
    std::uint64_t rays = 0;           // rays traced
    std::uint64_t surface_exits = 0;  // first-surface reflections into the geometry (no path in the skin)
    std::uint64_t surface_reflections = 0;  // every first-surface reflection leaving the top (the specular reflectance's)
    std::uint64_t truncated_rays = 0;       // rays stopped at the event limit (not recorded)
    double factor = 1.0;              // each exit's contribution (1, or 1 / band for 0/45)
    std::vector<std::vector<float>> layer_path_cm;  // [layer][exit], layer-major so that re-weighting vectorises
    // After thin(): the effective absorption per layer [1/cm] the kept exits survived (empty: every exit kept).
    std::vector<double> thinned_at_per_cm;

    void resize_layers(std::size_t layers) { layer_path_cm.resize(layers); }
    std::size_t layers() const { return layer_path_cm.size(); }
    std::size_t exits() const { return layer_path_cm.empty() ? 0 : layer_path_cm.front().size(); }
    void add_exit(const std::vector<double>& path_cm_per_layer) {
        for (std::size_t k = 0; k < layer_path_cm.size(); ++k) layer_path_cm[k].push_back(static_cast<float>(path_cm_per_layer[k]));
    }
    void append(const ExitPaths& other);
    // Analog absorption at a floor (Russian roulette on the recorded exits): each exit is kept with probability
    // exp(-sum_k m_k L_k), m_k = floor_per_cm[k] >= 0, and re-weighting then applies only the absorption above the
    // floor, exp(-sum_k (mu_a,k scale_k - m_k) L_k): the same expectation for every absorption (unbiased for any
    // floor; with the floor below every absorption asked for, each weight stays <= 1). The exits a fit can only
    // weigh little (long paths) go, and with them most of its memory traffic. Draws from `seed` in exit order:
    // reproducible, independent of threads. Once per ExitPaths.
    void thin(const std::vector<double>& floor_per_cm, std::uint64_t seed);
    // Over the rays, the sums of the weights exp(-sum_k (mu_a,k scale_k - m_k) L_k) of the exits (each first-surface
    // exit 1) and of their squares, before `factor` (m_k: thinned_at_per_cm, or 0): what a tally of R takes.
    struct WeightSums {
        double sum = 0.0, sum_of_squares = 0.0;
    };
    WeightSums weight_sums(const std::vector<double>& mu_a_per_cm, const std::vector<double>& path_scale) const;
    // Each exit's weight exp(-sum_k (mu_a,k - m_k) L_k) (m_k as above) into `out`, one per exit, in float (relative
    // error ~1e-6): for tallies that need the exits one by one (the volumetric walk's radial rings, rte_solver.cpp).
    void weights(const std::vector<double>& mu_a_per_cm, std::vector<float>& out) const;
    // R for the absorption coefficients mu_a [1/cm] per layer (scale_k multiplies layer k's paths: a thickness
    // ratio for layers whose paths scale with thickness), and its standard error over the rays. Single precision
    // per exit (relative error ~1e-6, far below the Monte Carlo error), sums in double.
    // With `gradient` (one entry per layer) also dR/dm_k, m_k = mu_a,k scale_k (the effective coefficient of the
    // recorded paths): -factor / N sum over exits of L_k exp(-tau), accumulated in the same pass, for the layers
    // flagged in `gradient_layers` (empty: every layer; the others' entries are 0).
    Estimate reflectance(const std::vector<double>& mu_a_per_cm, const std::vector<double>& path_scale,
                         std::vector<double>* gradient = nullptr, const std::vector<bool>& gradient_layers = {}) const;
};

}  // namespace skinspec
