#include "inverse/profile_fit/profile_system.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "appearance/image_convolution.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

void check_step(double step_mm) {
    if (!(step_mm > 0.0 && std::isfinite(step_mm))) throw InputError("quantisation step = " + format_number(step_mm) + " mm is outside (0, inf)");
}

// Bins 0, step, ... up to the largest distance (the last bin closes the last interval); InputError when there
// are more bins than usable patches (n > m), checked in floating point so no distance can overflow the count.
std::size_t bin_count(double max_distance_mm, double step_mm, std::size_t rows) {
    const double bins = std::floor(max_distance_mm / step_mm) + 2.0;
    if (!(bins <= static_cast<double>(rows))) {
        throw InputError(fmt::format("the quantisation gives n = {:.6g} distance bins for m = {} usable patches (n > m: "
                                     "under-determined); use a larger step or more patches",
                                     bins, rows));
    }
    return static_cast<std::size_t>(bins);
}

void mark_bins(ProfileSystem& s) {
    s.bin_has_data.resize(s.bins());
    for (std::size_t i = 0; i < s.bins(); ++i) s.bin_has_data[i] = s.w.col(static_cast<Eigen::Index>(i)).squaredNorm() > 0.0 ? 1 : 0;
}

}  // namespace

void validate(const PlanarScene& s) {
    if (s.width <= 0 || s.height <= 0) throw InputError("planar scene: the images are empty");
    const auto n = static_cast<std::size_t>(s.width) * s.height;
    if (s.incident.size() != n || s.observed.size() != n || s.valid.size() != n) throw InputError("planar scene: image sizes differ");
    if (!(s.pitch_mm > 0.0 && std::isfinite(s.pitch_mm))) throw InputError("pixel pitch = " + format_number(s.pitch_mm) + " mm is outside (0, inf)");
    std::size_t used = 0;
    for (std::size_t p = 0; p < n; ++p) {
        const int x = static_cast<int>(p % s.width), y = static_cast<int>(p / s.width);
        for (const auto& [name, v] : {std::pair{"irradiance", s.incident[p]}, std::pair{"observed", s.observed[p]}}) {
            if (!std::isfinite(v)) throw InputError(fmt::format("{} pixel ({}, {}) = {} is not a finite number", name, x, y, v));
            if (v < 0.0) throw InputError(fmt::format("{} pixel ({}, {}) = {} is outside [0, inf)", name, x, y, v));
        }
        used += s.valid[p] ? 1 : 0;
    }
    if (used == 0) throw InputError("planar scene: the mask leaves no valid pixel");
}

ProfileSystem planar_system(const PlanarScene& scene, double step_mm) {
    validate(scene);
    check_step(step_mm);
    ProfileSystem s;
    s.step_mm = step_mm;
    for (std::size_t p = 0; p < scene.valid.size(); ++p) {
        if (scene.valid[p]) s.rows.push_back(p);
    }
    const double h = scene.pitch_mm;
    const double max_distance = h * std::hypot(scene.width - 1, scene.height - 1);
    const std::size_t n = bin_count(max_distance, step_mm, s.rows.size());
    s.w.resize(static_cast<Eigen::Index>(s.rows.size()), static_cast<Eigen::Index>(n));
    s.l.resize(static_cast<Eigen::Index>(s.rows.size()));
    for (std::size_t r = 0; r < s.rows.size(); ++r) s.l[static_cast<Eigen::Index>(r)] = scene.observed[s.rows[r]];
    // Column i: sum_k c_k tent_i(d_jk) = (c * tent_i)(j), with tent_i(d) = max(0, 1 - |d - d'_i| / step) (Eq. 17-19).
    const int rx = scene.width - 1, ry = scene.height - 1, side = 2 * rx + 1;
    const ImageConvolver convolver(scene.incident, scene.width, scene.height, rx, ry);
    std::vector<double> distance(static_cast<std::size_t>(side) * (2 * ry + 1));
    for (int j = -ry; j <= ry; ++j) {
        for (int i = -rx; i <= rx; ++i) distance[static_cast<std::size_t>(j + ry) * side + (i + rx)] = h * std::hypot(i, j);
    }
    std::vector<double> kernel(distance.size());
    for (std::size_t b = 0; b < n; ++b) {
        const double centre = static_cast<double>(b) * step_mm;
        for (std::size_t k = 0; k < distance.size(); ++k) kernel[k] = std::max(0.0, 1.0 - std::abs(distance[k] - centre) / step_mm);
        const auto column = convolver.convolve(kernel);
        for (std::size_t r = 0; r < s.rows.size(); ++r) {
            s.w(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(b)) = column[s.rows[r]];
        }
    }
    // FFT round-off leaves ~1e-16 residues in columns that should be empty.
    const double floor = 1e-12 * s.w.cwiseAbs().maxCoeff();
    s.w = s.w.unaryExpr([floor](double v) { return std::abs(v) < floor ? 0.0 : v; });
    mark_bins(s);
    return s;
}

