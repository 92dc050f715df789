#include "formats/renderer_media.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "materials/measured_profile.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

constexpr double mm_per_cm = 10.0;

// p(cos theta) per sr of a measured profile at cos theta = -1 + 2 k / (n - 1): the probability of the cell of
// width h around each point from the profile's piecewise-linear C(theta) (Bruls & van der Leun 1984, as
// materials/measured_profile.hpp reads it), over the cell's solid angle 2 pi h.
std::vector<double> tabulated_values(const MeasuredProfile& profile, double wavelength_nm, std::size_t points) {
    const double h = 2.0 / static_cast<double>(points - 1);
    const auto c_of_mu = [&](double mu) { return profile.cdf(wavelength_nm, std::acos(std::clamp(mu, -1.0, 1.0)) * 180.0 / std::numbers::pi); };
    std::vector<double> values;
    for (std::size_t k = 0; k < points; ++k) {
        const double mu = -1.0 + h * static_cast<double>(k);
        const double lo = std::max(-1.0, mu - 0.5 * h), hi = std::min(1.0, mu + 0.5 * h);
        values.push_back((c_of_mu(lo) - c_of_mu(hi)) / (2.0 * std::numbers::pi * (hi - lo)));
    }
    return values;
}

// The table of `profile` with the fewest points (181, doubling the intervals) whose interpolated mean cosine is within
// tabulated_mean_cosine_tolerance of `mean_cosine`.
std::vector<double> tabulated_phase(const MeasuredProfile& profile, double wavelength_nm, double mean_cosine, const std::string& layer) {
    constexpr std::size_t first_points = 181, most_points = 184'321;
    for (std::size_t points = first_points; points <= most_points; points = 2 * points - 1) {
        auto values = tabulated_values(profile, wavelength_nm, points);
        if (std::abs(tabulated_mean_cosine(values) - mean_cosine) <= tabulated_mean_cosine_tolerance) return values;
    }
    throw InputError("layer '" + layer + "': no table of up to " + std::to_string(most_points) + " points holds its phase function's mean cosine " +
                     format_number(mean_cosine) + " to " + format_number(tabulated_mean_cosine_tolerance));
}

RendererPhase phase_of(const LayerStack& stack, std::size_t k, const MediaRequest& request) {
    const auto o = stack.optics(k, request.phase_wavelength_nm, OpticsScope{true, false});
    const auto& name = stack.layers[k].name;
    RendererPhase phase;
    phase.g = o.g.value_or(0.0);
    if (request.phase == PhaseExport::hg) return phase;
    switch (*o.phase) {
        case PhaseFunctionKind::henyey_greenstein: return phase;
        case PhaseFunctionKind::isotropic: return {RendererPhase::Kind::isotropic, 0.0, {}};
        case PhaseFunctionKind::rayleigh:
            throw InputError("layer '" + name + "' scatters by Rayleigh's phase function, which the export does not write (use --phase hg: HG with g = 0)");
        case PhaseFunctionKind::measured_stratum_corneum:
        case PhaseFunctionKind::measured_epidermis: {
            const auto& profile = *o.phase == PhaseFunctionKind::measured_epidermis ? MeasuredProfile::epidermis() : MeasuredProfile::stratum_corneum();
            return {RendererPhase::Kind::tabulated, phase.g, tabulated_phase(profile, request.phase_wavelength_nm, phase.g, name)};
        }
    }
    return phase;
}

}  // namespace

double tabulated_mean_cosine(const std::vector<double>& values) {
    // Exact integrals of the piecewise-linear p: over [a, b], int p = h (p_a + p_b) / 2 and
    // int mu p = h (p_a (2a + b) + p_b (a + 2b)) / 6.
    const double h = 2.0 / static_cast<double>(values.size() - 1);
    double norm = 0.0, first_moment = 0.0;
    for (std::size_t k = 0; k + 1 < values.size(); ++k) {
        const double a = -1.0 + h * static_cast<double>(k), b = a + h;
        norm += 0.5 * h * (values[k] + values[k + 1]);
        first_moment += h * (values[k] * (2.0 * a + b) + values[k + 1] * (a + 2.0 * b)) / 6.0;
    }
    return first_moment / norm;
}

std::string_view to_string(PhaseExport phase) { return phase == PhaseExport::hg ? "hg" : "own"; }

