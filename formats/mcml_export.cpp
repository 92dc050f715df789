#include "formats/mcml_export.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"

namespace skinspec {
namespace {

void check_range(double value, double lo, double hi, const std::string& what, bool open_low = false) {
    if (!(std::isfinite(value) && (open_low ? value > lo : value >= lo) && value <= hi)) {
        throw InputError(fmt::format("{} = {} is outside {}{}, {}]", what, format_number(value), open_low ? "(" : "[", format_number(lo), format_number(hi)));
    }
}

// The HG layer MCML runs for `layer` (same mean cosine), and what was substituted, if anything.
std::string hg_substitution(RteLayer& layer) {
    const auto kind = layer.phase.kind;
    const double g = layer.phase.mean_cosine();
    layer.phase = PhaseFunction::henyey_greenstein(g);
    switch (kind) {
        case PhaseFunction::Kind::henyey_greenstein: return {};
        case PhaseFunction::Kind::isotropic: return {};
        case PhaseFunction::Kind::two_term_hg: return "two-term HG -> HG of the same mean cosine";
        case PhaseFunction::Kind::rayleigh: return "Rayleigh -> isotropic (HG g = 0, Rayleigh's mean cosine)";
        case PhaseFunction::Kind::tabulated: return "the measured (tabulated) phase function -> HG of its mean cosine";
    }
    return {};
}

}  // namespace

std::vector<std::string> mcml_export_comments(const McmlExport& exported, const std::string& material, const std::vector<double>& wavelengths_nm) {
    std::string list;
    for (const double nm : wavelengths_nm) list += (list.empty() ? "" : ",") + fmt::format("{:g}", nm);
    std::vector<std::string> comments{fmt::format("skinspec export mcml: {}, its volumetric description at {} nm (one run each)", material, list),
                                      "MCML holds HG layers and a Fresnel bottom only; substituted:"};
    for (const auto& s : exported.substitutions) comments.push_back("  " + s);
    comments.push_back("diffuse R by adding-doubling, this file's stack against the material's own description:");
    for (std::size_t i = 0; i < exported.runs.size(); ++i) {
        comments.push_back(fmt::format("  {:g} nm: {:.5f} against {:.5f} ({:+.5f})", wavelengths_nm[i], exported.exported_reflectance[i],
                                       exported.own_reflectance[i], exported.exported_reflectance[i] - exported.own_reflectance[i]));
    }
    return comments;
}

McmlExport mcml_export(const LayerStack& stack, const McmlExportRequest& request) {
    if (request.wavelengths_nm.empty()) throw InputError("export mcml: no wavelengths");
    for (const double nm : request.wavelengths_nm) check_range(nm, 250.0, 2500.0, "wavelength [nm]");
    check_range(static_cast<double>(request.photons), 100.0, 1e15, "--photons");
    check_range(request.reach_mm, 0.0, 1000.0, "--reach [mm]", true);
    check_range(request.ring_mm, 0.0, request.reach_mm, "--ring [mm]", true);
    check_range(request.depth_bin_mm, 0.0, 1000.0, "--depth-bin [mm]", true);
    const double rings = std::round(request.reach_mm / request.ring_mm);
    if (rings > 100000.0) throw InputError(fmt::format("--reach / --ring = {} rings is more than 100000", format_number(rings)));
    McmlExport out;
    const auto note = [&](const std::string& text) {
        if (!text.empty() && std::find(out.substitutions.begin(), out.substitutions.end(), text) == out.substitutions.end()) out.substitutions.push_back(text);
    };
    AdCache cache;
    for (const double nm : request.wavelengths_nm) {
        const auto own = rte_stack_from(stack, nm);
        auto exported = own;
        for (std::size_t k = 0; k < exported.layers.size(); ++k) {
            const auto what = hg_substitution(exported.layers[k]);
            if (!what.empty()) note(fmt::format("layer {} ({}): {}", k + 1, stack.layers[k].name, what));
        }
        if (exported.bottom_reflector) {
            note(fmt::format("the Lambertian bottom reflector (reflectance {:g}) has no MCML form: left out, light reaching the bottom leaves "
                             "through it (T) into a medium of the last layer's index",
                             exported.bottom_reflectance));
            exported.bottom_reflector = false;
            exported.below_refractive_index = exported.layers.back().refractive_index;
        }
        McmlRun run;
        run.output_file = fmt::format("{}_{:g}nm.mco", request.output_stem, nm);
        run.photons = request.photons;
        double depth_cm = 0.0;
        for (const auto& l : exported.layers) depth_cm += l.thickness_cm;
        run.grid = RteGrid{request.depth_bin_mm / 10.0, request.ring_mm / 10.0,
                           static_cast<int>(std::clamp(std::ceil(depth_cm / (request.depth_bin_mm / 10.0)), 1.0, 10000.0)), static_cast<int>(rings),
                           request.angle_bins};
        const auto exported_r = solve_adding_doubling(exported, {}, {}, &cache);
        const auto own_r = solve_adding_doubling(own, {}, {}, &cache);
        out.exported_reflectance.push_back(exported_r.diffuse_reflectance);
        out.own_reflectance.push_back(own_r.diffuse_reflectance);
        run.stack = std::move(exported);
        out.runs.push_back(std::move(run));
    }
    return out;
}

}  // namespace skinspec