ProfileSystem patch_system(const std::vector<SurfacePatch>& patches, double step_mm) {
    check_step(step_mm);
    ProfileSystem s;
    s.step_mm = step_mm;
    double max_distance = 0.0;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (std::size_t p = 0; p < patches.size(); ++p) {
        const auto& q = patches[p];
        for (const double v : {q.position_mm.x, q.position_mm.y, q.position_mm.z, q.incident, q.observed}) {
            if (!std::isfinite(v)) throw InputError(fmt::format("patch {}: a value is not a finite number", p + 1));
        }
        if (q.incident < 0.0 || q.observed < 0.0) throw InputError(fmt::format("patch {}: c and l must be in [0, inf)", p + 1));
        if (q.visible) s.rows.push_back(p);
        lo = glm::min(lo, q.position_mm);
        hi = glm::max(hi, q.position_mm);
    }
    if (s.rows.empty()) throw InputError("patch list: no visible patch");
    max_distance = glm::length(hi - lo);
    const std::size_t n = bin_count(max_distance, step_mm, s.rows.size());
    s.w = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(s.rows.size()), static_cast<Eigen::Index>(n));
    s.l.resize(static_cast<Eigen::Index>(s.rows.size()));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.rows.size()), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t r = range.begin(); r != range.end(); ++r) {
            const auto& pj = patches[s.rows[r]];
            s.l[static_cast<Eigen::Index>(r)] = pj.observed;
            for (const auto& pk : patches) {
                const double d = glm::length(pj.position_mm - pk.position_mm) / step_mm;
                const auto i = static_cast<Eigen::Index>(d);
                const double beta = static_cast<double>(i) + 1.0 - d;  // Eq. 17: weight of the lower bin
                s.w(static_cast<Eigen::Index>(r), i) += beta * pk.incident;
                s.w(static_cast<Eigen::Index>(r), i + 1) += (1.0 - beta) * pk.incident;
            }
        }
    });
    mark_bins(s);
    return s;
}

std::vector<double> render_planar(const PlanarScene& scene, const std::function<double(double)>& profile) {
    const int rx = scene.width - 1, ry = scene.height - 1, side = 2 * rx + 1;
    std::vector<double> kernel(static_cast<std::size_t>(side) * (2 * ry + 1));
    for (int j = -ry; j <= ry; ++j) {
        for (int i = -rx; i <= rx; ++i) kernel[static_cast<std::size_t>(j + ry) * side + (i + rx)] = profile(scene.pitch_mm * std::hypot(i, j));
    }
    return ImageConvolver(scene.incident, scene.width, scene.height, rx, ry).convolve(kernel);
}

std::vector<double> render_patches(const std::vector<SurfacePatch>& patches, const std::function<double(double)>& profile) {
    std::vector<double> out(patches.size(), 0.0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, patches.size()), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t j = range.begin(); j != range.end(); ++j) {
            double sum = 0.0;
            for (const auto& pk : patches) sum += profile(glm::length(patches[j].position_mm - pk.position_mm)) * pk.incident;
            out[j] = sum;
        }
    });
    return out;
}

double psnr_db(const std::vector<double>& observed, const std::vector<double>& synthesised, const std::vector<char>& used) {
    double peak = 0.0, squared = 0.0;
    std::size_t count = 0;
    for (std::size_t p = 0; p < observed.size(); ++p) {
        if (!used[p]) continue;
        peak = std::max(peak, observed[p]);
        squared += (observed[p] - synthesised[p]) * (observed[p] - synthesised[p]);
        ++count;
    }
    if (count == 0 || peak == 0.0) return 0.0;
    const double mse = squared / static_cast<double>(count);
    return mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(peak * peak / mse);
}

}  // namespace skinspec
