#include "appearance/lit_patch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "appearance/image_convolution.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr int samples_per_pixel_side = 8;

// Linear interpolation of a profile sampled at radii j * dr.
double interpolate(const std::vector<double>& values, double dr, double r) {
    const double x = r / dr;
    const auto j = static_cast<std::size_t>(x);
    if (j + 1 >= values.size()) return values.back();
    const double f = x - static_cast<double>(j);
    return values[j] * (1.0 - f) + values[j + 1] * f;
}

// The reflectance leaving within each radius j * dr, 2 pi int_0^r R(r') r' dr' of the linear interpolation (exact for it).
std::vector<double> enclosed(const std::vector<double>& values, double dr) {
    std::vector<double> out{0.0};
    for (std::size_t j = 0; j + 1 < values.size(); ++j) {
        // int_{r_j}^{r_j+1} (a + b (r - r_j)) r dr for the segment's line.
        const double r0 = static_cast<double>(j) * dr, a = values[j], b = (values[j + 1] - values[j]) / dr;
        out.push_back(out.back() + 2.0 * std::numbers::pi * (a * (r0 * dr + 0.5 * dr * dr) + b * (0.5 * r0 * dr * dr + dr * dr * dr / 3.0)));
    }
    return out;
}

// The mean of R over the annulus [r - w/2, r + w/2] (the radial extent of a pixel of width w at distance r): the rings a
// pixel covers, so that a Monte Carlo profile's noise per ring averages out as it does over the pixel's area.
double annulus_mean(const std::vector<double>& enclosed_values, double dr, double r, double w) {
    const auto at = [&](double radius) { return interpolate(enclosed_values, dr, radius); };
    const double inner = r - 0.5 * w, outer = r + 0.5 * w;
    return (at(outer) - at(inner)) / (std::numbers::pi * (outer * outer - inner * inner));
}

// The kernel's pixels within `core` pixels (Chebyshev distance) of the centre, (2 core + 1)^2 row-major: each ring of the
// profile (R(r_k) on [r_k - dr/2, r_k + dr/2), the disc of radius dr/2 at r = 0) carries its energy R(r_k) times its
// area, shared among the core pixels by the share of its circle inside each (angles a quarter ring width apart). Near
// the entry point, where a dark skin's blue light leaves within a few rings, no ring is sampled by points that miss it.
std::vector<double> core_pixels(const std::vector<double>& values, double dr, double h, int core) {
    const int side = 2 * core + 1;
    std::vector<double> out(static_cast<std::size_t>(side) * side, 0.0);
    const double reach = (core + 0.5) * h * std::sqrt(2.0);
    out[static_cast<std::size_t>(core) * side + static_cast<std::size_t>(core)] += values.front() * std::numbers::pi * 0.25 * dr * dr;
    for (std::size_t k = 1; k < values.size() && static_cast<double>(k) * dr <= reach; ++k) {
        const double r = static_cast<double>(k) * dr, energy = values[k] * 2.0 * std::numbers::pi * r * dr;
        const int angles = std::max(8, static_cast<int>(std::ceil(2.0 * std::numbers::pi * r / (0.25 * dr))));
        const double share = energy / angles;
        for (int a = 0; a < angles; ++a) {
            const double phi = 2.0 * std::numbers::pi * (a + 0.5) / angles;
            const auto i = static_cast<int>(std::lround(r * std::cos(phi) / h)), j = static_cast<int>(std::lround(r * std::sin(phi) / h));
            if (std::max(std::abs(i), std::abs(j)) <= core) out[static_cast<std::size_t>(j + core) * side + static_cast<std::size_t>(i + core)] += share;
        }
    }
    return out;
}

}  // namespace

Illumination Illumination::spot(double radius_mm) {
    if (!(radius_mm > 0.0 && std::isfinite(radius_mm))) throw InputError("spot radius = " + format_number(radius_mm) + " mm is outside (0, inf)");
    Illumination l;
    l.kind_ = Kind::spot;
    l.radius_mm_ = radius_mm;
    return l;
}

Illumination Illumination::edge() {
    Illumination l;
    l.kind_ = Kind::edge;
    return l;
}

