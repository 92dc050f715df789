#pragma once
// One wavelength of the BioSpec walk (Krishnaswamy & Baranoski 2004, as specified in the shared
// biospec-model.md "One ray"): directions only, every layer crossed as a whole, per-crossing scattering
// (measured profile / Rayleigh + cosine / cosine / HG), absorption per crossing, Fresnel at every
// interface, skin-fold perturbation of surface reflection, Lambertian bottom reflector or exit.
#include <cstdint>
#include <optional>
#include <vector>

#include "transport/biospec/biospec_options.hpp"
#include "transport/direction.hpp"
#include "transport/measured_profile.hpp"
#include "transport/random_stream.hpp"
#include "transport/ray_tally.hpp"
#include "materials/layer_stack.hpp"

namespace skinspec {

// Which tally channel holds which quantity; -1 when not requested.
struct BiospecChannels {
    int reflectance = -1;
    int specular = -1;
    int transmittance = -1;
    int absorptance_surface = -1;
    int absorptance_first_layer = -1;
    int brdf_first_bin = -1;
    int btdf_first_bin = -1;
    std::size_t count = 0;

    BiospecChannels(const Quantities& quantities, std::size_t layers, std::size_t angular_bins);
};

class BiospecWavelength {
public:
    BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, const BiospecOptions& options,
                      const BiospecChannels& channels, std::vector<double> angular_bin_edges_deg);
    BiospecWavelength(const BiospecWavelength&) = delete;
    BiospecWavelength& operator=(const BiospecWavelength&) = delete;

    void trace(RandomStream& random, std::uint64_t rays, RayTally& tally) const;

private:
    struct Layer {
        double thickness_cm;
        double n;
        double mu_a_per_cm;
        double rayleigh_per_cm;
        double hg_g;
        CrossingScattering crossing;
        const InverseCdfTable* profile;
    };

    void trace_one(RandomStream& random, RayScore& score, std::uint64_t& truncated) const;
    Direction scatter(const Layer& layer, const Direction& d, RandomStream& random) const;
    void exit_into_bin(int first_bin, double cos_exit, double weight, RayScore& score) const;

    std::vector<Layer> layers_;
    std::optional<InverseCdfTable> stratum_corneum_table_;
    std::optional<InverseCdfTable> epidermis_table_;
    double n_above_;
    double n_below_;
    bool reflector_;
    double fold_sigma_;
    Direction incident_;
    BiospecOptions options_;
    BiospecChannels channels_;
    std::vector<double> bin_edges_cos_;  // cos of the bin edges, decreasing
};

}  // namespace skinspec
