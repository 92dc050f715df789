#include "formats/spectrum_csv.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

namespace {

// The checks every sample passes, from either format; `where` locates it ("F.csv:12: ", "F.json: result 3: ").
void check_sample(const std::string& where, const std::string& value_field, double wavelength, double value, const std::vector<double>& before,
                  const SpectrumFileRules& rules) {
    const std::string value_range = rules.allow_over_one ? "[0, inf)" : "[0, 1] (use --allow-over-one for values above 1)";
    if (!std::isfinite(wavelength) || wavelength <= 0.0) {
        throw InputError(where + "field 'wavelength_nm' = " + format_number(wavelength) + " is not allowed (allowed: finite, > 0 nm)");
    }
    if (!std::isfinite(value)) throw InputError(where + "field '" + value_field + "' = " + format_number(value) + " is not allowed (allowed: " + value_range + ")");
    if (value < 0.0 || (!rules.allow_over_one && value > 1.0)) {
        throw InputError(where + "field '" + value_field + "' = " + format_number(value) + " is outside " + value_range);
    }
    if (!before.empty() && !(wavelength > before.back())) {
        throw InputError(where + "field 'wavelength_nm' = " + format_number(wavelength) + " does not follow " + format_number(before.back()) +
                         " nm (allowed: strictly increasing wavelengths)");
    }
}

// A sweep's member is chosen the same way in both formats. Swept values match to 1e-9 relative (a CSV holds 9
// significant digits).
bool same_swept_value(double value, double wanted) { return std::abs(value - wanted) <= 1e-9 * std::max(std::abs(wanted), 1e-300); }

std::string several_match(const std::string& one, const std::string& other) {
    return "--where matches several members (" + one + "; " + other + "): give every swept field";
}

// The choice (rules.member, rules.where; `found`: whether --where found a member) against the file's members (their
// swept values, in file order): one message for each way it fails, none when it holds.
void check_member_choice(const std::string& name, const std::vector<std::string>& members, bool found, const SpectrumFileRules& rules) {
    const auto n = std::to_string(members.size());
    if (rules.member == 0 && rules.where.empty()) {
        if (members.size() > 1) {
            throw InputError(name + ": the file holds " + n + " members of a sweep (the first: " + members.front() + "); choose one with --member 1.." + n +
                             " or --where FIELD=VALUE");
        }
        return;
    }
    if (rules.member > members.size()) throw InputError(name + ": --member " + std::to_string(rules.member) + " is outside [1, " + n + "] (the file's members)");
    if (!rules.where.empty() && !found) {
        throw InputError(name + ": --where: no member matches (members: " + members.front() + (members.size() > 1 ? "; ... " + members.back() : std::string()) + ")");
    }
}

// The file's samples as a spectrum, once they are known to be at least 2 and to cover the range asked for.
SpectrumFile finished(const std::string& name, std::vector<double> wavelengths, std::vector<double> values, std::vector<double> standard_errors,
                      const SpectrumFileRules& rules) {
    if (wavelengths.size() < 2) {
        throw InputError(name + ": " + std::to_string(wavelengths.size()) + " data point(s) (allowed: at least 2)");
    }
    if (wavelengths.front() > rules.must_cover_from_nm || wavelengths.back() < rules.must_cover_to_nm) {
        throw InputError(name + ": wavelengths cover " + format_number(wavelengths.front()) + "-" +
                         format_number(wavelengths.back()) + " nm (allowed: must span at least " +
                         format_number(rules.must_cover_from_nm) + "-" + format_number(rules.must_cover_to_nm) + " nm)");
    }
    return {TabulatedSpectrum(name, std::move(wavelengths), std::move(values), rules.outside), std::move(standard_errors)};
}

// `skinspec spectrum --json` output: the results of the chosen material, the chosen member among them.
SpectrumFile read_spectrum_json(const std::string& name, std::istream& in, const SpectrumFileRules& rules) {
    using Json = nlohmann::json;
    try {
        const auto j = Json::parse(in);
        if (!j.is_object() || !j.contains("results") || !j.value("schema", std::string()).starts_with("skinspec-spectral-result/")) {
            throw InputError(name + ": a JSON file that is not a skinspec spectral result (schema skinspec-spectral-result/1)");
        }
        std::vector<const Json*> of_material;
        std::vector<std::string> materials;
        for (const auto& r : j.at("results")) {
            const auto material = r.at("material").get<std::string>();
            if (std::find(materials.begin(), materials.end(), material) == materials.end()) materials.push_back(material);
            if (rules.material.empty() ? material == materials.front() : material == rules.material) of_material.push_back(&r);
        }
        std::string seen;
        for (const auto& m : materials) seen += (seen.empty() ? "" : ", ") + m;
        if (rules.material.empty() && materials.size() > 1) throw InputError(name + ": the file holds several materials (" + seen + "); choose one with --material");
        if (of_material.empty()) throw InputError(name + ": " + (rules.material.empty() ? std::string("no results") : "--material " + rules.material + " has no results (materials: " + seen + ")"));
        const auto varied = [](const Json& r) { return r.contains("provenance") && r["provenance"].contains("varied") ? r["provenance"]["varied"] : Json::object(); };
        const auto key = [&](const Json& r) {
            std::string k;
            const auto fields = varied(r);
            for (const auto& [field, value] : fields.items()) k += (k.empty() ? "" : ", ") + field + "=" + format_number(value.get<double>());
            return k;
        };
        std::vector<std::string> members;
        for (const auto* r : of_material) members.push_back(key(*r));
        const Json* chosen = rules.member > 0 && rules.member <= of_material.size() ? of_material[rules.member - 1] : nullptr;
        for (std::size_t m = 0; m < of_material.size() && rules.member == 0 && !rules.where.empty(); ++m) {
            const auto v = varied(*of_material[m]);
            const bool match = std::all_of(rules.where.begin(), rules.where.end(),
                                           [&](const auto& w) { return v.contains(w.first) && same_swept_value(v[w.first].template get<double>(), w.second); });
            if (!match) continue;
            if (chosen) throw InputError(name + ": " + several_match(key(*chosen), members[m]));
            chosen = of_material[m];
        }
        check_member_choice(name, members, chosen != nullptr, rules);
        if (!chosen) chosen = of_material.front();
        const auto column = rules.column.empty() ? std::string("R") : rules.column;
        if (!chosen->contains(column) || column == "wavelength_nm" || !(*chosen)[column].is_array()) {
            throw InputError(name + ": --column " + column + " is not a value of the result (a quantity such as R or T)");
        }
        const auto nm = chosen->at("wavelength_nm").get<std::vector<double>>();
        const auto values = chosen->at(column).get<std::vector<double>>();
        const auto errors = chosen->contains(column + "_stderr") ? chosen->at(column + "_stderr").get<std::vector<double>>() : std::vector<double>{};
        if (values.size() != nm.size() || (!errors.empty() && errors.size() != nm.size())) {
            throw InputError(name + ": " + column + " has " + std::to_string(values.size()) + " values for " + std::to_string(nm.size()) + " wavelengths");
        }
        std::vector<double> wavelengths, kept;
        for (std::size_t i = 0; i < nm.size(); ++i) {
            check_sample(name + ": " + column + " at index " + std::to_string(i) + ": ", column, nm[i], values[i], wavelengths, rules);
            if (!errors.empty() && !(std::isfinite(errors[i]) && errors[i] >= 0.0)) {
                throw InputError(name + ": " + column + "_stderr at index " + std::to_string(i) + " = " + format_number(errors[i]) + " is outside [0, inf)");
            }
            wavelengths.push_back(nm[i]);
            kept.push_back(values[i]);
        }
        return finished(name, std::move(wavelengths), std::move(kept), errors, rules);
    } catch (const Json::exception& e) {
        throw InputError(name + ": not a readable skinspec spectral result JSON (" + e.what() + ")");
    }
}

}  // namespace

