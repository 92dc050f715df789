#pragma once
// One wavelength of the BioSpec walk (Krishnaswamy & Baranoski 2004, as docs/BIOSPEC.md "One ray" describes it):
// directions only, every layer crossed as a whole, per-crossing scattering
// (measured profile / Rayleigh + cosine / cosine / HG), absorption per crossing, Fresnel at every
// interface, skin-fold perturbation of surface reflection, Lambertian bottom reflector or exit.
//
// Absorption replay (Alerstam et al. 2008's "white Monte Carlo" for this walk): with the weighted estimator a
// ray's path does not depend on absorption, so one traced path serves several absorption sets (stacks that
// differ only in absorbers): the ray keeps its path length L_k in each layer, set s's optical depth is
// tau_s = sum_k mu_a,s,k L_k and its weight w_s = b_s exp(-tau_s) (b_s its roulette boosts), all sets at once in
// vector operations at exits and roulette looks, so a crossing costs the same for one set or hundreds. Each ray has
// its own random stream, and Russian roulette (looked at every 8 crossings, once a bound on every set's depth says
// some set may be due) draws a number keyed by (ray, event) shared by all sets, so a set's numbers equal those of
// its own run to rounding.
//
// Path recording (white Monte Carlo proper, for fitting): the walk traced without absorption keeps, for every ray
// that leaves the top into the measurement geometry, its path length in each layer, so that R for any absorption
// is the mean of exp(-sum_k mu_a,k L_k) over the recorded rays (ExitPaths::reflectance), a smooth function of mu_a.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "transport/biospec/biospec_options.hpp"
#include "transport/biospec/biospec_packet.hpp"
#include "transport/biospec/exit_paths.hpp"
#include "transport/direction.hpp"
#include "materials/measured_profile.hpp"
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
    int truncated = -1;  // 1 for a ray stopped at the event limit (always present)
    std::size_t count = 0;  // channels of one absorption set; set s uses [s * count, (s + 1) * count)

    BiospecChannels(const Quantities& quantities, std::size_t layers, std::size_t angular_bins);
};

class BiospecWavelength {
public:
    // `sets` share everything but their absorbers (InputError naming the first difference otherwise); one set
    // with the random estimator.
    BiospecWavelength(const std::vector<const LayerStack*>& sets, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                      const BiospecOptions& options, const BiospecChannels& channels, std::vector<double> angular_bin_edges_deg);
    // For path recording: the geometry and scattering of `stack`, absorption ignored; or, with `floor_per_cm` (one per
    // layer), absorbed at that floor by the random estimator's per-crossing test, so that the exits recorded are those
    // ExitPaths::thin at that floor keeps (the recorded paths say so: thinned_at_per_cm), traced no further than that
    // absorption lets them.
    BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                      const BiospecOptions& options, std::vector<double> floor_per_cm = {});
    // The sets' absorption coefficients at `wavelength_nm`, [set * layers + layer] (InputError naming a layer whose
    // absorbers give a value that is not finite).
    static std::vector<double> sets_absorption_per_cm(const std::vector<const LayerStack*>& sets, double wavelength_nm);
    BiospecWavelength(const BiospecWavelength&) = delete;
    BiospecWavelength& operator=(const BiospecWavelength&) = delete;

    void trace(RandomStream& random, std::uint64_t rays, RayTally& tally) const;
    // Path recording (the path-recording constructor only): appends this batch's exits to `paths`.
    void record(RandomStream& random, std::uint64_t rays, ExitPaths& paths) const;

private:
    // The geometry and scattering of `stack`, with its absorption as the one set.
    BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                      const BiospecOptions& options, const BiospecChannels& channels, std::vector<double> angular_bin_edges_deg);

    struct Lanes;
    // Traces `rays` rays in packets: into `tally`, or (recording) their exits into `paths`.
    void walk(RandomStream& random, std::uint64_t rays, RayTally& tally, ExitPaths* paths) const;
    // Step 1 for a new ray in `lane`: false when it ends at the surface (tallied), else the lane is set walking.
    bool enter(std::size_t lane, std::uint64_t key, Lanes& lanes, RayTally& tally, ExitPaths* paths) const;
    // What the packet step flagged in `lane`: absorptance, roulette, an end. True when the ray has ended.
    bool settle(std::size_t lane, Lanes& lanes, RayTally& tally, ExitPaths* paths) const;
    void leave_top(std::size_t lane, double cos_exit, Lanes& lanes, RayTally& tally, ExitPaths* paths) const;
    // A ray of set `set` leaving with |cos| = cos_exit: `value` into `channel`, `bin_value` into its angular bin
    // from `first_bin` (either channel -1: not requested).
    void tally_exit(RayTally& tally, std::size_t set, int channel, double value, int first_bin, double cos_exit, double bin_value) const;
    void finish_model();
    // The absorption sets, mu_a_per_cm[set * layers + layer]: the table the exits and the roulette weigh by.
    void set_absorption(const std::vector<double>& mu_a_per_cm);
    std::size_t exit_bin(double cos_exit) const;
    // What a ray leaving the top with |cos| = cos_exit adds to R per unit weight in the geometry (0 outside it).
    double geometry_factor(double cos_exit, bool first_surface) const;

    BiospecPacketModel packet_;        // the per-layer constants of the packet step
    std::size_t layers_ = 0;
    double n_top_ = 1.0;
    double entry_reflectance_ = 0.0;  // Fresnel of the incident beam at the top (step 1), the same for every ray
    Direction entry_direction_;       // the refracted beam
    std::size_t sets_ = 1;
    std::size_t set_stride_ = widest_double_vector;  // sets rounded up to whole vectors of doubles
    std::vector<double> set_mu_a_per_cm_;            // [layer * set_stride_ + set]
    struct ProfileArena;
    // The measured profiles' tables at their tabulated wavelengths, for every wavelength and walk (per entry count).
    static std::shared_ptr<const ProfileArena> profile_arena(std::size_t entries);
    std::shared_ptr<const ProfileArena> arena_;
    double n_above_;
    double n_below_;
    bool reflector_;
    double reflector_reflectance_;  // 1 for BioSpec's ideal reflector, the measured hypodermis' below 1
    double fold_sigma_;
    ModelOptions model_;
    MeasurementGeometry geometry_;
    double band_cos_lo_ = 0.0, band_cos_hi_ = 1.0, band_factor_ = 1.0;  // 0/45 acceptance
    bool recording_ = false;
    std::vector<double> floor_per_cm_;  // recording at a floor absorption (empty: none)
    Direction incident_;
    BiospecOptions options_;
    BiospecChannels channels_;
    std::vector<double> bin_edges_cos_;  // cos of the bin edges, decreasing
};

}  // namespace skinspec
