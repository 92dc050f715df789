#include "cli/spectral_output.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include <fmt/format.h>

#include "skinspec/version.hpp"
#include "transport/diffusion/diffusion_model.hpp"
#include "transport/result_quantities.hpp"
#include "spectral/line_plot.hpp"
#include "spectral/input_error.hpp"
#include "spectral/parallel_indices.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::cli {
namespace {

std::vector<double> wavelengths_of(const SpectralResult& r) {
    std::vector<double> nm;
    for (const auto& w : r.wavelengths) nm.push_back(w.wavelength_nm);
    return nm;
}

using Json = nlohmann::ordered_json;

Json setting_json(const SettingValue& v) {
    return std::visit([](const auto& x) { return Json(x); }, v);
}

// Column names, in order, with a getter each, from the result quantity table (transport/result_quantities.hpp);
// shared by CSV and the terminal tables.
struct Column {
    std::string name;
    std::function<Estimate(const WavelengthResult&)> get;
};

std::vector<Column> scalar_columns(const SpectralResult& r) {
    std::vector<Column> cols;
    for (const auto* q : quantities_of(r)) {
        for (std::size_t i = 0; i < q->count(r); ++i) cols.push_back({q->column(r, i), [q, i](const WavelengthResult& w) { return q->values(w)[i]; }});
    }
    return cols;
}

// An override's value as the material file reads it: a number, a boolean, or the text.
Json override_value(const std::string& text) {
    if (text == "true" || text == "false") return text == "true";
    if (const auto number = parse_double(text)) return *number;
    return text;
}

// `same_as`: the index of an earlier result whose material_toml is the same text (a sweep's base), written in its place.
Json provenance_json(const Provenance& p, std::optional<std::size_t> same_as) {
    Json overrides = Json::array();
    for (const auto& [key, value] : all_overrides(p)) overrides.push_back(Json{{"key", key}, {"value", override_value(value)}});
    Json varied = Json::object();
    for (std::size_t i = 0; i < p.varied.size(); ++i) varied[p.varied.field(i)] = p.varied.values[i];
    Json j{{"solver", p.solver}, {"skinspec_version", p.version}, {"overrides", overrides}, {"varied", varied}};
    if (same_as) j["material_toml_same_as"] = *same_as;
    else j["material_toml"] = *p.material_toml;
    return j;
}

Json result_json(const ReportedSpectrum& s, std::optional<std::size_t> same_material_as) {
    const auto& r = s.result;
    Json j{{"model", r.model}, {"material", r.material}, {"partial", r.partial}};
    Json settings = Json::object();
    for (const auto& [k, v] : all_settings(r)) settings[k] = setting_json(v);
    j["settings"] = settings;
    j["layers"] = r.layer_names;
    std::vector<double> nm, truncated;
    std::vector<std::uint64_t> rays;
    std::vector<bool> converged;
    for (const auto& w : r.wavelengths) {
        nm.push_back(w.wavelength_nm);
        rays.push_back(w.rays);
        converged.push_back(w.converged);
        truncated.push_back(static_cast<double>(w.truncated_rays));
    }
    if (r.bands.empty()) j["wavelength_nm"] = nm;
    else j["band"] = r.bands;
    if (r.quantities.angular) j["angular_bin_edges_deg"] = r.angular_bin_edges_deg;
    for (const auto* q : quantities_of(r)) {
        // A scalar is one array over the wavelengths, the others one array per wavelength; every one has a
        // *_stderr twin when the solver states standard errors.
        Json values = Json::array(), errors = Json::array();
        for (const auto& w : r.wavelengths) {
            const auto estimates = q->values(w);
            if (q->shape == QuantityShape::scalar) {
                values.push_back(estimates.front().value);
                errors.push_back(estimates.front().stderr);
                continue;
            }
            std::vector<double> v, e;
            for (const auto& x : estimates) {
                v.push_back(x.value);
                e.push_back(x.stderr);
            }
            values.push_back(std::move(v));
            errors.push_back(std::move(e));
        }
        j[std::string(q->key)] = std::move(values);
        if (r.has_uncertainty) j[std::string(q->key) + "_stderr"] = std::move(errors);
    }
    if (r.has_uncertainty) {
        j["rays"] = rays;
        j["converged"] = converged;
        j["truncated_rays"] = truncated;
    }
    Json warnings = Json::array();
    for (const auto& w : r.warnings) warnings.push_back(Json{{"kind", w.kind}, {"subject", w.subject}, {"at", w.at}, {"value", w.value}});
    j["warnings"] = warnings;
    if (const auto& e = r.stated_error) {
        j["stated_error"] = Json{{"R", e->R}, {"meaning", *e->meaning}};
        if (e->delta_e2000) j["stated_error"]["delta_e2000"] = *e->delta_e2000;
    }
    j["provenance"] = provenance_json(r.provenance, same_material_as);
    j["seconds"] = s.seconds;
    if (s.color) j["color"] = to_json(*s.color);
    return j;
}

// The text of items [0, n) written to `out` in order, formatted a block of items at a time, the blocks in parallel:
// a sweep's 12,288 CSV rows and table lines were formatted one by one into strings held whole (6 MB of fresh
// memory, a quarter of a dipole sweep's time).
void write_in_order(std::ostream& out, std::size_t n, const std::function<void(std::size_t, fmt::memory_buffer&)>& format) {
    constexpr std::size_t items_per_block = 256, blocks_at_once = 16;
    std::vector<fmt::memory_buffer> blocks(blocks_at_once);
    for (std::size_t first = 0; first < n; first += items_per_block * blocks_at_once) {
        const std::size_t count = std::min(blocks_at_once, (n - first + items_per_block - 1) / items_per_block);
        parallel_indices(count, [&](std::size_t b) {
            auto& text = blocks[b];
            text.clear();
            const std::size_t begin = first + b * items_per_block, end = std::min(n, begin + items_per_block);
            for (std::size_t i = begin; i < end; ++i) format(i, text);
        });
        for (std::size_t b = 0; b < count; ++b) out.write(blocks[b].data(), static_cast<std::streamsize>(blocks[b].size()));
    }
}

}  // namespace

