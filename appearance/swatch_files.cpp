#include "appearance/swatch_files.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "materials/material_fields.hpp"
#include "skinspec/version.hpp"
#include "spectral/chart_image.hpp"
#include "spectral/color_management.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

// "epidermis.melanosome_fraction: volume fraction of melanosomes (v_m), unit 1, log spacing".
std::string axis_title(const ParameterSweep& sweep) {
    const auto row = describe_field(sweep.field);
    std::string title = sweep.field;
    if (row) title += ": " + row->doc + (row->unit.empty() || row->unit == "1" ? std::string(" (unitless)") : " (" + row->unit + ")");
    return title + (sweep.log ? ", log spacing" : "");
}

std::vector<std::string> axis_values(const ParameterSweep& sweep) {
    std::vector<std::string> out;
    for (const double v : sweep.values()) out.push_back(fmt::format("{:.3g}", v));
    return out;
}

}  // namespace

SwatchFiles check_swatch_files(const SwatchFiles& files, const SwatchRequest& request) {
    if (files.patch_px < 32 || files.patch_px > 2048) throw InputError("--patch-size " + std::to_string(files.patch_px) + " is outside [32, 2048]");
    if (!files.images.files.empty()) {
        check_chart_size({request.sweeps.empty() ? 1 : request.sweeps[0].steps, request.sweeps.size() < 2 ? 1 : request.sweeps[1].steps, files.patch_px, 8});
    }
    return {check_image_outputs(files.images), files.patch_px};
}

void write_swatch_files(const SwatchChart& chart, const SwatchRequest& request, const SwatchFiles& files) {
    const auto& images = files.images;
    if (images.files.empty()) return;
    const auto& cm = ColorManagement::builtin();
    std::vector<RGB> working;
    std::vector<std::string> labels;  // each patch's sRGB value (the parameters are on the chart's axes)
    for (const auto& p : chart.patches) {
        working.push_back(cm.from_xyz(p.xyz, chart.white, images.space));
        labels.push_back(hex_rgb8(cm.from_xyz(p.xyz, chart.white, "sRGB")));
    }
    ImageMetadata metadata{{"Software", std::string("skinspec ") + version},
                           {"skinspec:model", request.solver},
                           {"skinspec:material", request.material},
                           {"skinspec:seed", std::to_string(request.seed)},
                           {"skinspec:partial", chart.partial ? "true" : "false"}};
    std::string parameters;
    for (const auto& s : request.sweeps) parameters += (parameters.empty() ? "" : "; ") + s.text();
    for (const auto& ov : request.overrides) parameters += "; set " + ov.key + "=" + ov.value;
    metadata.push_back({"skinspec:parameters", parameters});
    // Each patch's standard uncertainty (from R's standard errors and the solver's stated error), in patch order.
    std::string lab_uncertainty;
    double worst = 0.0;
    for (const auto& p : chart.patches) {
        lab_uncertainty += fmt::format("{}{:.3g} {:.3g} {:.3g}", lab_uncertainty.empty() ? "" : "; ", p.uncertainty.lab.L, p.uncertainty.lab.a, p.uncertainty.lab.b);
        worst = std::max(worst, p.uncertainty.delta_e2000);
    }
    metadata.push_back({"skinspec:lab_uncertainty", lab_uncertainty});
    metadata.push_back({"skinspec:worst_delta_e2000_uncertainty", fmt::format("{:.4g}", worst)});
    for (const auto& [k, v] : chart.settings) {
        metadata.push_back({"skinspec:" + k, std::visit([](const auto& x) { return fmt::format("{}", x); }, v)});
    }
    const auto geometry = std::string(to_string(request.geometry));
    metadata.push_back({"ImageDescription", "skinspec swatch: " + request.material + ", " + parameters + "; geometry " + geometry});

    const ChartLayout layout{chart.columns, chart.rows, files.patch_px, 8};
    ChartAxes axes;
    if (!request.sweeps.empty()) {
        axes.column_title = axis_title(request.sweeps[0]) + " (" + geometry + ")";
        axes.column_values = axis_values(request.sweeps[0]);
    }
    if (request.sweeps.size() > 1) {
        axes.row_title = axis_title(request.sweeps[1]);
        axes.row_values = axis_values(request.sweeps[1]);
    }
    for (const auto& out : images.files) {
        if (out.extension() == ".exr") write_linear_chart(out, layout, working, images.space, images.half, metadata, cm);
        else write_display_chart(out, layout, working, labels, images.space, images.display, images.view, metadata, cm, axes);
    }
}

}  // namespace skinspec
