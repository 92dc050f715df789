#include <catch2/catch.hpp>

#include "appearance/lut_export.hpp"
#include "inverse/image_fit/lut_from_chart.hpp"
#include "inverse/image_fit/pixel_fit.hpp"

using namespace skinspec;

namespace {

SwatchRequest chart_request(const ParameterSweep& u, const ParameterSweep& v) {
    SwatchRequest r;
    r.material = "biospec-moderately";
    r.solver = "biospec-adding-doubling";
    r.geometry = MeasurementGeometry::sce;
    r.delta_e = 1.0;
    r.switches.quadrature_channels = 8;
    r.sweeps = {u, v};
    return r;
}

}  // namespace

TEST_CASE("skin albedo made by the exact model between the table's nodes is fitted back within 5 percent", "[lut_from_chart]") {
    // The table at fit-image's default 24 x 16 nodes; the "image": the model solved at other values (between the nodes), not interpolated.
    const auto u = lut_axis(lut_melanin_field, "0.005:0.45:24:log", "--melanin"), v = lut_axis(lut_blood_field, "0.001:0.1:16:log", "--blood");
    const auto table = compute_swatch(chart_request(u, v));
    const auto& cm = ColorManagement::builtin();
    const auto lut = rgb_albedo_lut(table, u, v, "Linear Rec.709", cm);
    const auto tu = lut_axis(lut_melanin_field, "0.012:0.3:4:log", "--melanin"), tv = lut_axis(lut_blood_field, "0.003:0.06:3:log", "--blood");
    const auto truth = compute_swatch(chart_request(tu, tv));
    std::vector<float> image;
    for (const auto& p : truth.patches) {
        for (const double c : cm.from_xyz(p.xyz, truth.white, "Linear Rec.709")) image.push_back(static_cast<float>(c));
    }
    PixelFitSettings settings;
    settings.noise = 0.002;
    const auto fit = fit_image_pixels(lut, image, 4, 3, settings);
    for (std::size_t i = 0; i < fit.pixels.size(); ++i) {
        const auto& p = fit.pixels[i];
        CHECK(p.status == PixelStatus::fitted);
        CHECK(p.u_value == Approx(truth.patches[i].parameters[0]).epsilon(0.05));
        CHECK(p.v_value == Approx(truth.patches[i].parameters[1]).epsilon(0.05));
    }
}

TEST_CASE("a multispectral table holds each band's reflectance factor of the nodes' spectra", "[lut_from_chart]") {
    const auto u = lut_axis(lut_melanin_field, "0.01:0.2:3:log", "--melanin"), v = lut_axis(lut_blood_field, "0.002:0.05:2:log", "--blood");
    const auto chart = compute_swatch(chart_request(u, v));
    BandSensitivities bands{{"flat", "green"}, {380.0, 530.0, 540.0, 560.0, 570.0, 780.0}, {{1, 1, 1, 1, 1, 1}, {0, 0, 1, 1, 0, 0}}};
    const auto lut = band_albedo_lut(chart, u, v, bands);
    CHECK(lut.channels() == std::vector<std::string>{"flat", "green"});
    const auto& nm = chart.wavelengths.nm();
    for (std::size_t i = 0; i < chart.patches.size(); ++i) {
        const auto& r = chart.patches[i].reflectance;
        double mean = 0.0;
        for (const double x : r) mean += x / static_cast<double>(r.size());
        CHECK(lut.node(i % 3, i / 3, 0) == Approx(mean).epsilon(1e-12));
        // The green band is the mean of R at 540-560 nm (weights of its trapezoid on the 10 nm grid: 530 and 570 nm get
        // none, 540, 550, 560 nm equal).
        double green = 0.0;
        for (std::size_t w = 0; w < nm.size(); ++w) {
            if (nm[w] >= 540.0 && nm[w] <= 560.0) green += r[w] / 3.0;
        }
        CHECK(lut.node(i % 3, i / 3, 1) == Approx(green).epsilon(1e-12));
        INFO(i);
    }
}