std::optional<ColorSummary> reflectance_color(const SpectralResult& result, IlluminantKind illuminant, ObserverKind observer) {
    if (!result.quantities.reflectance) return std::nullopt;
    std::vector<double> nm, r, stderrs;
    for (const auto& w : result.wavelengths) {
        nm.push_back(w.wavelength_nm);
        r.push_back(w.reflectance.value);
        stderrs.push_back(result.has_uncertainty ? w.reflectance.stderr : 0.0);
    }
    if (!has_color_span(nm)) return std::nullopt;
    const TristimulusWeights weights(nm, illuminant, observer, OutOfRangePolicy::hold);
    const double stated = result.stated_error ? result.stated_error->R : 0.0;
    std::optional<ColorUncertainty> uncertainty;
    if (result.has_uncertainty || result.stated_error) uncertainty = color_uncertainty(weights, r, stderrs, stated);
    return summarize_color(weights.integrate(r), weights, illuminant, observer, {}, uncertainty);
}

Json to_json(const ReportedSpectra& spectra) {
    Json results = Json::array();
    // A sweep's members share their base material: its text is written once, in the first result that has it.
    std::vector<std::pair<const std::string*, std::size_t>> first_with;  // (material TOML, result index)
    for (std::size_t i = 0; i < spectra.size(); ++i) {
        const auto* toml = spectra[i].result.provenance.material_toml.get();
        const auto earlier = std::find_if(first_with.begin(), first_with.end(), [&](const auto& f) { return f.first == toml || *f.first == *toml; });
        std::optional<std::size_t> same_as;
        if (earlier != first_with.end()) same_as = earlier->second;
        else first_with.emplace_back(toml, i);
        results.push_back(result_json(spectra[i], same_as));
    }
    return Json{{"skinspec_version", version}, {"schema", "skinspec-spectral-result/1"}, {"results", results}};
}

