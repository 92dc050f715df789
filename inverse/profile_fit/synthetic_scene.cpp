#include "inverse/profile_fit/synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/random_stream.hpp"

namespace skinspec {

PlanarScene synthetic_planar_scene(const SyntheticSceneSpec& spec) {
    PlanarScene s;
    s.width = spec.width;
    s.height = spec.height;
    s.pitch_mm = spec.pitch_mm;
    const auto n = static_cast<std::size_t>(spec.width) * spec.height;
    s.incident.resize(n);
    s.valid.assign(n, 1);
    const double w_mm = spec.width * spec.pitch_mm, h_mm = spec.height * spec.pitch_mm;
    for (int y = 0; y < spec.height; ++y) {
        for (int x = 0; x < spec.width; ++x) {
            const double px = (x + 0.5) * spec.pitch_mm, py = (y + 0.5) * spec.pitch_mm;
            const auto spot = [&](double cx, double cy, double sigma) {
                return std::exp(-((px - cx) * (px - cx) + (py - cy) * (py - cy)) / (2.0 * sigma * sigma));
            };
            const double irradiance = 0.1 + 0.3 * px / w_mm + 1.0 * spot(0.35 * w_mm, 0.4 * h_mm, 0.12 * w_mm) +
                                      0.5 * spot(0.75 * w_mm, 0.7 * h_mm, 0.06 * w_mm);
            s.incident[static_cast<std::size_t>(y) * spec.width + x] = irradiance * spec.pitch_mm * spec.pitch_mm;
        }
    }
    const Dipole dipole(spec.medium);
    s.observed = render_planar(s, [&](double d) { return dipole.radial_reflectance(d); });
    if (spec.noise > 0.0) {
        auto rng = RandomStream::for_batch(spec.seed, 0.0, 0);
        for (auto& v : s.observed) {
            // Box-Muller from two uniforms of the project's PCG32 stream.
            const double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
            v *= 1.0 + spec.noise * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
            v = std::max(v, 0.0);  // a negative exitance cannot be observed
        }
    }
    return s;
}

}  // namespace skinspec