RendererMedia renderer_media(const LayerStack& stack, const MediaRequest& request) {
    if (request.wavelengths_nm.empty()) throw InputError("--wavelengths: no wavelength to export");
    if (request.rgb && request.wavelengths_nm.size() != 3) {
        throw InputError("--rgb: give exactly three wavelengths (taken as R, G, B), got " + std::to_string(request.wavelengths_nm.size()));
    }
    if (!(request.phase_wavelength_nm > 0.0) || !std::isfinite(request.phase_wavelength_nm)) {
        throw InputError("--phase-wavelength " + format_number(request.phase_wavelength_nm) + " nm is outside (0, inf)");
    }
    RendererMedia media;
    media.material = stack.name;
    media.wavelengths_nm = request.wavelengths_nm;
    media.rgb = request.rgb;
    media.phase_wavelength_nm = request.phase_wavelength_nm;
    media.above_refractive_index = stack.above_refractive_index;
    media.below_refractive_index = stack.below_refractive_index;
    if (stack.bottom == BottomBoundary::hypodermis) {
        throw InputError("bottom.boundary = hypodermis (the measured hypodermis as a reflector) is not exported: the scenes hold BioSpec's ideal "
                         "reflector or an open bottom only (set bottom.boundary = diffuse_reflector or exit)");
    }
    media.bottom_reflector = stack.bottom == BottomBoundary::diffuse_reflector;
    for (const auto& layer : stack.layers) media.layers.push_back({layer.name, 0.0, 1.0, {}, {}, {}});
    for (const double nm : request.wavelengths_nm) {
        const auto rte = rte_stack_from(stack, nm);
        for (std::size_t k = 0; k < rte.layers.size(); ++k) {
            auto& layer = media.layers[k];
            layer.thickness_mm = rte.layers[k].thickness_cm * mm_per_cm;
            layer.refractive_index = rte.layers[k].refractive_index;
            layer.sigma_a_per_mm.push_back(rte.layers[k].mu_a_per_cm / mm_per_cm);
            layer.sigma_s_per_mm.push_back(rte.layers[k].mu_s_per_cm / mm_per_cm);
        }
    }
    // A scene is geometry: the layers' depths (their sum) and coefficients must be finite numbers a renderer reads
    // (a 1e308 cm epidermis became vertices at -inf).
    double depth_mm = 0.0;
    for (const auto& layer : media.layers) {
        depth_mm += layer.thickness_mm;
        const auto finite = [](const std::vector<double>& v) { return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }); };
        if (!std::isfinite(depth_mm) || !finite(layer.sigma_a_per_mm) || !finite(layer.sigma_s_per_mm)) {
            throw InputError("layer '" + layer.name + "': thickness " + format_number(layer.thickness_mm) + " mm (stack depth " + format_number(depth_mm) +
                             " mm) or its coefficients are not finite numbers in a scene");
        }
    }
    // After the coefficients: rte_stack_from has refused any layer without volumetric scattering (and a phase).
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        auto& layer = media.layers[k];
        layer.phase = phase_of(stack, k, request);
        if (layer.phase.kind != RendererPhase::Kind::tabulated) continue;
        // A table is one wavelength's phase function (the renderers' are not spectral): its scattering coefficient keeps
        // the layer's reduced scattering mu_s (1 - g) at every wavelength (similarity relation, Wyman, Patterson &
        // Wilson 1989, J. Comput. Phys. 81:137), which took Mitsuba's R at 400 nm from -0.0118 to +0.0005 of the
        // description's (biospec-moderately; formats/scene_export.hpp states it per export).
        for (std::size_t i = 0; i < request.wavelengths_nm.size(); ++i) {
            const double g = stack.optics(k, request.wavelengths_nm[i], OpticsScope{true, false}).g.value_or(0.0);
            layer.sigma_s_per_mm[i] *= (1.0 - g) / (1.0 - layer.phase.g);
        }
    }
    return media;
}

std::vector<std::pair<double, double>> mean_cosine_spread(const LayerStack& stack, const std::vector<double>& wavelengths_nm) {
    std::vector<std::pair<double, double>> spread(stack.layers.size(), {1.0, -1.0});
    for (const double nm : wavelengths_nm) {
        for (std::size_t k = 0; k < stack.layers.size(); ++k) {
            const double g = stack.optics(k, nm, OpticsScope{true, false}).g.value_or(0.0);
            spread[k] = {std::min(spread[k].first, g), std::max(spread[k].second, g)};
        }
    }
    return spread;
}

void write_spd_file(const std::filesystem::path& file, const std::vector<double>& wavelengths_nm, const std::vector<double>& values,
                    const std::string& comment) {
    std::string text = "# " + comment + "\n# wavelength_nm value\n";
    for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) text += format_number(wavelengths_nm[i]) + " " + format_number(values[i]) + "\n";
    write_text_file(file, text, true);
}

std::pair<std::vector<double>, std::vector<double>> read_spd_file(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw InputError("spectrum file " + file.string() + " cannot be read");
    std::pair<std::vector<double>, std::vector<double>> out;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const auto hash = line.find('#');
        const auto content = trim(std::string_view(line).substr(0, hash));
        if (content.empty()) continue;
        const auto fields = split_fields(content);
        const auto nm = fields.size() == 2 ? parse_double(fields[0]) : std::nullopt;
        const auto value = fields.size() == 2 ? parse_double(fields[1]) : std::nullopt;
        if (!nm || !value || !std::isfinite(*nm) || !std::isfinite(*value)) {
            throw InputError(file.string() + " line " + std::to_string(number) + ": expected 'wavelength value', got '" + std::string(content) + "'");
        }
        out.first.push_back(*nm);
        out.second.push_back(*value);
    }
    if (out.first.empty()) throw InputError("spectrum file " + file.string() + " has no values");
    return out;
}

std::filesystem::path spectra_folder(const std::filesystem::path& scene) { return scene.parent_path() / (scene.stem().string() + "_spectra"); }

std::filesystem::path spectrum_file_path(const std::filesystem::path& scene, const std::string& layer, const std::string& quantity) {
    return spectra_folder(scene) / (layer + "_" + quantity + ".spd");
}

std::string spectrum_file_reference(const std::filesystem::path& scene, const std::string& layer, const std::string& quantity) {
    return (spectra_folder(scene).filename() / (layer + "_" + quantity + ".spd")).string();
}

std::vector<std::filesystem::path> scene_files(const RendererMedia& media, const std::filesystem::path& scene,
                                               const std::vector<std::string>& quantities) {
    std::vector<std::filesystem::path> files{scene};
    if (media.rgb) return files;
    for (const auto& l : media.layers) {
        for (const auto& q : quantities) files.push_back(spectrum_file_path(scene, l.name, q));
    }
    return files;
}

}  // namespace skinspec