void write_csv(std::ostream& out, const ReportedSpectra& spectra) {
    std::string head = fmt::format("# skinspec {} spectral result (docs/RESULTS_SCHEMA.md)\n", version);
    head += "# units: wavelength_nm [nm]";
    for (const auto& q : result_quantities()) {
        const auto column = q.shape == QuantityShape::scalar ? std::string(q.key) : std::string(q.key.substr(0, q.key.find('_'))) + "_*";
        head += "; " + column + " [" + (q.unit == "1" ? std::string("fraction of incident flux") : std::string(q.unit)) + "]";
    }
    head += "; *_stderr: standard error of the column before it\n";
    out << head;
    // A sweep's members share their settings and base material: each is written once, each member's overrides on
    // its own provenance line. Which results write their material text (the first of each name and text):
    std::vector<char> writes_material(spectra.size(), 0);
    std::vector<std::pair<std::string_view, const std::string*>> written;  // (name, material TOML)
    for (std::size_t i = 0; i < spectra.size(); ++i) {
        const auto& r = spectra[i].result;
        const auto* toml = r.provenance.material_toml.get();
        if (std::any_of(written.begin(), written.end(), [&](const auto& w) { return w.first == r.material && (w.second == toml || *w.second == *toml); })) continue;
        written.emplace_back(r.material, toml);
        writes_material[i] = 1;
    }
    write_in_order(out, spectra.size(), [&](std::size_t i, fmt::memory_buffer& text) {
        const auto& r = spectra[i].result;
        const auto* previous = i > 0 ? &spectra[i - 1].result : nullptr;
        auto to = fmt::appender(text);
        const auto same_model_settings = [&] {
            return previous->model_settings == r.model_settings ||
                   (previous->model_settings && r.model_settings && *previous->model_settings == *r.model_settings);
        };
        if (!previous || previous->material != r.material || previous->model != r.model || previous->partial != r.partial ||
            previous->settings != r.settings || !same_model_settings()) {
            fmt::format_to(to, "# material {}: model {}, partial {}", r.material, r.model, r.partial);
            for (const auto& [k, v] : all_settings(r)) fmt::format_to(to, ", {} {}", k, std::visit([](const auto& x) { return fmt::format("{}", x); }, v));
            text.push_back('\n');
        }
        const auto& p = r.provenance;
        fmt::format_to(to, "# provenance {}: solver {}, skinspec {}, overrides", r.material, p.solver, p.version);
        const auto overrides = all_overrides(p);
        if (overrides.empty()) fmt::format_to(to, " none");
        for (const auto& [key, value] : overrides) fmt::format_to(to, " {}={}", key, value);
        if (const auto& e = r.stated_error) {
            // Its meaning is written when it differs from the result before.
            const auto& before = previous ? previous->stated_error : std::nullopt;
            const bool repeated = before && (before->meaning == e->meaning || *before->meaning == *e->meaning);
            fmt::format_to(to, ", stated error of R {:.6g}", e->R);
            if (e->delta_e2000) fmt::format_to(to, ", CIEDE2000 {:.4g}", *e->delta_e2000);
            fmt::format_to(to, " ({})", repeated ? std::string_view("as above") : std::string_view(*e->meaning));
        }
        text.push_back('\n');
        if (!writes_material[i]) return;
        fmt::format_to(to, "# material_toml {}:\n", r.material);
        const std::string_view toml = *p.material_toml;
        for (std::size_t from = 0; from < toml.size();) {
            const auto end = std::min(toml.find('\n', from), toml.size());
            fmt::format_to(to, "#   {}\n", toml.substr(from, end - from));
            from = end + 1;
        }
    });
    if (spectra.empty()) return;
    const auto& first = spectra.front().result;
    const auto columns = scalar_columns(first);
    const bool uncertain = first.has_uncertainty;
    std::string header = "material";
    for (std::size_t f = 0; f < first.provenance.varied.size(); ++f) header += "," + first.provenance.varied.field(f);
    header += first.bands.empty() ? ",wavelength_nm" : ",band";
    for (const auto& c : columns) header += "," + c.name + (uncertain ? "," + c.name + "_stderr" : "");
    header += uncertain ? ",rays,converged\n" : "\n";
    out << header;
    write_in_order(out, spectra.size(), [&](std::size_t m, fmt::memory_buffer& text) {
        const auto& r = spectra[m].result;
        auto to = fmt::appender(text);
        for (std::size_t i = 0; i < r.wavelengths.size(); ++i) {
            const auto& w = r.wavelengths[i];
            fmt::format_to(to, "{}", r.material);
            for (const double value : r.provenance.varied.values) fmt::format_to(to, ",{:.9g}", value);
            if (r.bands.empty()) fmt::format_to(to, ",{:g}", w.wavelength_nm);
            else fmt::format_to(to, ",{}", r.bands[i]);
            for (const auto& c : columns) {
                const auto e = c.get(w);
                if (uncertain) fmt::format_to(to, ",{:.9g},{:.3g}", e.value, e.stderr);
                else fmt::format_to(to, ",{:.9g}", e.value);
            }
            if (uncertain) fmt::format_to(to, ",{},{}\n", w.rays, w.converged ? 1 : 0);
            else text.push_back('\n');
        }
    });
}

