#include "transport/spectral_request.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "materials/material_fields.hpp"
#include "materials/parameter_sweep.hpp"
#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

std::string_view to_string(MeasurementGeometry geometry) {
    switch (geometry) {
        case MeasurementGeometry::sci: return "sci";
        case MeasurementGeometry::sce: return "sce";
        case MeasurementGeometry::zero_45: return "0-45";
    }
    return "?";
}

MeasurementGeometry parse_measurement_geometry(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what, std::array{MeasurementGeometry::sci, MeasurementGeometry::sce, MeasurementGeometry::zero_45},
                              "a measurement geometry");
}

Quantities parse_quantities(std::string_view text, std::string_view what) {
    Quantities q{false, false, false, false};
    std::size_t start = 0;
    while (start <= text.size()) {
        const auto comma = std::min(text.find(',', start), text.size());
        const auto item = text.substr(start, comma - start);
        if (item == "R") q.reflectance = true;
        else if (item == "T") q.transmittance = true;
        else if (item == "A") q.absorptance = true;
        else if (item == "brdf" || item == "angular") q.angular = true;
        else throw InputError(std::string(what) + ": '" + std::string(item) + "' is not a quantity (allowed: R, T, A, brdf)");
        start = comma + 1;
    }
    return q;
}

std::vector<double> default_angular_bin_edges_deg() {
    std::vector<double> edges{0.0};
    for (double e = 2.5; e < 90.0; e += 5.0) edges.push_back(e);
    edges.push_back(90.0);
    return edges;
}

std::string result_label(const SpectralResult& result) {
    auto label = result.material;
    for (std::size_t i = 0; i < result.provenance.varied.size(); ++i) label += fmt::format("{}{:g}", i == 0 ? ": " : ", ", result.provenance.varied.values[i]);
    return label;
}

std::vector<std::pair<std::string, std::string>> all_overrides(const Provenance& provenance) {
    auto all = provenance.overrides;
    for (auto& o : sweep_overrides(provenance.varied)) all.emplace_back(std::move(o.key), std::move(o.value));
    return all;
}

void check_incidence_deg(double incidence_deg) {
    if (!std::isfinite(incidence_deg) || incidence_deg < 0.0 || incidence_deg >= 90.0) {
        throw InputError("incidence angle " + format_number(incidence_deg) + " deg is outside [0, 90)");
    }
}

ResultSettings model_result_settings(const ModelOptions& model) {
    ResultSettings settings;
    for (auto& [key, value] : model_settings(model)) {
        settings[key] = std::visit([](auto&& v) -> SettingValue { return std::move(v); }, std::move(value));
    }
    return settings;
}

ResultSettings all_settings(const SpectralResult& result) {
    auto out = result.settings;
    if (result.model_settings) {
        for (const auto& [key, value] : *result.model_settings) out.insert_or_assign(key, value);
    }
    return out;
}

std::vector<std::string> summarise_warnings(const std::vector<const ResultWarning*>& warnings) {
    const auto first_seen = [](std::vector<std::string>& list, const std::string& item) {
        if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
    };
    std::vector<std::string> kinds;
    for (const auto* w : warnings) first_seen(kinds, w->kind);
    std::vector<std::string> out;
    for (const auto& kind : kinds) {
        std::vector<std::string> subjects;
        for (const auto* w : warnings) {
            if (w->kind == kind) first_seen(subjects, w->subject);
        }
        std::string line = kind + ": ";
        for (std::size_t s = 0; s < subjects.size(); ++s) {
            std::vector<const ResultWarning*> found;
            for (const auto* w : warnings) {
                if (w->kind == kind && w->subject == subjects[s]) found.push_back(w);
            }
            double lowest = INFINITY, highest = -INFINITY;
            for (const auto* w : found) {
                lowest = std::min(lowest, w->value);
                highest = std::max(highest, w->value);
            }
            line += (s ? "; " : "") + subjects[s] + " at ";
            line += found.size() == 1 ? fmt::format("{} ({:.3g})", found.front()->at, lowest)
                                      : fmt::format("{} places, {} to {} (values {:.3g} to {:.3g})", found.size(), found.front()->at,
                                                    found.back()->at, lowest, highest);
        }
        out.push_back(std::move(line));
    }
    return out;
}

std::vector<std::string> summarise_warnings(const std::vector<ResultWarning>& warnings) {
    std::vector<const ResultWarning*> each;
    for (const auto& w : warnings) each.push_back(&w);
    return summarise_warnings(each);
}

}  // namespace skinspec
