#pragma once
// The volumetric walk's inner loop on packets of photons in SIMD lanes (Google Highway, dispatched at run time to the
// widest instruction set of the machine). One call advances every active lane by one segment: a free path drawn in
// the lane's layer (Wang, Jacques & Zheng 1995, Eq. 3.7; the optical depth left is kept across boundaries, MCML's
// "sleft"), the move, and then either a scattering event (the layer's phase function and a uniform azimuth) or the
// boundary (the Lambertian bottom reflector, Fresnel reflection or refraction, leaving). Weights, absorption, Russian
// roulette, tallies and launches stay with the caller (rte_solver.cpp), per lane in double precision.
//
// Precision: positions, directions and optical depths in single precision (relative error ~1e-7 per segment, far
// below the Monte Carlo error); every weight and tally in double, by the caller.
// Random numbers: every lane has its own xoshiro128+ stream seeded from the photon's key (simd_lanes-inl.h), so a
// photon's path depends on its key alone, not on the packet width, the other photons or the thread.
#include <cstdint>
#include <vector>

namespace skinspec {

// How a layer turns a photon at an interaction.
enum class PacketPhase : std::int32_t { henyey_greenstein = 0, two_term_hg = 1, rayleigh = 2, tabulated = 3, none = 4 };

// What a segment did to a lane (bits of RtePacket::event_bits).
enum RteLaneEvent : std::int32_t {
    rte_interaction = 1,   // the segment ended inside the layer: an interaction at (x, y, z), direction changed
    rte_left_top = 2,      // escaped through the top (|cos| of the escaping ray in exit_cos); kept > 0: split, goes on
    rte_left_bottom = 4,   // escaped through the bottom
    rte_truncated = 8,     // reached the step limit (still in the layer)
};

// Per-layer constants of one walk in single precision, padded to layer_stride entries (the layers, then zeros) so a
// vector load of them never reads past their end.
struct RtePacketModel {
    static constexpr std::size_t widest_vector = 16;  // floats in an AVX-512 vector
    std::int32_t layers = 0;
    std::size_t layer_stride = widest_vector;
    std::vector<std::int32_t> phase;                  // PacketPhase
    std::vector<float> mu_per_cm;                     // the coefficient of the free paths (mu_t, or mu_s in white mode)
    std::vector<float> top_cm, bottom_cm;             // depths of the layer's boundaries
    std::vector<float> g, g2, first_term_weight;      // HG g; two-term HG: g, g2 and the first term's probability
    std::vector<std::int32_t> table_offset, table_size;  // tabulated phase: its inverse-CDF table in table_cos
    // n_from / n_to at the boundary a downward (upward) segment meets, and n_to / n_from.
    std::vector<float> eta_down, eta_up, inverse_eta_down, inverse_eta_up;
    std::vector<float> table_cos;                     // the tabulated phases' inverse-CDF tables, concatenated
    bool reflector = false;                           // Lambertian reflector below the last layer
    float reflector_reflectance = 1.0f;               // below 1 (the hypodermis): a photon stays in it (T) with 1 - this
    bool split = false;                               // outer boundaries: part escapes, the photon goes on (kept)
    bool flag_every_segment = false;                  // hand every lane to the caller after every segment (white)
    bool radius = false;                              // store r_cm (radial grids need it)
    std::uint32_t max_steps = 0;

    // Sets layer_stride for `layers` and pads every per-layer array to it.
    void pad();
};

// A packet's lanes in structure-of-arrays form; the caller fills and empties lanes between segments.
struct RtePacket {
    static constexpr std::size_t lanes = 64;  // a multiple of every target's lane count (AVX-512: 16 floats)
    alignas(64) float x[lanes] = {}, y[lanes] = {}, z[lanes] = {};
    alignas(64) float r_cm[lanes] = {};         // sqrt(x^2 + y^2) after the segment (with model.radius)
    alignas(64) float dx[lanes] = {}, dy[lanes] = {}, dz[lanes] = {};
    alignas(64) float tau_left[lanes] = {};     // optical depth left of the current free path (0: draw a new one)
    alignas(64) float segment_cm[lanes] = {};   // length of the last segment
    alignas(64) float exit_cos[lanes] = {};     // |cos| of an escaping ray
    alignas(64) float kept[lanes] = {};         // split boundaries: the reflected fraction that goes on
    alignas(64) std::int32_t layer[lanes] = {};
    alignas(64) std::int32_t segment_layer[lanes] = {};  // the layer of the last segment (where it deposits)
    alignas(64) std::int32_t event_bits[lanes] = {};     // RteLaneEvent bits of the last segment
    alignas(64) std::int32_t active[lanes] = {};         // 1 while the lane holds a photon
    alignas(64) std::uint32_t steps[lanes] = {};         // segments so far
    alignas(64) std::uint32_t rng[4][lanes] = {};        // xoshiro128+ state

    // A new photon in `lane` at the origin in layer 0, heading (dx, dy, dz), its stream seeded from `key`.
    void launch(std::size_t lane, std::uint64_t key, float dx, float dy, float dz);
};

// Advances every active lane by one segment; returns the lanes the caller must look at (bit i: lane i): those with
// an event bit set, or every active lane with flag_every_segment.
std::uint64_t step_rte_packet(const RtePacketModel& model, RtePacket& packet);

// The name of the instruction set the packets run on here (e.g. "AVX3").
const char* rte_packet_target();

}  // namespace skinspec