std::string to_table(const ReportedSpectra& spectra) {
    std::string out;
    if (spectra.empty()) return out;
    const auto& first = spectra.front().result;
    const bool uncertain = first.has_uncertainty;
    const auto key_header = fmt::format("{:>13}", first.bands.empty() ? "wavelength_nm" : "band");
    const auto key = [&](const SpectralResult& r, std::size_t i) {
        return r.bands.empty() ? fmt::format("{:>13g}", r.wavelengths[i].wavelength_nm) : fmt::format("{:>13}", r.bands[i]);
    };
    const auto estimate = [&](const Estimate& e) {
        return uncertain ? fmt::format("{:.4f} +- {:.4f}", e.value, e.stderr) : fmt::format("{:.4f}", e.value);
    };
    const bool reflectance_of_each =
        std::all_of(spectra.results.begin(), spectra.results.end(), [](const SpectralResult& r) { return r.quantities.reflectance; });
    if (spectra.size() > 1 && reflectance_of_each) {
        // Side by side: total reflectance of every material.
        out += key_header;
        for (const auto& r : spectra.results) out += fmt::format("  {:>22}", r.material.substr(0, 22));
        out += '\n';
        const auto rows = first.wavelengths.size();
        for (std::size_t i = 0; i < rows; ++i) {
            out += key(first, i);
            for (const auto& r : spectra.results) {
                if (i < r.wavelengths.size()) out += fmt::format("  {:>22}", "R " + estimate(r.wavelengths[i].reflectance));
            }
            out += '\n';
        }
    } else {
        // Each material's requested quantities (without R, side by side would show a quantity nobody asked for).
        for (const auto& r : spectra.results) {
            if (spectra.size() > 1) out += (&r == &first ? "" : "\n") + r.material + ":\n";
            const auto columns = scalar_columns(r);
            out += key_header;
            for (const auto& c : columns) out += fmt::format("  {:>20}", c.name.substr(0, 20));
            out += uncertain ? fmt::format("  {:>10}\n", "rays") : "\n";
            for (std::size_t i = 0; i < r.wavelengths.size(); ++i) {
                const auto& w = r.wavelengths[i];
                out += key(r, i);
                for (const auto& c : columns) out += fmt::format("  {:>20}", estimate(c.get(w)));
                out += uncertain ? fmt::format("  {:>10}\n", w.rays) : "\n";
            }
        }
    }
    out += '\n';
    for (std::size_t k = 0; k < spectra.size(); ++k) {
        const auto s = spectra[k];
        std::uint64_t rays = 0, truncated = 0;
        bool all_converged = true;
        for (const auto& w : s.result.wavelengths) {
            rays += w.rays;
            truncated += w.truncated_rays;
            all_converged = all_converged && w.converged;
        }
        if (s.result.has_uncertainty) {
            const char* rows = s.result.bands.empty() ? "wavelengths" : "bands";
            out += fmt::format("{}: {} {}, {} rays in {:.2f} s{}{}{}\n", s.result.material, s.result.wavelengths.size(), rows, rays, s.seconds,
                               all_converged ? "" : fmt::format("; standard error target NOT met at some {} (budget spent)", rows),
                               truncated ? fmt::format("; {} rays stopped at the event limit", truncated) : "",
                               s.result.partial ? "; PARTIAL (interrupted)" : "");
        } else {
            out += fmt::format("{}: {} {} ({} model, deterministic) in {:.3f} s{}\n", s.result.material, s.result.wavelengths.size(),
                               s.result.bands.empty() ? "wavelengths" : "bands", s.result.model, s.seconds,
                               s.result.partial ? "; PARTIAL (interrupted)" : "");
        }
        if (const auto& e = s.result.stated_error) {
            out += fmt::format("  stated error of R: {:.4f}{} ({})\n", e->R,
                               e->delta_e2000 ? fmt::format(", colour CIEDE2000 {:.2f}", *e->delta_e2000) : std::string(), *e->meaning);
        }
        if (s.color) {
            const auto& u = s.color->uncertainty;
            out += fmt::format("  colour of R under {} ({} observer, held outside {:g}-{:g} nm): XYZ {:.4f} {:.4f} {:.4f}, "
                               "Lab {:.2f} {:.2f} {:.2f}{}, {}sRGB {}{}\n",
                               short_name(s.color->illuminant), display_name(s.color->observer),
                               s.result.wavelengths.front().wavelength_nm, s.result.wavelengths.back().wavelength_nm,
                               s.color->xyz.X, s.color->xyz.Y, s.color->xyz.Z, s.color->lab.L, s.color->lab.a, s.color->lab.b,
                               u ? fmt::format(" +- {:.2f} {:.2f} {:.2f} (CIEDE2000 +- {:.2f})", u->lab.L, u->lab.a, u->lab.b, u->delta_e2000) : std::string(),
                               s.color->skin_tone ? fmt::format("ITA {:.1f} deg ({}), ", s.color->skin_tone->ita_deg, to_string(s.color->skin_tone->category)) : std::string(),
                               s.color->srgb_hex, s.color->srgb_in_gamut ? "" : " (clipped: outside sRGB)");
        } else if (s.result.bands.empty()) {
            out += "  no colour: " + color_span_problem(wavelengths_of(s.result)) + "\n";
        }
    }
    return out;
}