Illumination Illumination::pattern(std::vector<float> irradiance, int width_px, int height_px) {
    if (width_px <= 0 || height_px <= 0 || irradiance.size() != static_cast<std::size_t>(width_px) * height_px) {
        throw InputError("illumination pattern: size does not match its pixels");
    }
    for (const float v : irradiance) {
        if (!std::isfinite(v) || v < 0.0f) throw InputError("illumination pattern: irradiance = " + format_number(v) + " is outside [0, inf)");
    }
    Illumination l;
    l.kind_ = Kind::pattern;
    l.image_ = std::move(irradiance);
    l.image_w_ = width_px;
    l.image_h_ = height_px;
    return l;
}

std::string Illumination::description() const {
    switch (kind_) {
        case Kind::spot: return fmt::format("spot of radius {:g} mm", radius_mm_);
        case Kind::edge: return "shadow edge (lit for x > 0)";
        case Kind::pattern: return fmt::format("projected pattern {}x{}", image_w_, image_h_);
    }
    return {};
}

std::vector<double> Illumination::rasterize(const PatchGeometry& view, int margin) const {
    const int w = view.width_px + 2 * margin, h = view.height_px + 2 * margin;
    std::vector<double> out(static_cast<std::size_t>(w) * h, 0.0);
    const double h_mm = view.pixel_mm;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int vx = x - margin, vy = y - margin;  // view pixel
            double sum = 0.0;
            if (kind_ == Kind::pattern) {
                if (vx < 0 || vy < 0 || vx >= view.width_px || vy >= view.height_px) continue;
                const int ix = std::min(image_w_ - 1, vx * image_w_ / view.width_px);
                const int iy = std::min(image_h_ - 1, vy * image_h_ / view.height_px);
                out[static_cast<std::size_t>(y) * w + x] = image_[static_cast<std::size_t>(iy) * image_w_ + ix];
                continue;
            }
            for (int sy = 0; sy < samples_per_pixel_side; ++sy) {
                for (int sx = 0; sx < samples_per_pixel_side; ++sx) {
                    const double px = (vx + (sx + 0.5) / samples_per_pixel_side - 0.5 * view.width_px) * h_mm;
                    const double py = (0.5 * view.height_px - vy - (sy + 0.5) / samples_per_pixel_side) * h_mm;
                    sum += kind_ == Kind::spot ? (px * px + py * py <= radius_mm_ * radius_mm_ ? 1.0 : 0.0) : (px > 0.0 ? 1.0 : 0.0);
                }
            }
            out[static_cast<std::size_t>(y) * w + x] = sum / (samples_per_pixel_side * samples_per_pixel_side);
        }
    }
    return out;
}

