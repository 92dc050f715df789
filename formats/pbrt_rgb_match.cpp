#include "formats/pbrt_rgb_match.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <Eigen/Dense>

#include "spectral/colorimetry.hpp"
#include "spectral/input_error.hpp"
#include "spectral/rgb_uplift.hpp"
#include "spectral/wavelength_grid.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

// The slab's linear sRGB under D65 (CIE 1931) when layer k's coefficients at wavelength i are sigma_a(k, i),
// sigma_s(k, i) [1/mm], with the media's thicknesses, indices, phase functions and bottom.
class SlabColour {
public:
    SlabColour(const RendererMedia& media, std::vector<double> nm)
        : media_(media), nm_(std::move(nm)), weights_(nm_, IlluminantKind::d65, ObserverKind::cie1931_2deg, OutOfRangePolicy::hold) {}

    std::array<double, 3> operator()(const std::function<double(std::size_t, std::size_t)>& sigma_a,
                                     const std::function<double(std::size_t, std::size_t)>& sigma_s) {
        constexpr double per_cm_per_per_mm = 10.0, cm_per_mm = 0.1;
        std::vector<double> reflectance;
        for (std::size_t i = 0; i < nm_.size(); ++i) {
            RteStack stack;
            stack.above_refractive_index = media_.above_refractive_index;
            stack.below_refractive_index = media_.below_refractive_index;
            stack.bottom_reflector = media_.bottom_reflector;
            for (std::size_t k = 0; k < media_.layers.size(); ++k) {
                const auto& l = media_.layers[k];
                const auto phase = l.phase.kind == RendererPhase::Kind::isotropic ? PhaseFunction::isotropic() : PhaseFunction::henyey_greenstein(l.phase.g);
                stack.layers.push_back({l.refractive_index, sigma_a(k, i) * per_cm_per_per_mm, sigma_s(k, i) * per_cm_per_per_mm,
                                        l.thickness_mm * cm_per_mm, phase});
            }
            const auto r = solve_adding_doubling(stack, AdIncidence{false, 0.0}, AdOptions{pbrt_rgb_match_channels, false}, &cache_);
            reflectance.push_back(r.specular_reflectance + r.diffuse_reflectance);
        }
        return linear_srgb(weights_.integrate(reflectance));
    }

private:
    const RendererMedia& media_;
    std::vector<double> nm_;
    TristimulusWeights weights_;
    AdCache cache_;
};

// Relative to the target channel (a channel of ~0, as of a black slab, counts absolutely).
constexpr double smallest_channel = 1e-6;
double largest_relative(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double worst = 0.0;
    for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), smallest_channel));
    return worst;
}

}  // namespace

PbrtRgbMatch match_pbrt_rgb(const LayerStack& stack, const MediaRequest& request, const RendererMedia& point) {
    const auto grid = WavelengthGrid::parse(pbrt_rgb_match_wavelengths, "pbrt RGB match");
    MediaRequest spectral_request = request;
    spectral_request.rgb = false;
    spectral_request.wavelengths_nm.assign(grid.nm().begin(), grid.nm().end());
    const auto spectral = [&] {
        try {
            return renderer_media(stack, spectral_request);
        } catch (const InputError& e) {
            throw InputError(std::string("pbrt-v4's RGB media are matched to the colour of the spectral media over ") + std::string(pbrt_rgb_match_wavelengths) +
                             " nm, which this material cannot give: " + e.what());
        }
    }();
    SlabColour colour(point, spectral_request.wavelengths_nm);

    PbrtRgbMatch out;
    out.media = point;
    out.spectral_srgb = colour([&](std::size_t k, std::size_t i) { return spectral.layers[k].sigma_a_per_mm[i]; },
                               [&](std::size_t k, std::size_t i) { return spectral.layers[k].sigma_s_per_mm[i]; });
    // The smooth spectra pbrt-v4 makes of the scattering coefficients (unchanged) and of the scaled absorption ones.
    std::vector<UpliftedSpectrum> scattering;
    for (const auto& l : point.layers) scattering.emplace_back(std::array{l.sigma_s_per_mm[0], l.sigma_s_per_mm[1], l.sigma_s_per_mm[2]});
    const auto& nm = spectral_request.wavelengths_nm;
    const auto rendered = [&](const Eigen::Vector3d& factors) {
        std::vector<UpliftedSpectrum> absorption;
        for (const auto& l : point.layers) {
            absorption.emplace_back(std::array{l.sigma_a_per_mm[0] * factors[0], l.sigma_a_per_mm[1] * factors[1], l.sigma_a_per_mm[2] * factors[2]});
        }
        return colour([&](std::size_t k, std::size_t i) { return absorption[k](nm[i]); }, [&](std::size_t k, std::size_t i) { return scattering[k](nm[i]); });
    };
    const auto to_vector = [](const std::array<double, 3>& a) { return Eigen::Vector3d(a[0], a[1], a[2]); };
    const Eigen::Vector3d target = to_vector(out.spectral_srgb);

    // Newton on the three factors with a forward-difference Jacobian; a step that would make a factor non-positive or
    // not reduce the difference is halved.
    Eigen::Vector3d factors = Eigen::Vector3d::Ones();
    out.point_srgb = rendered(factors);
    Eigen::Vector3d value = to_vector(out.point_srgb);
    const auto relative = [&](const Eigen::Vector3d& v) { return largest_relative({v[0], v[1], v[2]}, out.spectral_srgb); };
    for (int iteration = 0; iteration < 12 && relative(value) > pbrt_rgb_match_tolerance; ++iteration) {
        Eigen::Matrix3d jacobian;
        for (int c = 0; c < 3; ++c) {
            Eigen::Vector3d shifted = factors;
            const double h = 1e-4 * factors[c];
            shifted[c] += h;
            jacobian.col(c) = (to_vector(rendered(shifted)) - value) / h;
        }
        const Eigen::Vector3d step = jacobian.colPivHouseholderQr().solve(target - value);
        if (!step.allFinite()) break;
        bool improved = false;
        for (double damping = 1.0; damping > 1e-3; damping *= 0.5) {
            const Eigen::Vector3d next = factors + damping * step;
            if ((next.array() <= 0.0).any()) continue;
            const Eigen::Vector3d next_value = to_vector(rendered(next));
            if (relative(next_value) < relative(value)) {
                factors = next;
                value = next_value;
                improved = true;
                break;
            }
        }
        if (!improved) break;
    }
    for (std::size_t c = 0; c < 3; ++c) out.absorption_factors[c] = factors[static_cast<Eigen::Index>(c)];
    for (auto& l : out.media.layers) {
        for (std::size_t c = 0; c < 3; ++c) l.sigma_a_per_mm[c] *= out.absorption_factors[c];
    }
    out.matched_srgb = {value[0], value[1], value[2]};
    out.largest_relative_difference = largest_relative(out.matched_srgb, out.spectral_srgb);
    return out;
}

}  // namespace skinspec