void write_sweep_table(std::ostream& out, const ReportedSpectra& spectra) {
    if (spectra.empty()) return;
    const auto& first = spectra.front().result;
    std::string header = fmt::format("{:<22}", "material");
    for (std::size_t f = 0; f < first.provenance.varied.size(); ++f) header += fmt::format("  {:>30}", first.provenance.varied.field(f).substr(0, 30));
    // A sweep at one wavelength (or band) has no colours to show: its R is the column that tells the members apart.
    const bool one_row = first.quantities.reflectance &&
                         std::all_of(spectra.results.begin(), spectra.results.end(), [](const auto& r) { return r.wavelengths.size() == 1; });
    if (one_row) {
        header += fmt::format("  {:>20}", first.bands.empty() ? fmt::format("R at {:g} nm", first.wavelengths.front().wavelength_nm) : "R, band " + first.bands.front());
    }
    header += fmt::format("  {:>9}  {:<22}  {:<24}  {:>9}  {:>12}  {:>10}\n", "sRGB", "Lab", "ITA deg (category)", "dE00 +-", "worst stderr", "rays");
    out << header;
    write_in_order(out, spectra.size(), [&](std::size_t i, fmt::memory_buffer& text) {
        const auto s = spectra[i];
        auto to = fmt::appender(text);
        fmt::format_to(to, "{:<22}", std::string_view(s.result.material).substr(0, 22));
        for (const double value : s.result.provenance.varied.values) fmt::format_to(to, "  {:>30.6g}", value);
        if (one_row) {
            const auto& r = s.result.wavelengths.front().reflectance;
            if (s.result.has_uncertainty) fmt::format_to(to, "  {:>20}", fmt::format("{:.4f} +- {:.4f}", r.value, r.stderr));
            else fmt::format_to(to, "  {:>20.4f}", r.value);
        }
        double worst = 0.0;
        std::uint64_t rays = 0;
        for (const auto& w : s.result.wavelengths) {
            worst = std::max({worst, w.reflectance.stderr, w.transmittance.stderr});
            rays += w.rays;
        }
        const auto lab = s.color ? fmt::format("{:.2f} {:.2f} {:.2f}", s.color->lab.L, s.color->lab.a, s.color->lab.b) : std::string("-");
        const auto spread = s.color && s.color->uncertainty ? fmt::format("{:.2f}", s.color->uncertainty->delta_e2000) : std::string("-");
        const auto tone = s.color && s.color->skin_tone ? fmt::format("{:.1f} ({})", s.color->skin_tone->ita_deg, to_string(s.color->skin_tone->category))
                                                         : std::string("-");
        fmt::format_to(to, "  {:>9}  {:<22}  {:<24}  {:>9}  {:>12}  {:>10}\n", s.color ? s.color->srgb_hex : "-", lab, tone, spread,
                       s.result.has_uncertainty ? fmt::format("{:.4f}", worst) : std::string("-"), s.result.has_uncertainty ? rays : 0);
    });
    const bool partial = std::any_of(spectra.results.begin(), spectra.results.end(), [](const auto& r) { return r.partial; });
    out << fmt::format("{} results (rays per result: traced once and shared where replayed){}\n", spectra.size(), partial ? "; PARTIAL (interrupted)" : "");
    if (!first.wavelengths.empty() && first.bands.empty() && !spectra.front().color) out << "no colours (sRGB, Lab: -): " + color_span_problem(wavelengths_of(first)) + "\n";
}

