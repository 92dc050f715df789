#pragma once
// The BioSpec walk's inner loop on packets of rays in SIMD lanes (Google Highway, dispatched at run time to the
// widest instruction set of the machine). One call advances every active lane of a packet by one event: the
// crossing's scattering (measured profile table, Henyey-Greenstein, Rayleigh + cosine, cosine; same-hemisphere
// re-draws), the path length the crossing adds in its layer, and the interface the ray then meets
// (bottom reflector, Fresnel reflection or refraction, moving on or leaving). What happens once per ray or rarely
// (entry, exits, Russian roulette, the event limit, tallies) stays with the caller (biospec_walk.cpp), per lane.
//
// Precision: directions, path lengths and optical depths in single precision (relative error ~1e-7 per event, far
// below the Monte Carlo error); weights, tallies and energy bookkeeping in double, by the caller.
// Random numbers: every lane has its own xoshiro128+ stream (Blackman & Vigna 2018, "Scrambled linear pseudorandom
// number generators"), seeded from the ray's key and advanced only when that lane draws, so a ray's path depends on
// its key alone (not on the packet width, the other rays in the packet or the thread).
#include <cstdint>
#include <vector>

#include "materials/model_options.hpp"

namespace skinspec {

// Re-draws of a perturbation that reverses the travel sense (a crossing's, or the fold's at the surface) before the
// unperturbed direction is kept.
inline constexpr int max_redraws = 1000;

// How a layer changes a crossing ray's direction.
enum class PacketScattering : std::int32_t { table = 0, henyey_greenstein = 1, rayleigh_cosine = 2, cosine = 3 };

// What an event did to a lane (BiospecPacket::status).
enum class LaneStatus : std::int32_t {
    walking = 0,      // still in the skin
    left_top = 1,     // left through the top, |cos| in exit_cos (R)
    left_bottom = 2,  // left through the bottom, |cos| in exit_cos (T)
    absorbed = 3,     // random estimator: absorbed in crossing_layer
    truncated = 4,    // reached the event limit in `layer`
};

// The per-wavelength constants of one walk, per layer (index k) in single precision. The per-layer arrays hold
// layer_stride entries (the layers, then zeros), so that a vector load of them never reads past their end.
struct BiospecPacketModel {
    static constexpr std::size_t widest_vector = 16;  // floats in an AVX-512 vector
    std::int32_t layers = 0;
    std::size_t layer_stride = widest_vector;  // a multiple of widest_vector, >= layers
    std::vector<std::int32_t> scattering;    // PacketScattering
    std::vector<std::int32_t> redraw;        // 1: re-draw perturbations that reverse the travel sense; 0: keep them
    // A measured profile is a mixture of two tabulated tables (MeasuredProfile::Mixture): the upper one with
    // probability table_upper_weight. Offsets into table_cos / table_sin.
    std::vector<std::int32_t> table_offset, table_offset_upper;
    std::vector<std::int32_t> table_size;
    std::vector<float> table_upper_weight;
    std::vector<float> thickness_cm, hg_g;
    std::vector<float> turn_mean_free_path_cm;  // 1 / the turn coefficient, Rayleigh + Mie (inf without a turn)
    // n_from / n_to at the interface a downward (upward) crossing meets, and n_to / n_from; with
    // model.swapped_upward_indices the upward ones have the indices swapped (authors' behaviour 1).
    std::vector<float> eta_down, eta_up, inverse_eta_down, inverse_eta_up;
    const float* table_cos = nullptr;  // the measured-profile inverse-CDF tables, concatenated (owned by the walk)
    const float* table_sin = nullptr;
    // Absorption per layer: the first set's (the random estimator's per-crossing test) and the largest of every set's
    // (rounded up), which bounds every set's optical depth (BiospecPacket::depth_bound); without layer_paths, the one
    // set's own, so that depth_bound is its optical depth.
    std::vector<float> mu_a_per_cm, mu_a_bound_per_cm;

