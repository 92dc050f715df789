#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "inverse/image_fit/pixel_fit.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;

namespace {

const ParameterSweep melanin{"epidermis.melanosome_fraction", 0.01, 0.4, 24, true};
const ParameterSweep blood{"dermis.blood_fraction", 0.002, 0.08, 16, true};

// A smooth skin-like albedo (more melanin darkens blue most, more blood darkens green most): the reference the
// table samples and the pixels are made from, independent of the table's interpolation.
std::array<double, 3> albedo(double m, double b) {
    return {0.55 * std::exp(-1.5 * m - 2.0 * b), 0.45 * std::exp(-3.0 * m - 12.0 * b), 0.40 * std::exp(-5.0 * m - 6.0 * b)};
}

AlbedoLut table() {
    std::vector<double> values;
    for (const double b : blood.values()) {
        for (const double m : melanin.values()) {
            const auto c = albedo(m, b);
            values.insert(values.end(), c.begin(), c.end());
        }
    }
    return AlbedoLut(melanin, blood, {"R", "G", "B"}, values);
}

void add_pixel(std::vector<float>& image, const std::array<double, 3>& c) {
    for (const double x : c) image.push_back(static_cast<float>(x));
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

TEST_CASE("noiseless pixels between the nodes give back their fields", "[pixel_fit]") {
    const auto lut = table();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> lm(std::log(0.012), std::log(0.38)), lb(std::log(0.0025), std::log(0.075));
    std::vector<std::array<double, 2>> truth;
    std::vector<float> image;
    for (int i = 0; i < 200; ++i) {
        truth.push_back({std::exp(lm(rng)), std::exp(lb(rng))});
        add_pixel(image, albedo(truth.back()[0], truth.back()[1]));
    }
    PixelFitSettings settings;
    settings.noise = 0.002;
    const auto fit = fit_image_pixels(lut, image, 20, 10, settings);
    REQUIRE(fit.pixels.size() == 200);
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const auto& p = fit.pixels[i];
        CHECK(p.status == PixelStatus::fitted);
        // The table's interpolation error only (values within 2e-4, far below an image's noise): well inside the 5 % a
        // round trip is asked for, largest where the colour changes least with the field (little blood).
        CHECK(p.u_value == Approx(truth[i][0]).epsilon(0.01));
        CHECK(p.v_value == Approx(truth[i][1]).epsilon(0.025));
        CHECK(p.residual < 2e-4);
    }
}

TEST_CASE("the stated uncertainties and the estimated noise match the spread of noisy fits", "[pixel_fit]") {
    const auto lut = table();
    const double sigma = 0.003, m = 0.06, b = 0.012;
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<float> image;
    const auto c = albedo(m, b);
    for (int i = 0; i < 2000; ++i) add_pixel(image, {c[0] + noise(rng), c[1] + noise(rng), c[2] + noise(rng)});
    const auto fit = fit_image_pixels(lut, image, 50, 40, PixelFitSettings{});
    CHECK(fit.noise_estimated);
    CHECK(fit.noise == Approx(sigma).epsilon(0.1));
    std::vector<double> us, vs, su, sv;
    for (const auto& p : fit.pixels) {
        us.push_back(p.u_value);
        vs.push_back(p.v_value);
        su.push_back(p.u_stderr);
        sv.push_back(p.v_stderr);
    }
    const auto spread = [](const std::vector<double>& x) {
        double mean = 0.0, var = 0.0;
        for (const double v : x) mean += v / static_cast<double>(x.size());
        for (const double v : x) var += (v - mean) * (v - mean) / static_cast<double>(x.size() - 1);
        return std::sqrt(var);
    };
    // Linear propagation against the brute-force spread of the fitted values (2000 noisy pixels).
    CHECK(median(su) == Approx(spread(us)).epsilon(0.15));
    CHECK(median(sv) == Approx(spread(vs)).epsilon(0.15));
    CHECK(median(us) == Approx(m).epsilon(0.02));
    CHECK(median(vs) == Approx(b).epsilon(0.05));
    // About 1 in 16,000 pixels of pure noise lies beyond 4 sigma with one degree of freedom.
    CHECK(fit.count(PixelStatus::fitted) >= 1995);
}

TEST_CASE("what the model cannot explain is flagged and not forced", "[pixel_fit]") {
    const auto lut = table();
    std::vector<float> image;
    add_pixel(image, albedo(0.05, 0.01));    // skin
    add_pixel(image, {0.1, 0.1, 0.8});       // blue: no skin
    add_pixel(image, albedo(0.9, 0.01));     // skin beyond the table's melanin
    add_pixel(image, {0.2, NAN, 0.1});       // not a number
    add_pixel(image, {0.2, -0.01, 0.1});     // negative
    add_pixel(image, {0.0, 0.0, 0.0});       // black
    PixelFitSettings settings;
    settings.noise = 0.002;
    const auto fit = fit_image_pixels(lut, image, 6, 1, settings);
    CHECK(fit.pixels[0].status == PixelStatus::fitted);
    CHECK(fit.pixels[1].status == PixelStatus::outside_gamut);
    CHECK(fit.pixels[2].status != PixelStatus::fitted);
    CHECK(fit.pixels[2].u_value == Approx(0.4));
    for (std::size_t i = 3; i < 6; ++i) {
        CHECK(fit.pixels[i].status == PixelStatus::invalid);
        CHECK(fit.pixels[i].u_value == 0.0);
    }
    for (const auto& p : fit.pixels) {
        CHECK(std::isfinite(p.u_value));
        CHECK(std::isfinite(p.u_stderr));
        CHECK(std::isfinite(p.residual));
    }
}

TEST_CASE("a stopped fit returns its pixels not fitted", "[pixel_fit]") {
    const auto lut = table();
    std::vector<float> image;
    for (int i = 0; i < 12; ++i) add_pixel(image, albedo(0.05, 0.01));
    CancelFlag cancel{true};
    PixelFitSettings settings;
    settings.noise = 0.002;
    settings.cancel = &cancel;
    const auto fit = fit_image_pixels(lut, image, 4, 3, settings);
    CHECK(fit.partial);
    CHECK(fit.count(PixelStatus::not_fitted) == 12);
}

TEST_CASE("bad fit settings and images are refused with the value", "[pixel_fit]") {
    const auto lut = table();
    std::vector<float> image;
    add_pixel(image, albedo(0.05, 0.01));
    PixelFitSettings settings;
    CHECK_THROWS_WITH(fit_image_pixels(lut, image, 2, 1, settings), Catch::Contains("3 values for 2 x 1 pixels of 3 channels"));
    settings.noise = -1.0;
    CHECK_THROWS_WITH(fit_image_pixels(lut, image, 1, 1, settings), Catch::Contains("--noise -1 is outside (0, inf)"));
    settings.noise = 0.01;
    settings.gamut_sigma = 0.0;
    CHECK_THROWS_WITH(fit_image_pixels(lut, image, 1, 1, settings), Catch::Contains("--gamut-sigma 0 is outside (0, inf)"));
    const AlbedoLut two(melanin, blood, {"a", "b"}, std::vector<double>(24 * 16 * 2, 0.3));
    CHECK_THROWS_WITH(fit_image_pixels(two, {0.3f, 0.3f}, 1, 1, PixelFitSettings{}), Catch::Contains("give it"));
}

TEST_CASE("edits re-render the fitted pixels by the model's ratio and leave those they would take off the table", "[pixel_fit]") {
    const auto lut = table();
    std::vector<float> image;
    add_pixel(image, albedo(0.08, 0.01));
    add_pixel(image, {0.1, 0.1, 0.8});
    PixelFitSettings settings;
    settings.noise = 0.002;
    const auto fit = fit_image_pixels(lut, image, 2, 1, settings);
    const auto half = parse_field_edit("epidermis.melanosome_fraction=*0.5", melanin.field, blood.field);
    const auto set = parse_field_edit("dermis.blood_fraction=0.03", melanin.field, blood.field);
    const auto edited = edited_values(lut, fit, image, {half, set});
    const auto expected = albedo(0.04, 0.03);
    for (std::size_t c = 0; c < 3; ++c) CHECK(edited.values[c] == Approx(expected[c]).epsilon(0.002));
    for (std::size_t c = 3; c < 6; ++c) CHECK(edited.values[c] == image[c]);  // not skin: unchanged
    CHECK(edited.rendered == 1);
    CHECK(edited.beyond_table == 0);
    // Ten times the melanin is beyond the table: the pixel is left as it was, and counted.
    const auto beyond = edited_values(lut, fit, image, {parse_field_edit("epidermis.melanosome_fraction=*10", melanin.field, blood.field)});
    CHECK(beyond.values == image);
    CHECK(beyond.rendered == 0);
    CHECK(beyond.beyond_table == 1);
    CHECK_THROWS_WITH(parse_field_edit("epidermis.melanin=*2", melanin.field, blood.field), Catch::Contains("FIELD epidermis.melanosome_fraction or dermis.blood_fraction"));
    CHECK_THROWS_WITH(parse_field_edit("dermis.blood_fraction=*-1", melanin.field, blood.field), Catch::Contains("'-1' is not a number in (0, inf)"));
    CHECK_THROWS_WITH(parse_field_edit("dermis.blood_fraction=x", melanin.field, blood.field), Catch::Contains("'x' is not a number"));
}
