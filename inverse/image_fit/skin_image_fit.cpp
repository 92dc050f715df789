#include "inverse/image_fit/skin_image_fit.hpp"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "appearance/lut_export.hpp"
#include "inverse/image_fit/lut_from_chart.hpp"
#include "skinspec/version.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/memory_budget.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

std::size_t channel_count(const SkinImageRequest& request) { return request.bands ? request.bands->names.size() : 3; }

double white_of(const SkinImageRequest& request, std::size_t channel) { return request.white[request.white.size() == 1 ? 0 : channel]; }

// The 25th, 50th and 75th percentiles of `values` (empty: zeros).
std::array<double, 3> quartiles(std::vector<double> values) {
    if (values.empty()) return {0.0, 0.0, 0.0};
    std::sort(values.begin(), values.end());
    const auto at = [&](double q) { return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5)]; };
    return {at(0.25), at(0.5), at(0.75)};
}

constexpr const char* status_legend = "0 fitted, 1 outside the model's gamut, 2 on the table's edge, 3 invalid pixel, 4 not fitted (stopped)";

}  // namespace

void check_skin_image_request(const SkinImageRequest& request) {
    if (request.table.sweeps.size() != 2) throw std::logic_error("fit-image: the table needs two sweeps");
    check_pixel_fit_settings(request.fit, channel_count(request));
    const auto k = channel_count(request);
    if (request.white.size() != 1 && request.white.size() != k) {
        throw InputError("--white: " + std::to_string(request.white.size()) + " values; give one, or one per channel (" + std::to_string(k) + ")");
    }
    for (const double w : request.white) {
        if (!(std::isfinite(w) && w > 0.0)) throw InputError("--white " + format_number(w) + " is outside (0, inf)");
    }
    if (!request.bands) space_chromaticities(ColorManagement::builtin().canonical_space(request.space, "--space"));
}

SkinImage read_skin_image(const std::filesystem::path& file, const SkinImageRequest& request) {
    check_skin_image_request(request);
    SkinImage out;
    auto image = read_data_image(file);
    out.stated = stated_image_settings(image, file.string());
    if (request.bands) {
        if (static_cast<std::size_t>(image.channels) != request.bands->names.size()) {
            throw InputError(file.string() + ": " + std::to_string(image.channels) + " channels, but the band sensitivities describe " +
                             std::to_string(request.bands->names.size()) + " bands");
        }
        out.width = image.width;
        out.height = image.height;
        out.values = std::move(image.values);
    } else {
        auto rgb = linear_image(image, ColorManagement::builtin().canonical_space(request.space, "--space"), ColorManagement::builtin());
        out.width = rgb.width;
        out.height = rgb.height;
        out.values = std::move(rgb.rgb);
    }
    return out;
}

SkinImageFit fit_skin_image(const SkinImageRequest& request, const SkinImage& image) {
    check_skin_image_request(request);
    check_image_size(image.values.size(), image.width, image.height, channel_count(request));
    // Before the table: the fit and its edit, the albedo copy, the maps (six floats) and the writer's copy of them.
    const double pixels = static_cast<double>(image.width) * image.height;
    check_memory(pixels * (pixel_fit_bytes_per_pixel(channel_count(request)) + static_cast<double>((channel_count(request) + 12) * sizeof(float))),
                 fmt::format("fitting an image of {} x {} pixels", image.width, image.height), "fit a crop of it, or a smaller copy");
    const auto start = std::chrono::steady_clock::now();
    const auto since_start = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    SkinImageFit out;
    const auto chart = compute_swatch(request.table);
    out.table_nodes = chart.patches.size();
    out.table_settings = chart.settings;
    out.warnings = chart.warnings;
    for (const auto& p : chart.patches) out.worst_delta_e = std::max(out.worst_delta_e, p.uncertainty.delta_e2000);
    out.table_seconds = since_start();
    if (chart.partial) {
        out.table_partial = true;
        out.seconds = out.table_seconds;
        return out;
    }
    const auto& u = request.table.sweeps[0];
    const auto& v = request.table.sweeps[1];
    out.lut = std::make_shared<const AlbedoLut>(request.bands ? band_albedo_lut(chart, u, v, *request.bands)
                                                              : rgb_albedo_lut(chart, u, v, request.space, ColorManagement::builtin()));
    // The values as albedo (white = 1), and the edited image back in the image's units.
    const std::size_t k = channel_count(request);
    auto albedo = image.values;
    for (std::size_t i = 0; i < albedo.size(); ++i) albedo[i] = static_cast<float>(albedo[i] / white_of(request, i % k));
    out.fit = fit_image_pixels(*out.lut, albedo, image.width, image.height, request.fit);
    if (!request.edits.empty() && !out.fit.partial) {
        out.edited = edited_values(*out.lut, out.fit, albedo, request.edits);
        for (std::size_t i = 0; i < out.edited->values.size(); ++i) out.edited->values[i] = static_cast<float>(out.edited->values[i] * white_of(request, i % k));
    }
    out.seconds = since_start();
    return out;
}

