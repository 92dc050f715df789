#include <catch2/catch.hpp>

#include "studies/phase_study/phantom_sheet.hpp"

using namespace skinspec;

namespace {

Texture checker() {
    Texture t{8, 8, std::vector<float>(8 * 8 * 3)};
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) t.rgb[(y * 8 + x) * 3 + c] = ((x + y) % 2) ? 1.0f : 0.0f;
    return t;
}

double contrast(const LinearImage& img) {
    double lo = 1e9, hi = -1e9;
    for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
        lo = std::min<double>(lo, img.rgb[i]);
        hi = std::max<double>(hi, img.rgb[i]);
    }
    return hi - lo;
}

}  // namespace

TEST_CASE("phantom sheets: no deflection shows the background, wider deflection blurs more", "[phantom_sheet]") {
    PhantomView view;
    view.width_px = 32;
    view.height_px = 32;
    view.samples_per_pixel = 16;
    const AngleSampler none = [](RandomStream&) { return 0.0; };
    const auto sharp = render_phantom(checker(), none, view);
    CHECK(contrast(sharp) > 0.9);
    view.separation = 2.0;
    const auto blurred = render_phantom(checker(), hg_angle_sampler(0.8), view);
    CHECK(contrast(blurred) < 0.8 * contrast(sharp));
    // A uniform background stays uniform whatever the sheet does; back-scattered rays see nothing.
    Texture grey{2, 2, std::vector<float>(12, 0.5f)};
    const auto flat = render_phantom(grey, hg_angle_sampler(0.95), view);
    for (const float v : flat.rgb) CHECK(v <= 0.5f + 1e-6f);
    const AngleSampler backwards = [](RandomStream&) { return 120.0; };
    for (const float v : render_phantom(grey, backwards, view).rgb) CHECK(v == 0.0f);
}
