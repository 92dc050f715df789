#pragma once
// Random numbers for the Monte Carlo solvers: PCG32 (O'Neill 2014, libpcg-cpp) with one independent stream
// per (seed, wavelength, batch), so a given seed gives identical results whatever the thread count or the
// order in which batches run.
#include <bit>
#include <cstdint>

#include <pcg_random.hpp>

namespace skinspec {

class RandomStream {
public:
    // The stream for one batch of rays at one wavelength. The wavelength enters by value, so 550 nm draws the
    // same numbers whatever grid it is part of.
    static RandomStream for_batch(std::uint64_t seed, double wavelength_nm, std::uint64_t batch) {
        const auto wavelength_bits = std::bit_cast<std::uint64_t>(wavelength_nm);
        const std::uint64_t state = mix(mix(seed) ^ mix(wavelength_bits + 0x632be59bd9b4e019ULL) ^ batch);
        const std::uint64_t stream = mix(wavelength_bits ^ mix(batch + 0x9e3779b97f4a7c15ULL));
        return RandomStream(state, stream);
    }

    // Uniform in [0, 1), 32 random bits.
    double uniform() { return static_cast<double>(engine_()) * 0x1.0p-32; }

    // 64 random bits: a ray's key, drawn from its batch's stream (two draws per ray whatever the ray does).
    std::uint64_t bits64() {
        const std::uint64_t hi = engine_();
        return (hi << 32) | engine_();
    }
    // A ray's own stream: its path depends only on (seed, wavelength, batch, ray index), not on how long the
    // rays before it were traced (absorption replay traces a ray as long as any absorption set needs it).
    static RandomStream for_ray(std::uint64_t key) { return RandomStream(mix(key ^ 0x5851f42d4c957f2dULL), mix(key + 0x14057b7ef767814fULL)); }
    // Uniform in [0, 1) from a key and an event index, without state: the same number for every absorption
    // set of a ray at one event (Russian roulette), so each set's decisions equal those of its own run.
    static double keyed_uniform(std::uint64_t key, std::uint64_t event) {
        return static_cast<double>(mix(mix(key) ^ (event * 0x9e3779b97f4a7c15ULL + 0x2545f4914f6cdd1dULL)) >> 11) * 0x1.0p-53;
    }

private:
    RandomStream(std::uint64_t state, std::uint64_t stream) : engine_(state, stream) {}
    // SplitMix64 finaliser (Steele, Lea & Flood 2014): decorrelates nearby seeds.
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    pcg32 engine_;
};

}  // namespace skinspec
