#include "studies/phase_study/phantom_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

#include "transport/direction.hpp"

namespace skinspec {
namespace {

void lookup(const Texture& t, double u, double v, float out[3]) {
    const double x = std::clamp(u * t.width - 0.5, 0.0, t.width - 1.0);
    const double y = std::clamp(v * t.height - 0.5, 0.0, t.height - 1.0);
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, t.width - 1), y1 = std::min(y0 + 1, t.height - 1);
    const double fx = x - x0, fy = y - y0;
    for (int c = 0; c < 3; ++c) {
        const auto at = [&](int xx, int yy) { return t.rgb[(static_cast<std::size_t>(yy) * t.width + xx) * 3 + c]; };
        out[c] = static_cast<float>((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) + fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1)));
    }
}

}  // namespace

LinearImage render_phantom(const Texture& background, const AngleSampler& sheet, const PhantomView& view) {
    LinearImage out{view.width_px, view.height_px, std::vector<float>(static_cast<std::size_t>(view.width_px) * view.height_px * 3, 0.0f)};
    auto& image = out.rgb;
    constexpr double deg = std::numbers::pi / 180.0;
    tbb::parallel_for(0, view.height_px, [&](int row) {
        auto random = RandomStream::for_batch(view.seed, view.separation, static_cast<std::uint64_t>(row));
        for (int col = 0; col < view.width_px; ++col) {
            double sum[3] = {0, 0, 0};
            for (int s = 0; s < view.samples_per_pixel; ++s) {
                // Position on the sheet (jittered within the pixel), in texture units [0, 1].
                const double u = (col + random.uniform()) / view.width_px;
                const double v = (row + random.uniform()) / view.height_px;
                const double theta = sheet(random);
                if (theta >= 90.0) continue;
                const auto azimuth = sample_azimuth(random);
                const double offset = view.separation * std::tan(theta * deg) / view.background_width;
                float c[3];
                lookup(background, u + offset * azimuth.cos_phi, v + offset * azimuth.sin_phi, c);
                for (int k = 0; k < 3; ++k) sum[k] += c[k];
            }
            for (int k = 0; k < 3; ++k) {
                image[(static_cast<std::size_t>(row) * view.width_px + col) * 3 + k] = static_cast<float>(sum[k] / view.samples_per_pixel);
            }
        }
    });
    return out;
}

}  // namespace skinspec
