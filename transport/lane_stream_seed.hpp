#pragma once
// Seeding a SIMD packet lane's xoshiro128+ stream (simd_lanes-inl.h) from a ray's 64-bit key.
#include <cstddef>
#include <cstdint>

namespace skinspec {

// SplitMix64 (Steele, Lea & Flood 2014) of the key: two 64-bit outputs make the four 32-bit words of lane `lane`
// in rng[word][lane] (never the all-zero state).
template <std::size_t Lanes>
void seed_lane_stream(std::uint32_t (&rng)[4][Lanes], std::size_t lane, std::uint64_t key) {
    const auto next = [&key] {
        std::uint64_t z = (key += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    const std::uint64_t a = next();
    const std::uint64_t b = next();
    rng[0][lane] = static_cast<std::uint32_t>(a);
    rng[1][lane] = static_cast<std::uint32_t>(a >> 32);
    rng[2][lane] = static_cast<std::uint32_t>(b);
    rng[3][lane] = static_cast<std::uint32_t>(b >> 32);
    if ((a | b) == 0) rng[0][lane] = 1;
}

}  // namespace skinspec
