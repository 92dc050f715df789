#include "formats/rxt_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <iterator>
#include <sstream>

#include "inverse/iad/inverse_adding_doubling.hpp"
#include "spectral/input_error.hpp"
#include "spectral/input_file.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

struct Token {
    std::string text;
    std::size_t line;
};

// Whitespace-separated words, '#' to the end of a line a comment (also right after a number: "8# note").
std::vector<Token> tokens_of(std::string_view text) {
    std::vector<Token> out;
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (c == '\n') ++line;
        if (c == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
            continue;
        }
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
            continue;
        }
        const std::size_t start = i;
        while (i < text.size() && text[i] != '#' && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        out.push_back({std::string(text.substr(start, i - start)), line});
    }
    return out;
}

// The header's numbers in iad's order (its manual, "The header").
constexpr std::array header_keys{"sample_index",      "slide_index",        "sample_thickness_mm", "slide_thickness_mm", "beam_diameter_mm",
                                 "r_standard",        "spheres",            "r_sphere_mm",         "r_sample_port_mm",   "r_entrance_port_mm",
                                 "r_detector_port_mm", "r_wall",            "t_sphere_mm",         "t_sample_port_mm",   "t_third_port_mm",
                                 "t_detector_port_mm", "t_wall"};

// Letters iad knows that skinspec does not take, and why.
std::string unsupported_letter(char c) {
    switch (c) {
        case 'a': case 'A': case 'b': case 'F': case 'j':
            return "fixes an optical property (iad's constrained searches): not supported; fit without it";
        case 'e': return "sets iad's tolerance: use --tolerance";
        case 'E': return "gives absorbing slides: not supported (slides are clear)";
        case 'q': return "sets iad's quadrature points: use --channels";
        default: return "is not a letter iad's data legend knows";
    }
}

}  // namespace

RxtFile parse_rxt(std::string_view text, const std::string& name) {
    const auto tokens = tokens_of(text);
    std::size_t next = 0;
    const auto where = [&](std::size_t line) { return name + ":" + std::to_string(line) + ": "; };
    const auto last_line = [&] { return tokens.empty() ? std::size_t{1} : tokens.back().line; };
    if (text.substr(0, 4) != "IAD1") throw InputError(name + ":1: not an iad measurement file (it must start with IAD1)");
    ++next;  // the magic word
    const auto number = [&](std::string_view key) {
        if (next >= tokens.size()) throw InputError(where(last_line()) + "the header ends before " + std::string(key));
        const auto& t = tokens[next++];
        const auto v = parse_double(t.text);
        if (!v) throw InputError(where(t.line) + std::string(key) + ": '" + t.text + "' is not a number");
        return *v;
    };
    RxtFile out;
    auto& s = out.setup;
    for (const auto* key : header_keys) s.*(setup_field(key)->member) = number(key);
    if (s.slide_thickness_mm == 0.0 || s.slide_index == 0.0 || s.slide_index == 1.0) {
        s.slide_index = 1.0;
        s.slide_thickness_mm = 0.0;
    }
    if (next >= tokens.size()) throw InputError(where(last_line()) + "no data legend (a column count or letters such as 'r t') after the header");

    // The legend: a column count (one token: data may follow on the same line), or letters, the rest of the line
    // with blanks removed.
    const std::size_t legend_line = tokens[next].line;
    std::string legend = tokens[next++].text;
    const bool counted = legend.size() == 1 && legend[0] >= '1' && legend[0] <= '7';
    while (!counted && next < tokens.size() && tokens[next].line == legend_line) legend += tokens[next++].text;
    std::size_t columns = counted ? static_cast<std::size_t>(legend[0] - '0') : legend.size();
    if (!counted) {
        for (const char c : legend) {
            if (c == 'L' || c == 'r' || c == 't' || c == 'u' || c == 'M' || setup_field_by_letter(c)) continue;
            throw InputError(where(legend_line) + "data legend '" + legend + "': column letter '" + std::string(1, c) + "' " + unsupported_letter(c));
        }
        for (const char c : std::string("LrtuMSnNdDBiRTcCfgwW")) {
            if (std::count(legend.begin(), legend.end(), c) > 1) throw InputError(where(legend_line) + "data legend '" + legend + "': column '" + std::string(1, c) + "' twice");
        }
    }
    const bool w_column = legend.find('W') != std::string::npos;
    while (next < tokens.size()) {
        const std::size_t line = tokens[next].line;
        if (tokens.size() - next < columns) {
            throw InputError(where(line) + "the last row has " + std::to_string(tokens.size() - next) + " numbers, the legend " + std::to_string(columns));
        }
        SlabMeasurement row;
        row.setup = s;
        row.source = name + ":" + std::to_string(line);
        std::vector<double> values;
        for (std::size_t k = 0; k < columns; ++k) {
            const auto& t = tokens[next++];
            const auto v = parse_double(t.text);
            if (!v) throw InputError(where(t.line) + "'" + t.text + "' is not a number");
            values.push_back(*v);
        }
        if (counted) {
            // [wavelength] M_R [M_T [M_U [w [W [R [T]]]]]]: a first number above 1 is the wavelength, read beside the count.
            std::size_t k = 0;
            if (values[0] > 1.0) {
                row.wavelength_nm = values[0];
                if (next >= tokens.size()) throw InputError(where(line) + "a wavelength and no M_R");
                const auto v = parse_double(tokens[next].text);
                if (!v) throw InputError(where(tokens[next].line) + "'" + tokens[next].text + "' is not a number");
                ++next;
                values.push_back(*v);
                k = 1;
            }
            const std::size_t given = values.size() - k;
            row.m_r = values[k];
            if (given > 1) row.m_t = values[k + 1];
            if (given > 2) row.m_u = values[k + 2];
            if (given > 3) row.setup.r_wall = row.setup.t_wall = values[k + 3];
            if (given > 4) row.setup.t_wall = values[k + 4];
            if (given > 5) row.setup.r_standard = values[k + 5];
            if (given > 6) row.setup.t_standard = values[k + 6];
        } else {
            for (std::size_t k = 0; k < columns; ++k) {
                const char c = legend[k];
                const double v = values[k];
                if (c == 'L') row.wavelength_nm = v;
                else if (c == 'r') row.m_r = v;
                else if (c == 't') row.m_t = v;
                else if (c == 'u') row.m_u = v;
                else if (c == 'M') row.setup.spheres = v;
                else {
                    row.setup.*(setup_field_by_letter(c)->member) = v;
                    if (c == 'w' && !w_column) row.setup.t_wall = v;
                }
            }
            if (row.setup.slide_thickness_mm == 0.0 || row.setup.slide_index == 1.0) {
                row.setup.slide_index = 1.0;
                row.setup.slide_thickness_mm = 0.0;
            }
        }
        validate(row.setup, row.source);
        out.rows.push_back(std::move(row));
    }
    if (out.rows.empty()) throw InputError(name + ": no measurements after the data legend");
    return out;
}