    // Sets layer_stride for `layers` and pads every per-layer array to it.
    void pad();
    bool reflector = false;
    // Below 1 (the measured hypodermis), a ray reaching the reflector stays in it (leaves the bottom: T) with
    // probability 1 - reflector_reflectance, a test independent of the absorption sets (so every set shares it).
    float reflector_reflectance = 1.0f;
    bool bottom_exit_fresnel = true;
    bool weighted = true;            // weighted estimator (else the random per-crossing absorption test)
    bool roulette = true;            // flag lanes for Russian roulette (off when recording paths)
    bool flag_every_event = false;   // hand every lane to the caller after every event (per-layer absorptance)
    // Weighted: add each crossing's path to the ray's length in that layer (BiospecPacket::path_cm), which several
    // absorption sets, the per-layer absorptance and path recording need; without it one set's depth is depth_bound.
    bool layer_paths = true;
    RayleighTurn rayleigh_turn = RayleighTurn::sampled_depth;
    std::uint32_t max_events = 0;
    std::uint32_t roulette_every = 8;  // events between two roulette looks (a power of 2)
};

// A packet's lanes in structure-of-arrays form; the caller fills and empties lanes between events.
struct BiospecPacket {
    static constexpr std::size_t lanes = 64;  // a multiple of every target's lane count (AVX-512: 16 floats)
    explicit BiospecPacket(std::size_t layers) : path_cm(layers * lanes, 0.0f) {}

    alignas(64) float dx[lanes] = {}, dy[lanes] = {}, dz[lanes] = {};
    alignas(64) float exit_cos[lanes] = {};
    alignas(64) std::int32_t layer[lanes] = {};
    alignas(64) std::int32_t crossing_layer[lanes] = {};  // the layer of the event's crossing (absorption charged there)
    alignas(64) std::int32_t status[lanes] = {};          // LaneStatus after the event
    alignas(64) std::int32_t active[lanes] = {};          // 1 while the lane holds a ray
    alignas(64) std::int32_t roulette_due[lanes] = {};    // 1 when depth_bound passed look_at at a roulette look
    alignas(64) std::uint32_t event[lanes] = {};          // events so far (the roulette key of the last one is event - 1)
    alignas(64) std::int32_t attempts[lanes] = {};        // same-hemisphere re-draws of the current crossing so far
    alignas(64) std::uint32_t rng[4][lanes] = {};         // xoshiro128+ state
    // The roulette look's screen: depth_bound, the sum over crossings of the model's mu_a_bound_per_cm times the path,
    // grows at least as fast as the optical depth of every set, so no set can pass its roulette depth before
    // depth_bound passes look_at (set by the caller from the sets' margins). Without the model's layer_paths it is the
    // one set's optical depth.
    alignas(64) float depth_bound[lanes] = {};
    alignas(64) float look_at[lanes] = {};
    std::vector<float> path_cm;  // [layer * lanes + lane]: the ray's path length in each layer so far (layer_paths)

    // Seeds lane `lane`'s stream from a ray key (SplitMix64 of the key; never the all-zero state).
    void seed_lane(std::size_t lane, std::uint64_t key);
};

// Advances every active lane by one event; returns the lanes the caller must look at (bit i: lane i), i.e. those
// whose status is not `walking`, that are due for roulette, or all active lanes with flag_every_event.
std::uint64_t step_biospec_packet(const BiospecPacketModel& model, BiospecPacket& packet);

// The name of the instruction set the walk's packets run on here (e.g. "AVX3", "AVX2").
const char* biospec_packet_target();

// Doubles in the widest vector a target has (AVX-512); set_stride below is a multiple of it.
inline constexpr std::size_t widest_double_vector = 8;

// One ray's absorption sets at once, vectorised over the sets (arrays of set_stride values; the first `sets` are
// meant, the rest are padding): its optical depths, depth[s] = sum over layers of mu_a_per_cm[k * set_stride + s] *
// path_cm[k]; with `due` (else null), the sets past `limit`, bit s % 64 of due[s / 64]; with `weight` (else null),
// the sets' weights, weight[s] = exp(boost_log[s] - depth[s]) (the set's roulette boosts times Beer-Lambert);
struct SetArrays {
    const double* mu_a_per_cm;
    std::size_t set_stride, sets, layers;
    const double* path_cm;
    const double* limit;
    const double* boost_log;
    double* depth;
    std::uint64_t* due;
    double* weight;
};
void biospec_sets(const SetArrays& a);
// the smallest margin limit[s] - depth[s] (limit +inf for a set that is out).
double biospec_set_margin(std::size_t set_stride, const double* limit, const double* depth);

}  // namespace skinspec