void write_plot(const std::string& file, const ReportedSpectra& spectra) {
    std::vector<PlotCurve> curves;
    const bool any_t = std::any_of(spectra.results.begin(), spectra.results.end(), [](const auto& r) { return r.quantities.transmittance; });
    // Curves take their skin's colour; without colours (a short range, one wavelength) each its own colour and marker.
    const bool coloured = std::all_of(spectra.colors.begin(), spectra.colors.end(), [](const auto& c) { return c != nullptr; });
    for (std::size_t k = 0; k < spectra.size(); ++k) {
        const auto s = spectra[k];
        const auto style = distinct_series_style(k);
        const auto curve = [&](const char* quantity, auto get, bool dashed) {
            PlotCurve c{(any_t ? quantity + std::string(" ") : std::string()) + result_label(s.result), {}, {}, {}, coloured ? s.color->srgb : style.colour, dashed, coloured ? 0 : style.marker};
            for (const auto& w : s.result.wavelengths) {
                c.x.push_back(w.wavelength_nm);
                c.value.push_back(get(w).value);
                c.stderr.push_back(get(w).stderr);
            }
            curves.push_back(std::move(c));
        };
        if (s.result.quantities.reflectance) curve("R", [](const WavelengthResult& w) { return w.reflectance; }, false);
        if (s.result.quantities.transmittance) curve("T", [](const WavelengthResult& w) { return w.transmittance; }, true);
    }
    const bool uncertain = !spectra.empty() && spectra.front().result.has_uncertainty;
    std::string varied;
    if (!spectra.empty()) {
        const auto& swept = spectra.front().result.provenance.varied;
        for (std::size_t f = 0; f < swept.size(); ++f) varied += (varied.empty() ? "" : ", ") + swept.field(f);
    }
    write_line_plot(file,
                    "skinspec " + (spectra.empty() ? std::string() : spectra.front().result.model) +
                        (uncertain ? " spectra (bands: +-2 standard errors)" : " spectra") + (varied.empty() ? "" : "; curves labelled by " + varied),
                    "Wavelength (nm)", any_t ? "Reflectance R, transmittance T (fraction)" : "Reflectance R (fraction)", curves);
}

namespace {

void print_warning_summary(const std::string& subject, const std::vector<const ResultWarning*>& warnings, const std::vector<const SpectralResult*>& results) {
    // A stated model error says with a number what diffusion's trust findings only hint at: when every result
    // states one, it replaces them on the terminal (they stay in the JSON), and it is printed once when it matters.
    const bool all_stated = !results.empty() && std::all_of(results.begin(), results.end(), [](const auto* r) { return r->stated_error.has_value(); });
    const SpectralResult* worst = nullptr;
    for (const auto* r : results) {
        if (!r->stated_error) continue;
        const auto size = [](const SpectralResult& x) { return x.stated_error->delta_e2000.value_or(0.0) * 1e3 + x.stated_error->R; };
        if (!worst || size(*r) > size(*worst)) worst = r;
    }
    if (worst && (worst->stated_error->delta_e2000.value_or(0.0) > stated_color_error_worth_a_warning ||
                  (!worst->stated_error->delta_e2000 && worst->stated_error->R > stated_R_error_worth_a_warning))) {
        const auto& e = *worst->stated_error;
        std::cerr << fmt::format("skinspec: warning: {}: {} model error{}: R off by up to {:.3f}{} ({}){}\n", subject, worst->model,
                                 results.size() > 1 ? " (the largest of the results)" : "", e.R,
                                 e.delta_e2000 ? fmt::format(", colour by CIEDE2000 {:.1f}", *e.delta_e2000) : std::string(), *e.meaning,
                                 all_stated ? "; the trust findings per layer are in the JSON" : "");
    }
    std::vector<const ResultWarning*> shown;
    for (const auto* w : warnings) {
        if (!(all_stated && w->kind.starts_with(diffusion_warning_prefix))) shown.push_back(w);
    }
    for (const auto& line : summarise_warnings(shown)) std::cerr << "skinspec: warning: " << subject << ": " << line << '\n';
}

}  // namespace

void print_warning_summary(const std::string& subject, const std::vector<ResultWarning>& warnings, const std::vector<const SpectralResult*>& results) {
    std::vector<const ResultWarning*> each;
    for (const auto& w : warnings) each.push_back(&w);
    print_warning_summary(subject, each, results);
}

void print_warning_summary(const std::string& subject, const std::vector<const SpectralResult*>& results) {
    std::vector<const ResultWarning*> each;
    for (const auto* r : results) {
        for (const auto& w : r->warnings) each.push_back(&w);
    }
    print_warning_summary(subject, each, results);
}

}  // namespace skinspec::cli