RxtFile read_rxt(const std::filesystem::path& file) {
    auto in = open_input_file(file, "iad measurement file");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    return parse_rxt(text, file.string());
}

IadInput iad_input(const std::optional<std::filesystem::path>& file, const GivenMeasurements& given, const std::map<std::string, double>& setup) {
    IadInput in;
    const bool any = !given.m_r.empty() || !given.m_t.empty() || !given.m_u.empty();
    if (file) {
        if (any) throw InputError("reflectance/transmittance/unscattered: give the measurements in " + file->string() + " or as options, not both");
        auto f = read_rxt(*file);
        in = {f.setup, std::move(f.rows), file->string()};
    } else {
        if (given.m_r.empty()) throw InputError("give an iad measurement file (.rxt) or at least the reflectance M_R (-r)");
        const std::size_t n = given.m_r.size();
        for (const auto& [what, list] : {std::pair{"transmittance M_T", &given.m_t}, std::pair{"unscattered M_U", &given.m_u},
                                         std::pair{"wavelengths", &given.wavelength_nm}}) {
            if (!list->empty() && list->size() != n) {
                throw InputError(std::string(what) + ": " + std::to_string(list->size()) + " values for " + std::to_string(n) + " reflectances M_R");
            }
        }
        in.name = "options";
        const auto at = [](const std::vector<double>& v, std::size_t i) { return v.empty() ? std::nullopt : std::optional(v[i]); };
        for (std::size_t i = 0; i < n; ++i) {
            in.rows.push_back({at(given.wavelength_nm, i), given.m_r[i], at(given.m_t, i), at(given.m_u, i), in.setup,
                               n == 1 ? std::string("the options") : "measurement " + std::to_string(i)});
        }
    }
    for (const auto& [key, value] : setup) {
        const auto* f = setup_field(key);
        if (!f) throw InputError("'" + key + "' is not a setup field (skinspec iad --help lists them)");
        in.setup.*(f->member) = value;
        for (auto& r : in.rows) r.setup.*(f->member) = value;
    }
    validate(in.setup, in.name);
    for (const auto& r : in.rows) check_measurement(r);
    return in;
}

}  // namespace skinspec