LitPatch render_lit_patch(const Material& material, const WavelengthGrid& wavelengths, const Illumination& light,
                          const PatchGeometry& view, const SpectralSolver& solver, const ProfileRequest& settings, MeasurementGeometry geometry,
                          const std::function<void(std::size_t, std::size_t)>& on_progress, const std::atomic<bool>* cancel) {
    for (const int px : {view.width_px, view.height_px}) {
        if (px < 8 || px > 4096) throw InputError("image size " + std::to_string(px) + " px is outside [8, 4096]");
    }
    if (!(view.pixel_mm > 0.0 && view.pixel_mm <= 100.0)) throw InputError("pixel size = " + format_number(view.pixel_mm) + " mm is outside (0, 100]");
    if (geometry == MeasurementGeometry::zero_45) {
        throw InputError("--geometry 0-45: a lit patch shows the light leaving every point of the surface at every angle (sce, or sci with the "
                         "first-surface reflection)");
    }
    LitPatch out;
    out.geometry = view;
    out.geometry_measured = geometry;
    // The kernel reaches half the larger side of the view: light from up to that far away is gathered.
    const int margin = std::max(view.width_px, view.height_px) / 2;
    out.kernel_radius_px = margin;
    const double h = view.pixel_mm;
    const double dr = h / samples_per_pixel_side;
    std::vector<double> radii;
    for (int j = 0; j * dr <= (margin + 2) * h * std::sqrt(2.0); ++j) radii.push_back(j * dr);
    // The set-up steps are not interruptible inside (the light's raster, the FFT of the lit image: ~0.2 s each at
    // 1024 px, ~1 s at 2048): a stop is checked between them.
    const auto stopped = [&] { return cancel && cancel->load(); };
    out.partial = stopped();
    if (out.partial) return out;
    const auto widened = light.rasterize(view, margin);
    out.partial = stopped();
    if (out.partial) return out;
    const int we = view.width_px + 2 * margin, he = view.height_px + 2 * margin;
    const ImageConvolver convolver(widened, we, he, margin, margin);
    const int side = 2 * margin + 1;

    // A layered material's profile per wavelength, each convolved as it comes (progress in even steps: a profile
    // and its convolution per wavelength; solved all first, the estimate took the profiles' rate for the cheaper
    // convolutions); a band material's bands in one solve.
    const auto* stack = std::get_if<LayerStack>(&material);
    const std::size_t channels = profile_channel_count(material, wavelengths);
    const std::size_t per_solve = stack ? 1 : channels;
    out.profiles.material = material_name(material);
    for (std::size_t c = 0; c < channels; ++c) {
        if (stopped()) {
            out.partial = true;
            break;
        }
        if (c % per_solve == 0) {
            const auto grid = stack ? WavelengthGrid::list({wavelengths.nm()[c]}) : wavelengths;
            auto request = settings;
            request.wavelengths = grid;
            request.radii_mm = radii;
            request.transmittance = false;
            request.cancel = cancel;
            request.on_progress = {};
            auto part = solve_profiles(solver, material, request);
            out.profiles.model = part.model;
            out.profiles.stderr_target = part.stderr_target;
            out.profiles.radii_mm = part.radii_mm;
            out.profiles.max_pairs = std::max(out.profiles.max_pairs, part.max_pairs);
            out.profiles.frequencies = std::max(out.profiles.frequencies, part.frequencies);
            out.profiles.converged = out.profiles.converged && part.converged;
            out.profiles.warnings.insert(out.profiles.warnings.end(), part.warnings.begin(), part.warnings.end());
            out.profiles.channels.insert(out.profiles.channels.end(), part.channels.begin(), part.channels.end());
            if (part.partial) {
                out.profiles.partial = out.partial = true;
                break;
            }
        }
        const auto& profile = out.profiles.channels[c];
        const auto within = enclosed(profile.reflectance_per_mm2, dr);
        // Kernel: R(r) integrated over each pixel: near the centre the rings' energies shared by their circles' shares in
        // each pixel (core_pixels), further out R's mean over the annulus the pixel spans radially, times its area.
        constexpr int core = 3;
        const auto centre = core_pixels(profile.reflectance_per_mm2, dr, h, core);
        std::vector<double> kernel(static_cast<std::size_t>(side) * side);
        double sum = 0.0;
        for (int j = -margin; j <= margin; ++j) {
            for (int i = -margin; i <= margin; ++i) {
                const double value = std::max(std::abs(i), std::abs(j)) <= core
                                         ? centre[static_cast<std::size_t>(j + core) * (2 * core + 1) + static_cast<std::size_t>(i + core)]
                                         : annulus_mean(within, dr, std::hypot(i * h, j * h), h) * h * h;
                kernel[static_cast<std::size_t>(j + margin) * side + static_cast<std::size_t>(i + margin)] = value;
                sum += value;
            }
        }
        // Energy: the kernel must sum to the material's total diffuse reflectance (analytic).
        const double correction = profile.total_reflectance - sum;
        kernel[static_cast<std::size_t>(margin) * side + static_cast<std::size_t>(margin)] += correction;
        if (profile.total_reflectance > 0.0) {
            out.largest_kernel_correction = std::max(out.largest_kernel_correction, std::abs(correction) / profile.total_reflectance);
        }
        // The convolution (one FFT round trip, ~0.1-0.3 s at 1024 px) cannot stop inside: a stop is checked around it.
        if (stopped()) {
            out.partial = true;
            break;
        }
        const auto exitance = convolver.convolve(kernel);
        if (stopped()) {
            out.partial = true;
            break;
        }
        std::vector<float> image(static_cast<std::size_t>(view.width_px) * view.height_px);
        // sci: the first-surface reflection where the light falls, as a sphere counts it.
        const double specular = geometry == MeasurementGeometry::sci ? profile.specular_reflectance : 0.0;
        for (int y = 0; y < view.height_px; ++y) {
            for (int x = 0; x < view.width_px; ++x) {
                const auto at = static_cast<std::size_t>(y + margin) * we + static_cast<std::size_t>(x + margin);
                // FFT round-off (~1e-16 of the lit level) can leave dark pixels a hair below zero.
                image[static_cast<std::size_t>(y) * view.width_px + x] = static_cast<float>(std::max(0.0, exitance[at]) + specular * widened[at]);
            }
        }
        out.exitance.push_back(std::move(image));
        if (on_progress) on_progress(c + 1, channels);
    }
    return out;
}

}  // namespace skinspec