SpectrumFile read_spectrum_file(const std::filesystem::path& file, const SpectrumFileRules& rules) {
    const std::string name = file.string();
    auto in = open_input_file(file, "spectrum file");
    // A JSON result (spectrum --json) starts with '{'; anything else is read as CSV.
    in >> std::ws;
    if (in.peek() == '{') return read_spectrum_json(name, in, rules);

    std::vector<std::string> header;
    std::size_t wavelength_column = 0, value_column = 1;
    std::optional<std::size_t> material_column, stderr_column;
    std::vector<std::size_t> key_columns;  // a sweep's swept fields: the columns before wavelength_nm but material
    std::vector<std::string> members_seen;  // the chosen material's members (their key fields), in file order
    std::string member_chosen;  // the key of the member whose rows are read
    std::string value_field = rules.quantity;
    std::vector<std::string> materials_seen;
    // Chooses the columns once the header (or the first data row, without one) is known.
    const auto choose_columns = [&](std::size_t line_number) {
        const std::string where = name + ":" + std::to_string(line_number) + ": ";
        if (header.empty()) {
            if (!rules.column.empty()) throw InputError(where + "--column " + rules.column + ": the file has no header line naming columns");
            if (!rules.material.empty()) throw InputError(where + "--material " + rules.material + ": the file has no material column");
            return;
        }
        const auto find = [&](const std::string& column) -> std::optional<std::size_t> {
            const auto it = std::find(header.begin(), header.end(), column);
            return it == header.end() ? std::nullopt : std::optional<std::size_t>(static_cast<std::size_t>(it - header.begin()));
        };
        std::string names;
        for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
        wavelength_column = find("wavelength_nm").value_or(0);
        material_column = find("material");
        if (!rules.material.empty() && !material_column) throw InputError(where + "--material " + rules.material + ": the file has no material column (columns: " + names + ")");
        if (!rules.column.empty()) {
            const auto c = find(rules.column);
            if (!c || *c == wavelength_column || c == material_column) {
                throw InputError(where + "--column " + rules.column + " is not a value column of the file (columns: " + names + ")");
            }
            value_column = *c;
        } else if (header.size() == 2) {
            value_column = 1 - wavelength_column;
        } else if (const auto r = find("R")) {
            value_column = *r;
        } else {
            throw InputError(where + std::to_string(header.size()) + " columns; choose the value column with --column (columns: " + names + ")");
        }
        value_field = header[value_column];
        stderr_column = find(value_field + "_stderr");
        for (std::size_t c = 0; c < wavelength_column; ++c) {
            if (c != material_column) key_columns.push_back(c);
        }
        for (const auto& [field, value] : rules.where) {
            const auto c = find(field);
            if (!c || std::find(key_columns.begin(), key_columns.end(), *c) == key_columns.end()) {
                std::string swept;
                for (const auto k : key_columns) swept += (swept.empty() ? "" : ", ") + header[k];
                throw InputError(where + "--where " + field + ": not a swept field of the file (swept: " + (swept.empty() ? "none" : swept) + ")");
            }
        }
    };
    // Whether a row's key fields match --where (numbers equal to 1e-9 relative: the file holds 9 significant digits).
    const auto matches = [&](const std::vector<std::string_view>& fields) {
        for (const auto& [field, value] : rules.where) {
            const auto c = static_cast<std::size_t>(std::find(header.begin(), header.end(), field) - header.begin());
            const auto v = parse_double(fields[c]);
            if (!v || !same_swept_value(*v, value)) return false;
        }
        return true;
    };
    std::vector<double> wavelengths;
    std::vector<double> values, standard_errors;
    std::string line;
    std::size_t line_number = 0;
    bool seen_first_row = false;
    while (std::getline(in, line)) {
        ++line_number;
        const auto text = trim(line);
        if (text.empty() || text.front() == '#') continue;
        const std::string where = name + ":" + std::to_string(line_number) + ": ";
        const auto fields = split_fields(text);
        const bool first_row = !seen_first_row;
        seen_first_row = true;
        const bool all_text = std::none_of(fields.begin(), fields.end(), [](auto f) { return parse_double(f).has_value(); });
        if (first_row) {
            if (all_text) header.assign(fields.begin(), fields.end());
            choose_columns(line_number);
            if (all_text) continue;
        }
        const std::size_t expected = header.empty() ? 2 : header.size();
        if (fields.size() != expected) {
            throw InputError(where + std::to_string(fields.size()) + " field(s) (allowed: " + std::to_string(expected) +
                             (header.empty() ? ", wavelength_nm," + value_field : ", as the header") + ")");
        }
        if (material_column) {
            const std::string material(fields[*material_column]);
            if (std::find(materials_seen.begin(), materials_seen.end(), material) == materials_seen.end()) materials_seen.push_back(material);
            if (rules.material.empty() && materials_seen.size() > 1) {
                throw InputError(where + "the file holds several materials (" + materials_seen.front() + ", " + material +
                                 "); choose one with --material");
            }
            if (!rules.material.empty() && material != rules.material) continue;
        }
        if (!key_columns.empty()) {
            std::string key;
            for (const auto c : key_columns) key += (key.empty() ? "" : ", ") + header[c] + "=" + std::string(fields[c]);
            auto seen = std::find(members_seen.begin(), members_seen.end(), key);
            if (seen == members_seen.end()) seen = members_seen.insert(members_seen.end(), key);
            const auto position = static_cast<std::size_t>(seen - members_seen.begin()) + 1;
            const bool chosen = rules.member > 0 ? position == rules.member
                                                 : (rules.where.empty() ? members_seen.size() == 1 : matches(fields));
            if (!chosen) continue;
            if (member_chosen.empty()) member_chosen = key;
            if (key != member_chosen) {
                throw InputError(where + several_match(member_chosen, key));
            }
        }
        const auto wavelength = parse_double(fields[wavelength_column]);
        const auto value = parse_double(fields[value_column]);
        const std::string wavelength_text(fields[wavelength_column]), value_text(fields[value_column]);
        if (!wavelength) throw InputError(where + "field 'wavelength_nm' = '" + wavelength_text + "' is not a number");
        if (!value) throw InputError(where + "field '" + value_field + "' = '" + value_text + "' is not a number");
        check_sample(where, value_field, *wavelength, *value, wavelengths, rules);
        if (stderr_column) {
            const std::string text(fields[*stderr_column]);
            const auto error = parse_double(text);
            if (!error || !std::isfinite(*error) || *error < 0.0) {
                throw InputError(where + "field '" + value_field + "_stderr' = '" + text + "' is not allowed (allowed: a number in [0, inf))");
            }
            standard_errors.push_back(*error);
        }
        wavelengths.push_back(*wavelength);
        values.push_back(*value);
    }
    if ((rules.member > 0 || !rules.where.empty()) && key_columns.empty()) {
        throw InputError(name + ": " + (rules.member > 0 ? std::string("--member") : std::string("--where")) + ": the file holds no sweep (no swept fields before wavelength_nm)");
    }
    check_member_choice(name, members_seen, !member_chosen.empty(), rules);
    if (!rules.material.empty() && wavelengths.empty()) {
        std::string seen;
        for (const auto& m : materials_seen) seen += (seen.empty() ? "" : ", ") + m;
        throw InputError(name + ": --material " + rules.material + " has no rows (materials: " + seen + ")");
    }
    return finished(name, std::move(wavelengths), std::move(values), std::move(standard_errors), rules);
}

