#include "appearance/lit_swatch.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "appearance/profile_shape_report.hpp"
#include "skinspec/version.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/spectral_image.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

PatchGeometry lit_view(double field_mm, int pixels) {
    if (!(field_mm > 0.0 && field_mm <= 1000.0)) throw InputError("--field " + format_number(field_mm) + " mm is outside (0, 1000]");
    return {pixels, pixels, field_mm / pixels};
}

Illumination pattern_lighting(const LinearImage& image, PatchGeometry& view) {
    std::vector<float> irradiance;
    for (std::size_t p = 0; p < image.rgb.size(); p += 3) {
        // Luminance of linear Rec.709 (ITU-R BT.709-6 Table 3 item 3.2).
        irradiance.push_back(0.2126f * image.rgb[p] + 0.7152f * image.rgb[p + 1] + 0.0722f * image.rgb[p + 2]);
    }
    view.height_px = std::max(8, static_cast<int>(std::lround(view.width_px * static_cast<double>(image.height) / image.width)));
    return Illumination::pattern(std::move(irradiance), image.width, image.height);
}

LitSwatch render_lit_swatch(const Material& material, const WavelengthGrid& wavelengths, const Illumination& light, const PatchGeometry& view,
                            const SpectralSolver& solver, const ProfileRequest& settings, MeasurementGeometry geometry, IlluminantKind illuminant,
                            ObserverKind observer,
                            const std::string& space, const std::function<void(std::size_t done, std::size_t total)>& on_progress,
                            const std::atomic<bool>* cancel) {
    LitSwatch out;
    out.patch = render_lit_patch(material, wavelengths, light, view, solver, settings, geometry, on_progress, cancel);
    if (out.patch.partial) return out;
    const auto& cm = ColorManagement::builtin();
    out.bands = std::holds_alternative<HomogeneousMaterial>(material);
    if (out.bands && out.patch.exitance.size() != 3) {
        throw InputError(material_name(material) + ": a lit swatch of a band material needs exactly three bands (R, G, B)");
    }
    out.image = out.bands ? rgb_planes_to_image(out.patch.exitance, view.width_px, view.height_px, "Linear Rec.709", space, cm)
                          : spectral_planes_to_image(out.patch.exitance, view.width_px, view.height_px, wavelengths.nm(), illuminant, observer, space, cm);
    return out;
}

void write_lit_swatch(const LitSwatch& swatch, const std::string& material, const Illumination& light, double field_mm,
                      const std::string& wavelengths_text, const ImageOutputs& files, const std::string& profile_shape) {
    const auto& cm = ColorManagement::builtin();
    const auto lighting = light.description();
    const auto& model = swatch.patch.profiles.model;
    ImageMetadata metadata{{"Software", std::string("skinspec ") + version},
                                 {"skinspec:model", model},
                                 {"skinspec:geometry", std::string(to_string(swatch.patch.geometry_measured))},
                                 {"skinspec:material", material},
                                 {"skinspec:lighting", lighting},
                                 {"skinspec:field_mm", fmt::format("{:g}", field_mm)},
                                 {"skinspec:pixel_mm", fmt::format("{:g}", swatch.patch.geometry.pixel_mm)},
                                 {"skinspec:wavelengths", swatch.bands ? std::string("bands R, G, B") : wavelengths_text},
                                 {"ImageDescription", fmt::format("skinspec lit swatch: {} under {} ({} mode; geometry {}: {})", material, lighting, model,
                                                                  to_string(swatch.patch.geometry_measured),
                                                                  swatch.patch.geometry_measured == MeasurementGeometry::sci
                                                                      ? "diffuse exitance and the first-surface reflection"
                                                                      : "diffuse exitance, no first-surface reflection")}};
    if (!profile_shape.empty()) metadata.emplace_back("skinspec:profile_shape", profile_shape);
    if (const auto precision = profile_precision_line(swatch.patch.profiles); !precision.empty()) metadata.emplace_back("skinspec:profile_precision", precision);
    for (const auto& out : files.files) {
        if (out.extension() == ".exr") write_linear_image(out, swatch.image, files.space, files.half, metadata, cm);
        else write_image_grid(out, {swatch.image}, 1, {fmt::format("{}, {}\n{}, {:g} mm", material, to_string(swatch.patch.geometry_measured), lighting, field_mm)}, files.space, files.display, files.view, metadata, cm);
    }
}

}  // namespace skinspec
