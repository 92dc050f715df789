#include "spectral/colorimetry.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr int cie_first_nm = 360;
constexpr int cie_last_nm = 830;

}  // namespace

Chromaticity chromaticity(const XYZ& xyz) {
    const double sum = xyz.X + xyz.Y + xyz.Z;
    if (sum == 0.0) return {};
    return {xyz.X / sum, xyz.Y / sum};
}

Lab xyz_to_lab(const XYZ& xyz, const XYZ& white) {
    // CIE 015:2018 Eq. 8.3: f(t) = t^(1/3) above (6/29)^3, linear below.
    constexpr double delta = 6.0 / 29.0;
    const auto f = [](double t) {
        return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
    };
    const double fx = f(xyz.X / white.X);
    const double fy = f(xyz.Y / white.Y);
    const double fz = f(xyz.Z / white.Z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

TristimulusWeights::TristimulusWeights(std::span<const double> wavelengths_nm, IlluminantKind illuminant_kind,
                                       ObserverKind observer_kind, OutOfRangePolicy outside)
    : weights_(wavelengths_nm.size(), {0.0, 0.0, 0.0}) {
    if (wavelengths_nm.empty()) throw InputError("tristimulus weights: no sample wavelengths");
    const auto& source = illuminant(illuminant_kind).power;
    const auto& cmf = observer(observer_kind);
    const auto n = wavelengths_nm.size();
    double y_white = 0.0;
    std::array<double, 3> white{0.0, 0.0, 0.0};
    for (int nm = cie_first_nm; nm <= cie_last_nm; ++nm) {
        const double lambda = nm;
        const double s = source(lambda);
        const std::array<double, 3> sxyz{s * cmf.xbar(lambda), s * cmf.ybar(lambda), s * cmf.zbar(lambda)};
        for (int c = 0; c < 3; ++c) white[c] += sxyz[c];
        y_white += sxyz[1];
        const auto add = [&](std::size_t i, double hat) {
            for (int c = 0; c < 3; ++c) weights_[i][c] += hat * sxyz[c];
        };
        if (lambda < wavelengths_nm.front() || lambda > wavelengths_nm.back()) {
            if (outside == OutOfRangePolicy::zero) continue;
            if (outside == OutOfRangePolicy::error) {
                throw InputError("spectrum covers " + format_number(wavelengths_nm.front()) + "-" +
                                 format_number(wavelengths_nm.back()) + " nm but colour needs " +
                                 std::to_string(cie_first_nm) + "-" + std::to_string(cie_last_nm) +
                                 " nm under this out-of-range policy (error)");
            }
            add(lambda < wavelengths_nm.front() ? 0 : n - 1, 1.0);
            continue;
        }
        const auto upper = std::upper_bound(wavelengths_nm.begin(), wavelengths_nm.end(), lambda);
        if (upper == wavelengths_nm.end()) {
            add(n - 1, 1.0);
            continue;
        }
        const auto i = static_cast<std::size_t>(upper - wavelengths_nm.begin());
        const double t = (lambda - wavelengths_nm[i - 1]) / (wavelengths_nm[i] - wavelengths_nm[i - 1]);
        add(i - 1, 1.0 - t);
        add(i, t);
    }
    for (auto& w : weights_) {
        for (auto& c : w) c /= y_white;
    }
    white_ = {white[0] / y_white, 1.0, white[2] / y_white};
}

namespace {

// Where wavelengths fail to give a colour: nullopt when they cover 400-700 nm closely enough, 0 when they do not
// cover it, i when the step ending at nm[i] is too wide.
std::optional<std::size_t> color_span_gap(std::span<const double> nm) {
    if (nm.size() < 2 || nm.front() > 400.0 || nm.back() < 700.0) return 0;
    for (std::size_t i = 1; i < nm.size(); ++i) {
        if (nm[i] - nm[i - 1] > max_color_step_nm) return i;
    }
    return std::nullopt;
}

}  // namespace

std::string color_span_problem(std::span<const double> nm) {
    const auto gap = color_span_gap(nm);
    if (!gap) return {};
    const auto needs = fmt::format("a colour needs wavelengths covering 400-700 nm at steps of at most {:g} nm", max_color_step_nm);
    if (*gap == 0) return nm.empty() ? needs : fmt::format("{} (these cover {:g}-{:g} nm)", needs, nm.front(), nm.back());
    return fmt::format("{} (a step of {:g} nm at {:g} nm)", needs, nm[*gap] - nm[*gap - 1], nm[*gap - 1]);
}

// Asked per result of a sweep: no message is formatted (that was 3 us of each dipole member's 10).
bool has_color_span(std::span<const double> nm) { return !color_span_gap(nm).has_value(); }

XYZ TristimulusWeights::integrate(std::span<const double> samples) const {
    if (samples.size() != weights_.size()) {
        throw InputError("tristimulus weights: " + std::to_string(samples.size()) + " samples for " +
                         std::to_string(weights_.size()) + " wavelengths");
    }
    XYZ xyz;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        xyz.X += weights_[i][0] * samples[i];
        xyz.Y += weights_[i][1] * samples[i];
        xyz.Z += weights_[i][2] * samples[i];
    }
    return xyz;
}

XYZ spectrum_to_xyz(const TabulatedSpectrum& spectrum, IlluminantKind illuminant_kind, ObserverKind observer_kind) {
    const TristimulusWeights weights(spectrum.wavelengths_nm(), illuminant_kind, observer_kind, spectrum.outside());
    return weights.integrate(spectrum.values());
}

}  // namespace skinspec
