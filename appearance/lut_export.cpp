#include "appearance/lut_export.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "skinspec/version.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// Channel name of a reflectance sample in the OpenEXR spectral layout of Fichet, Pacanowski & Wilkie 2021
// (JCGT 10(3), Sec. 3): "T." + wavelength with a comma as decimal separator + "nm".
std::string spectral_channel(double nm) {
    auto text = format_number(nm);
    std::replace(text.begin(), text.end(), '.', ',');
    return "T." + text + "nm";
}

std::string spectra_csv(const SwatchChart& chart, const ParameterSweep& u, const ParameterSweep& v, const std::string& material) {
    std::string out = fmt::format("# skinspec {} look-up spectra: material {}, texel (column, row) = ({}, {})\n", version, material, u.field, v.field);
    out += "# units: fractions unitless; R and R_stderr unitless (reflectance in the LUT's geometry); rays per texel\n";
    out += "column,row," + u.field + "," + v.field + ",delta_e_uncertainty,L_uncertainty,a_uncertainty,b_uncertainty,rays,converged";
    for (const double nm : chart.wavelengths.nm()) out += fmt::format(",R_{}nm", format_number(nm));
    for (const double nm : chart.wavelengths.nm()) out += fmt::format(",R_stderr_{}nm", format_number(nm));
    out += '\n';
    for (std::size_t i = 0; i < chart.patches.size(); ++i) {
        const auto& p = chart.patches[i];
        out += fmt::format("{},{},{},{},{:.4g},{:.4g},{:.4g},{:.4g},{},{}", i % chart.columns, i / chart.columns, format_number(p.parameters[0]),
                           format_number(p.parameters[1]), p.uncertainty.delta_e2000, p.uncertainty.lab.L, p.uncertainty.lab.a, p.uncertainty.lab.b,
                           p.rays, p.converged ? 1 : 0);
        for (const double r : p.reflectance) out += fmt::format(",{:.9g}", r);
        for (const double s : p.reflectance_stderr) out += fmt::format(",{:.3g}", s);
        out += '\n';
    }
    return out;
}

DataImage spectra_image(const SwatchChart& chart) {
    DataImage image;
    image.width = static_cast<int>(chart.columns);
    image.height = static_cast<int>(chart.rows);
    image.channels = static_cast<int>(chart.wavelengths.size());
    image.floating_point = true;
    for (const double nm : chart.wavelengths.nm()) image.channel_names.push_back(spectral_channel(nm));
    image.values.assign(static_cast<std::size_t>(image.width) * image.height * image.channels, 0.0f);
    for (std::size_t i = 0; i < chart.patches.size(); ++i) {
        for (std::size_t w = 0; w < chart.wavelengths.size(); ++w) {
            image.values[i * chart.wavelengths.size() + w] = static_cast<float>(chart.patches[i].reflectance[w]);
        }
    }
    return image;
}

// Every `every`-th value labelled, the others blank (64 labels do not fit above 64 texels); the axis ends are in
// the texture's metadata.
std::vector<std::string> sparse_labels(const ParameterSweep& sweep, std::size_t every) {
    std::vector<std::string> out;
    const auto values = sweep.values();
    for (std::size_t i = 0; i < values.size(); ++i) {
        out.push_back(i % every == 0 ? fmt::format("{:.3g}", values[i]) : std::string());
    }
    return out;
}

ChartLayout texture_layout(const ParameterSweep& u, const ParameterSweep& v) { return {u.steps, v.steps, 1, 0}; }

ChartLayout preview_layout(const ParameterSweep& u, const ParameterSweep& v) {
    return {u.steps, v.steps, std::max(8, static_cast<int>(512 / std::max(u.steps, v.steps))), 0};
}

}  // namespace

std::string value_list(const ParameterSweep& sweep) {
    std::string out;
    for (const double v : sweep.values()) {
        if (!out.empty()) out += ',';
        out += format_number(v);
    }
    return out;
}

ParameterSweep lut_axis(const std::string& field, const std::string& text, const std::string& option) {
    try {
        return parse_sweep(field + "=" + text);
    } catch (const InputError& e) {
        throw InputError(option + " " + text + ": " + e.what() + " (FIRST:LAST:STEPS[:log])");
    }
}

