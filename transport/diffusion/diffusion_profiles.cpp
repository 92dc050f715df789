#include "transport/diffusion/diffusion_profiles.hpp"

#include <cmath>

#include <fmt/format.h>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

std::size_t profile_channel_count(const Material& material, const WavelengthGrid& wavelengths) {
    return std::holds_alternative<LayerStack>(material) ? wavelengths.size() : std::get<HomogeneousMaterial>(material).bands.size();
}

SpectralProfiles diffusion_profiles(const Material& material, const WavelengthGrid& wavelengths, std::span<const double> radii_mm,
                                    const DiffusionOptions& options, bool transmittance, const std::atomic<bool>* cancel,
                                    const std::function<void(const Progress&)>& on_progress) {
    for (std::size_t i = 0; i < radii_mm.size(); ++i) {
        if (!std::isfinite(radii_mm[i]) || radii_mm[i] < 0.0) {
            throw InputError("radius = " + format_number(radii_mm[i]) + " mm is outside [0, inf)");
        }
        if (i > 0 && radii_mm[i] <= radii_mm[i - 1]) throw InputError("radii must increase (" + format_number(radii_mm[i]) + " mm follows " + format_number(radii_mm[i - 1]) + " mm)");
    }
    SpectralProfiles out;
    out.material = material_name(material);
    out.model = std::string(to_string(options.mode));
    out.radii_mm.assign(radii_mm.begin(), radii_mm.end());
    const std::size_t channels = profile_channel_count(material, wavelengths);
    const auto add = [&](const DiffusionMaterial& m, std::string label, double nm) {
        if (out.partial || (cancel && cancel->load())) {
            out.partial = true;
            return;
        }
        ChannelProfile c{std::move(label), nm, {}, {}, m.diffuse_reflectance(),
                         m.total_transmittance(), m.specular_reflectance, {}, {}};
        auto r = m.reflectance_profile(radii_mm, cancel);
        if (r.cancelled) {
            out.partial = true;
            return;
        }
        c.reflectance_per_mm2 = std::move(r.values);
        out.max_pairs = std::max(out.max_pairs, r.max_pairs);
        out.frequencies = std::max(out.frequencies, r.frequencies);
        out.converged = out.converged && r.converged;
        if (transmittance) {
            auto t = m.transmittance_profile(radii_mm, cancel);
            if (t.cancelled) {
                out.partial = true;
                return;
            }
            c.transmittance_per_mm2 = std::move(t.values);
            out.converged = out.converged && t.converged;
        }
        for (const auto& w : m.warnings) out.warnings.push_back(result_warning(w, c.label));
        out.channels.push_back(std::move(c));
        if (on_progress) on_progress(Progress{0, 0, out.channels.size(), channels});
    };
    if (const auto* stack = std::get_if<LayerStack>(&material)) {
        for (const double nm : wavelengths.nm()) {
            if (out.partial) break;
            add(diffusion_material(*stack, nm, options), fmt::format("{:g} nm", nm), nm);
        }
    } else {
        const auto& h = std::get<HomogeneousMaterial>(material);
        for (std::size_t b = 0; b < h.bands.size() && !out.partial; ++b) add(diffusion_material(h, b, options), h.bands[b], 0.0);
    }
    return out;
}

}  // namespace skinspec