bool is_skinspec_result(const std::filesystem::path& file, const char* kind) {
    auto in = open_input_file(file, kind);
    in >> std::ws;
    if (in.peek() == '{') return true;
    std::string first;
    std::getline(in, first);
    return first.starts_with("# skinspec");
}

std::vector<NamedSpectrum> read_result_spectra(const std::filesystem::path& file, SpectrumFileRules rules) {
    // The members: (material, position among the material's members, their swept values), in file order.
    struct Member {
        std::string material;
        std::size_t position;
        std::string swept;
    };
    std::vector<Member> members;
    const auto add = [&](const std::string& material, const std::string& swept) {
        std::size_t position = 1;
        for (const auto& m : members) {
            if (m.material != material) continue;
            if (m.swept == swept) return;
            ++position;
        }
        members.push_back({material, position, swept});
    };
    auto in = open_input_file(file, "spectrum file");
    in >> std::ws;
    if (in.peek() == '{') {
        try {
            const auto j = nlohmann::json::parse(in);
            for (const auto& r : j.at("results")) {
                std::string swept;
                if (r.contains("provenance") && r["provenance"].contains("varied")) {
                    for (const auto& [field, value] : r["provenance"]["varied"].items()) swept += (swept.empty() ? "" : ";") + field + "=" + format_number(value.get<double>());
                }
                add(r.at("material").get<std::string>(), swept);
            }
        } catch (const nlohmann::json::exception& e) {
            throw InputError(file.string() + ": not a readable skinspec spectral result JSON (" + e.what() + ")");
        }
    } else {
        std::vector<std::string> header;
        std::string line;
        while (std::getline(in, line)) {
            const auto text = trim(line);
            if (text.empty() || text.front() == '#') continue;
            const auto fields = split_fields(text);
            if (header.empty()) {
                header.assign(fields.begin(), fields.end());
                continue;
            }
            if (fields.size() != header.size()) continue;  // read_spectrum_file names the row
            std::string material, swept;
            for (std::size_t c = 0; c < header.size() && header[c] != "wavelength_nm"; ++c) {
                if (header[c] == "material") material = std::string(fields[c]);
                else swept += (swept.empty() ? "" : ";") + header[c] + "=" + std::string(fields[c]);
            }
            add(material, swept);
        }
    }
    std::size_t materials = 0;
    for (std::size_t i = 0; i < members.size(); ++i) materials += members[i].position == 1 ? 1 : 0;
    std::vector<NamedSpectrum> out;
    for (const auto& m : members) {
        rules.material = materials > 1 ? m.material : std::string();
        rules.member = m.swept.empty() ? 0 : m.position;
        rules.where.clear();
        // A name without blanks or commas, so that it is one field of a CSV: "MATERIAL[FIELD=VALUE;FIELD=VALUE]".
        auto name = m.material.empty() ? file.stem().string() : m.material;
        if (!m.swept.empty()) name += fmt::format("[{}]", m.swept);
        out.push_back({std::move(name), read_spectrum_file(file, rules)});
    }
    if (out.empty()) throw InputError(file.string() + ": no spectrum (no data rows)");
    return out;
}

TabulatedSpectrum read_spectrum_csv(const std::filesystem::path& file, const SpectrumFileRules& rules) {
    return read_spectrum_file(file, rules).spectrum;
}

}  // namespace skinspec
