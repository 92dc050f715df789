#include "transport/diffusion/diffusion_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/rough_surface.hpp"
#include "transport/fresnel.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/hypodermis_reflectance.hpp"

namespace skinspec {
namespace {

// One layer (or several merged) as the diffusion models see it; per mm.
struct SlabSpec {
    std::string name;
    double thickness_mm;
    double sigma_a_per_mm;
    double sigma_s_reduced_per_mm;
    double n_top, n_bottom;  // the slab's index at its top and bottom faces (they differ after a merge)
    double mean_free_path_mm() const { return 1.0 / (sigma_a_per_mm + sigma_s_reduced_per_mm); }
};

// A smooth face's diffuse internal reflectance F_dr(eta) (Donner & Jensen 2005 Eq. 8); exactly 0 for matched indices.
double face_reflectance(double n_inside, double n_outside) {
    return n_inside == n_outside ? 0.0 : diffuse_fresnel_reflectance(n_inside / n_outside);
}

SlabSpec merge(const SlabSpec& upper, const SlabSpec& lower) {
    const double d = upper.thickness_mm + lower.thickness_mm;
    const auto mix = [&](double a, double b) { return (a * upper.thickness_mm + b * lower.thickness_mm) / d; };
    return {upper.name + "+" + lower.name, d, mix(upper.sigma_a_per_mm, lower.sigma_a_per_mm),
            mix(upper.sigma_s_reduced_per_mm, lower.sigma_s_reduced_per_mm), upper.n_top, lower.n_bottom};
}

// Seed 002 has no rule for a layer thinner than diffusion resolves; merging it with its neighbour is ours. A hard
// threshold makes R jump at the wavelength where a layer crosses it (0.3565 -> 0.3201 between 480 and 482 nm on
// biospec-lightly), so the merge fades in: fully merged below diffusion_merge_fully_below_mfp, kept above
// diffusion_merge_none_above_mfp, and in between both stacks are solved and blended with a weight smooth (C1) in log
// thickness: R, T and R(r) are continuous in wavelength.
double merge_weight(double mean_free_paths) {
    if (mean_free_paths <= diffusion_merge_fully_below_mfp) return 1.0;
    if (mean_free_paths >= diffusion_merge_none_above_mfp) return 0.0;
    const double t = std::log(mean_free_paths / diffusion_merge_fully_below_mfp) /
                     std::log(diffusion_merge_none_above_mfp / diffusion_merge_fully_below_mfp);
    return 1.0 - t * t * (3.0 - 2.0 * t);
}

struct WeightedSpecs {
    double weight;
    std::vector<SlabSpec> slabs;
};

// Merges slab i with the one below (the last with the one above); the index of the merged slab.
std::size_t merge_at(std::vector<SlabSpec>& slabs, std::size_t i) {
    if (i + 1 == slabs.size()) {
        slabs[i - 1] = merge(slabs[i - 1], slabs[i]);
        slabs.pop_back();
        return i - 1;
    }
    slabs[i] = merge(slabs[i], slabs[i + 1]);
    slabs.erase(slabs.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    return i;
}

// Every stack the thin layers from slab `i` on can become, with its weight (they sum to `weight`).
void merge_thin(std::vector<SlabSpec> slabs, std::size_t i, double weight, std::vector<WeightedSpecs>& out,
                std::vector<TrustWarning>& warnings) {
    while (slabs.size() > 1 && i < slabs.size()) {
        const double mfp = slabs[i].thickness_mm / slabs[i].mean_free_path_mm();
        const double w = merge_weight(mfp);
        if (w == 0.0) {
            ++i;
            continue;
        }
        warnings.push_back({slabs[i].name, "merged", mfp});
        if (w < 1.0) merge_thin(slabs, i + 1, weight * (1.0 - w), out, warnings);
        weight *= w;
        i = merge_at(slabs, i);
    }
    out.push_back({weight, std::move(slabs)});
}

void check_trust(const SlabSpec& s, bool finite, std::vector<TrustWarning>& warnings) {
    const double albedo = s.sigma_s_reduced_per_mm / (s.sigma_a_per_mm + s.sigma_s_reduced_per_mm);
    if (albedo < diffusion_min_reduced_albedo) {
        warnings.push_back({s.name, "albedo", albedo});
    }
    const double mfp = s.thickness_mm / s.mean_free_path_mm();
    if (finite && mfp < diffusion_min_slab_mean_free_paths) {
        warnings.push_back({s.name, "thin", mfp});
    }
}

struct Surface {
    double top_internal_reflectance;
    double specular;
};

Surface surface(double n_above, double n_top, const DiffusionOptions& options, double incidence_deg) {
    check_incidence_deg(incidence_deg);
    const double mu = std::cos(incidence_deg * std::numbers::pi / 180.0);
    if (options.surface_roughness) {
        // Seed 002 Sec. 2.4: rho_d replaces F_dr (Eq. 24) and rho_dt the Fresnel transmittance (Eq. 25-26).
        // rho_d depends only on the roughness and the two indices: computed once (Donner & Jensen 2005: "once for a given
        // material"), not per wavelength.
        thread_local std::optional<RoughSurface> rough;
        if (!rough || rough->roughness() != *options.surface_roughness || rough->n_outside() != n_above || rough->n_inside() != n_top) {
            rough.emplace(*options.surface_roughness, n_above, n_top);
        }
        return {rough->internal_diffuse_reflectance(), 1.0 - rough->entry_transmittance(mu)};
    }
    return {face_reflectance(n_top, n_above), fresnel_reflectance(mu, n_above, n_top)};
}

DiffusionMaterial build(std::vector<SlabSpec> specs, double n_above, double n_below, DiffusionBottom bottom,
                        bool semi_infinite, const DiffusionOptions& options, double incidence_deg, double reflectance = 1.0) {
    std::vector<TrustWarning> warnings;
    if (options.mode == DiffusionMode::dipole && specs.size() > 1) {
        SlabSpec all = specs.front();
        for (std::size_t i = 1; i < specs.size(); ++i) all = merge(all, specs[i]);
        specs = {all};
        semi_infinite = true;
    }
    std::vector<WeightedSpecs> configurations;
    if (semi_infinite) configurations.push_back({1.0, std::move(specs)});
    else merge_thin(std::move(specs), 0, 1.0, configurations, warnings);
    // Every configuration keeps the top slab's top face: one surface for all.
    const auto top = surface(n_above, configurations.front().slabs.front().n_top, options, incidence_deg);
    DiffusionMaterial out{{}, {}, top.specular, 1.0 - top.specular, {}};
    double heaviest = -1.0;
    for (const auto& [weight, slab_specs] : configurations) {
        std::vector<Multipole> slabs;
        std::vector<std::string> names;
        for (std::size_t i = 0; i < slab_specs.size(); ++i) {
            const auto& s = slab_specs[i];
            const bool last = i + 1 == slab_specs.size();
            const double n_next = last ? (bottom == DiffusionBottom::reflector ? s.n_bottom : n_below) : slab_specs[i + 1].n_top;
            const double n_prev = i == 0 ? n_above : slab_specs[i - 1].n_bottom;
            DiffusionSlab slab{s.sigma_s_reduced_per_mm, s.sigma_a_per_mm,
                               semi_infinite ? std::numeric_limits<double>::infinity() : s.thickness_mm,
                               i == 0 ? top.top_internal_reflectance : face_reflectance(s.n_top, n_prev),
                               face_reflectance(s.n_bottom, n_next)};
            check_trust(s, !semi_infinite, warnings);
            slabs.emplace_back(slab);
            names.push_back(s.name);
        }
        if (weight > heaviest) {
            heaviest = weight;
            out.slab_names = std::move(names);
        }
        out.stacks.push_back({weight, LayeredDiffusion(std::move(slabs), semi_infinite ? DiffusionBottom::open : bottom, reflectance)});
    }
    // A slab both branches keep is judged once.
    for (const auto& w : warnings) {
        const bool seen = std::any_of(out.warnings.begin(), out.warnings.end(),
                                      [&](const TrustWarning& o) { return o.slab == w.slab && o.kind == w.kind && o.value == w.value; });
        if (!seen) out.warnings.push_back(w);
    }
    return out;
}

}  // namespace

std::string_view to_string(DiffusionMode mode) { return mode == DiffusionMode::dipole ? "dipole" : "multipole"; }

namespace {

// The configurations' profiles blended by their weights, times what enters.
template <class Profile>
RadialProfile blended(const std::vector<WeightedStack>& stacks, double entry_transmittance, std::span<const double> radii_mm, Profile profile) {
    RadialProfile out;
    out.values.assign(radii_mm.size(), 0.0);
    for (const auto& s : stacks) {
        const auto p = profile(s.stack, radii_mm);
        for (std::size_t i = 0; i < radii_mm.size(); ++i) out.values[i] += s.weight * entry_transmittance * p.values[i];
        out.max_pairs = std::max(out.max_pairs, p.max_pairs);
        out.frequencies = std::max(out.frequencies, p.frequencies);
        out.converged = out.converged && p.converged;
        out.cancelled = out.cancelled || p.cancelled;
    }
    return out;
}

}  // namespace

double DiffusionMaterial::diffuse_reflectance() const {
    double r = 0.0;
    for (const auto& s : stacks) r += s.weight * s.stack.total_reflectance();
    return entry_transmittance * r;
}

double DiffusionMaterial::total_transmittance() const {
    double t = 0.0;
    for (const auto& s : stacks) t += s.weight * s.stack.total_transmittance();
    return entry_transmittance * t;
}

RadialProfile DiffusionMaterial::reflectance_profile(std::span<const double> radii_mm, const std::atomic<bool>* cancel) const {
    return blended(stacks, entry_transmittance, radii_mm, [cancel](const LayeredDiffusion& s, std::span<const double> r) { return s.reflectance_profile(r, cancel); });
}

RadialProfile DiffusionMaterial::transmittance_profile(std::span<const double> radii_mm, const std::atomic<bool>* cancel) const {
    return blended(stacks, entry_transmittance, radii_mm, [cancel](const LayeredDiffusion& s, std::span<const double> r) { return s.transmittance_profile(r, cancel); });
}

DiffusionMaterial diffusion_material(const LayerStack& stack, double wavelength_nm, const DiffusionOptions& options, double incidence_deg) {
    std::vector<SlabSpec> specs;
    const auto optics = stack.optics(wavelength_nm, OpticsScope{.volumetric = false, .reduced = true});
    for (std::size_t i = 0; i < optics.size(); ++i) {
        const auto& o = optics[i];
        if (!o.mu_s_reduced_per_cm) {
            throw InputError("layer '" + stack.layers[i].name +
                             "' has no reduced scattering (set reduced_scattering_table or reduced_scattering_* for the diffusion modes)");
        }
        specs.push_back({stack.layers[i].name, o.thickness_cm * 10.0, o.mu_a_per_cm / 10.0, *o.mu_s_reduced_per_cm / 10.0,
                         o.refractive_index, o.refractive_index});
    }
    const auto bottom = has_reflector(stack.bottom) ? DiffusionBottom::reflector : DiffusionBottom::open;
    return build(std::move(specs), stack.above_refractive_index, stack.below_refractive_index, bottom, false, options, incidence_deg,
                 bottom_reflectance(stack, wavelength_nm));
}

DiffusionMaterial diffusion_material(const HomogeneousMaterial& m, std::size_t band, const DiffusionOptions& options, double incidence_deg) {
    const double n = m.relative_refractive_index;
    SlabSpec spec{m.name, std::numeric_limits<double>::infinity(), m.absorption_per_mm.at(band), m.reduced_scattering_per_mm.at(band), n, n};
    return build({spec}, 1.0, 1.0, DiffusionBottom::open, true, options, incidence_deg);
}

namespace {


// R as `geometry` measures it: sce leaves out the first-surface (specular) reflection.
WavelengthResult row(const DiffusionMaterial& m, double wavelength_nm, const Quantities& q, MeasurementGeometry geometry) {
    WavelengthResult w;
    w.wavelength_nm = wavelength_nm;
    if (q.reflectance) {
        w.reflectance = {m.total_reflectance() - (geometry == MeasurementGeometry::sce ? m.specular_reflectance : 0.0), 0.0};
        w.specular_reflectance = {m.specular_reflectance, 0.0};
    }
    if (q.transmittance) w.transmittance = {m.total_transmittance(), 0.0};
    return w;
}

SpectralResult base_result(const std::string& name, const SpectralRequest& request, const DiffusionOptions& options) {
    SpectralResult r;
    r.model = std::string(to_string(options.mode));
    r.material = name;
    r.quantities = request.quantities;
    r.has_uncertainty = false;
    r.settings["incidence_deg"] = request.incidence_deg;
    r.settings["surface_roughness"] = options.surface_roughness ? *options.surface_roughness : 0.0;
    return r;
}

}  // namespace

SpectralResult solve_diffusion_spectrum(const LayerStack& stack, const SpectralRequest& request, const DiffusionOptions& options) {
    auto result = base_result(stack.name, request, options);
    for (const double nm : request.wavelengths.nm()) {
        if (request.cancel && request.cancel->load()) {
            result.partial = true;
            break;
        }
        const auto m = diffusion_material(stack, nm, options, request.incidence_deg);
        if (result.layer_names.empty()) result.layer_names = m.slab_names;
        for (const auto& w : m.warnings) result.warnings.push_back(result_warning(w, fmt::format("{:g} nm", nm)));
        result.wavelengths.push_back(row(m, nm, request.quantities, request.geometry));
    }
    return result;
}

SpectralResult solve_diffusion_bands(const HomogeneousMaterial& material, const SpectralRequest& request, const DiffusionOptions& options) {
    auto result = base_result(material.name, request, options);
    result.bands = material.bands;
    result.layer_names = {material.name};
    for (std::size_t b = 0; b < material.bands.size(); ++b) {
        const auto m = diffusion_material(material, b, options, request.incidence_deg);
        for (const auto& w : m.warnings) result.warnings.push_back(result_warning(w, "band " + material.bands[b]));
        result.wavelengths.push_back(row(m, 0.0, request.quantities, request.geometry));
    }
    return result;
}

ResultWarning result_warning(const TrustWarning& w, const std::string& at) {
    // Worded once (a sweep's members each carry a few).
    static const std::string albedo = fmt::format("{}reduced albedo below {} (not trustworthy there)", diffusion_warning_prefix, diffusion_min_reduced_albedo);
    static const std::string thin =
        fmt::format("{}slab thinner than {} transport mean free paths (not trustworthy there)", diffusion_warning_prefix, diffusion_min_slab_mean_free_paths);
    static const std::string merged = fmt::format("{}layer thinner than {} transport mean free paths, merged with its neighbour (fully below {})",
                                                  diffusion_warning_prefix, diffusion_merge_none_above_mfp, diffusion_merge_fully_below_mfp);
    return {w.kind == "albedo" ? albedo : w.kind == "thin" ? thin : merged, w.slab, at, w.value};
}

}  // namespace skinspec