LutFiles check_lut_files(const LutFiles& files, const ParameterSweep& u, const ParameterSweep& v) {
    const auto& cm = ColorManagement::builtin();
    LutFiles out = files;
    out.space = cm.canonical_space(files.space, "--space");
    space_chromaticities(out.space);
    check_chart_size(texture_layout(u, v));
    cm.check_display_view(files.display, files.view);
    check_output_path(files.texture, files.overwrite, {".exr"});
    if (!files.spectra.empty()) check_output_path(files.spectra, files.overwrite, {".exr", ".csv"});
    if (!files.preview.empty()) {
        check_output_path(files.preview, files.overwrite, {".png", ".tif", ".tiff"});
        check_chart_size(preview_layout(u, v));
    }
    load_image_module_in_background();
    return out;
}

LutSummary write_lut_files(const SwatchChart& chart, const SwatchRequest& request, const LutFiles& files) {
    const auto& cm = ColorManagement::builtin();
    const auto& u = request.sweeps.at(0);
    const auto& v = request.sweeps.at(1);
    std::vector<RGB> albedo;
    LutSummary summary;
    for (const auto& p : chart.patches) {
        albedo.push_back(cm.from_xyz(p.xyz, chart.white, files.space));
        summary.rays += p.rays;
        summary.worst_delta_e = std::max(summary.worst_delta_e, p.uncertainty.delta_e2000);
    }
    ImageMetadata metadata{{"Software", std::string("skinspec ") + version},
                           {"skinspec:content", "diffuse albedo: the colour of R (" + std::string(to_string(request.geometry)) +
                                                    ") under the illuminant, white = 1"},
                           {"skinspec:material", request.material},
                           {"skinspec:model", request.solver},
                           {"skinspec:u_field", u.field},
                           {"skinspec:u_values", value_list(u)},
                           {"skinspec:u_spacing", u.log ? "log" : "linear"},
                           {"skinspec:v_field", v.field},
                           {"skinspec:v_values", value_list(v)},
                           {"skinspec:v_spacing", v.log ? "log" : "linear"},
                           {"skinspec:v_direction", "row 0 (top) is the first value"},
                           {"skinspec:seed", std::to_string(request.seed)},
                           {"skinspec:worst_delta_e_uncertainty", fmt::format("{:.4g}", summary.worst_delta_e)},
                           {"skinspec:partial", chart.partial ? "true" : "false"}};
    for (const auto& ov : request.overrides) metadata.push_back({"skinspec:set " + ov.key, ov.value});
    for (const auto& [k, value] : chart.settings) {
        metadata.push_back({"skinspec:" + k, std::visit([](const auto& x) { return fmt::format("{}", x); }, value)});
    }
    metadata.push_back({"ImageDescription", fmt::format("skinspec look-up texture: {}; columns {} ({}), rows {} ({})", request.material, u.field,
                                                        value_list(u), v.field, value_list(v))});

    write_linear_chart(files.texture, texture_layout(u, v), albedo, files.space, files.half, metadata, cm);
    if (!files.spectra.empty()) {
        if (files.spectra.extension() == ".csv") {
            write_text_file(files.spectra, spectra_csv(chart, u, v, request.material), files.overwrite);
        } else {
            auto spectral_metadata = metadata;
            spectral_metadata.push_back({"spectralLayoutVersion", "1.0"});
            spectral_metadata.push_back({"skinspec:content", "reflectance spectra, one channel per wavelength"});
            write_atomically(files.spectra, [&](const std::filesystem::path& temporary) {
                write_data_image(temporary, spectra_image(chart), spectral_metadata);
            });
        }
    }
    if (!files.preview.empty()) {
        const ChartAxes axes{u.field + (u.log ? " (log spacing)" : ""), sparse_labels(u, 8), v.field + (v.log ? " (log spacing)" : ""),
                             sparse_labels(v, 8)};
        write_display_chart(files.preview, preview_layout(u, v), albedo, {}, files.space, files.display, files.view, metadata, cm, axes);
    }
    return summary;
}

nlohmann::ordered_json lut_summary_json(const SwatchChart& chart, const SwatchRequest& request, const LutFiles& files, const LutSummary& summary,
                                        double seconds, int processes) {
    return {{"skinspec_version", version}, {"material", request.material}, {"columns", chart.columns}, {"rows", chart.rows},
            {"space", files.space}, {"partial", chart.partial}, {"delta_e_target", request.delta_e},
            {"worst_delta_e_uncertainty", summary.worst_delta_e}, {"rays", summary.rays}, {"seconds", seconds}, {"processes", processes}};
}

}  // namespace skinspec