DataImage skin_image_maps(const SkinImageFit& result) {
    const auto& lut = *result.lut;
    DataImage image;
    image.width = result.fit.width;
    image.height = result.fit.height;
    image.floating_point = true;
    image.channel_names = {lut.u().field, lut.v().field, lut.u().field + ".stderr", lut.v().field + ".stderr", "residual", "status"};
    image.channels = static_cast<int>(image.channel_names.size());
    image.values.reserve(result.fit.pixels.size() * image.channel_names.size());
    for (const auto& p : result.fit.pixels) {
        for (const double x : {p.u_value, p.v_value, p.u_stderr, p.v_stderr, p.residual, static_cast<double>(p.status)}) {
            image.values.push_back(static_cast<float>(x));
        }
    }
    return image;
}

ImageMetadata skin_image_metadata(const SkinImageFit& result, const SkinImageRequest& request, const std::string& image_name) {
    const auto& u = request.table.sweeps[0];
    const auto& v = request.table.sweeps[1];
    ImageMetadata metadata{
        {"Software", std::string("skinspec ") + version},
        {"skinspec:content", std::string("fitted skin fields per pixel, their standard uncertainties, the RMS residual (image units, white = 1) and "
                                         "the status (") + status_legend + ")"},
        {"skinspec:image", image_name},
        {"skinspec:channels", request.bands ? "bands " + fmt::format("{}", fmt::join(request.bands->names, ",")) : "linear RGB in " + request.space},
        {"skinspec:white", fmt::format("{}", fmt::join(request.white, ","))},
        {"skinspec:material", request.table.material},
        {"skinspec:model", request.table.solver},
        {"skinspec:geometry", std::string(to_string(request.table.geometry))},
        {"skinspec:u_field", u.field},
        {"skinspec:u_values", value_list(u)},
        {"skinspec:v_field", v.field},
        {"skinspec:v_values", value_list(v)},
        {"skinspec:noise", format_number(result.fit.noise)},
        {"skinspec:noise_estimated", result.fit.noise_estimated ? "true" : "false"},
        {"skinspec:gamut_sigma", format_number(request.fit.gamut_sigma)},
        {"skinspec:table_worst_delta_e_uncertainty", fmt::format("{:.4g}", result.worst_delta_e)},
        {"skinspec:partial", result.partial() ? "true" : "false"}};
    for (const auto& ov : request.table.overrides) metadata.push_back({"skinspec:set " + ov.key, ov.value});
    for (const auto& [key, value] : result.table_settings) {
        metadata.push_back({"skinspec:" + key, std::visit([](const auto& x) { return fmt::format("{}", x); }, value)});
    }
    return metadata;
}

nlohmann::ordered_json skin_image_summary_json(const SkinImageFit& result, const SkinImageRequest& request, const std::string& image_name) {
    const auto& fit = result.fit;
    nlohmann::ordered_json counts;
    for (const auto s : {PixelStatus::fitted, PixelStatus::outside_gamut, PixelStatus::outside_range, PixelStatus::invalid, PixelStatus::not_fitted}) {
        counts[std::string(to_string(s))] = fit.count(s);
    }
    std::vector<double> us, vs, u_errors, v_errors, residuals;
    for (const auto& p : fit.pixels) {
        if (p.status != PixelStatus::fitted) continue;
        us.push_back(p.u_value);
        vs.push_back(p.v_value);
        u_errors.push_back(p.u_stderr);
        v_errors.push_back(p.v_stderr);
        residuals.push_back(p.residual);
    }
    const auto field = [](const std::vector<double>& values, const std::vector<double>& errors) {
        const auto q = quartiles(values);
        return nlohmann::ordered_json{{"median", q[1]}, {"p25", q[0]}, {"p75", q[2]}, {"median_stderr", quartiles(errors)[1]}};
    };
    nlohmann::ordered_json channels = request.bands ? request.bands->names : std::vector<std::string>{"R", "G", "B"};
    return {{"skinspec_version", version},
            {"image", image_name},
            {"width", fit.width},
            {"height", fit.height},
            {"channels", channels},
            {"space", request.bands ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(request.space)},
            {"material", request.table.material},
            {"model", request.table.solver},
            {"table_nodes", result.table_nodes},
            {"table_worst_delta_e_uncertainty", result.worst_delta_e},
            {"white", request.white},
            {"noise", fit.noise},
            {"noise_estimated", fit.noise_estimated},
            {"pixels", counts},
            {request.table.sweeps[0].field, field(us, u_errors)},
            {request.table.sweeps[1].field, field(vs, v_errors)},
            {"median_residual", quartiles(residuals)[1]},
            {"edit", result.edited ? nlohmann::ordered_json{{"rendered", result.edited->rendered}, {"beyond_table", result.edited->beyond_table}}
                                   : nlohmann::ordered_json(nullptr)},
            {"partial", result.partial()},
            {"table_seconds", result.table_seconds},
            {"seconds", result.seconds}};
}

StatedImageSettings stated_image_settings(const DataImage& image, const std::string& name) {
    StatedImageSettings out;
    for (const auto& [key, value] : image.metadata) {
        if (key == "skinspec:geometry") out.geometry = parse_measurement_geometry(value, name + ": skinspec:geometry");
        if (key == "colorspace" && image.floating_point) out.space = ColorManagement::builtin().canonical_space(value, name + ": colorspace");
    }
    return out;
}

}  // namespace skinspec
