#include "spectral/text_fields.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "spectral/input_error.hpp"

namespace skinspec {

std::string_view trim(std::string_view text) {
    constexpr std::string_view blanks = " \t\r\n";
    const auto first = text.find_first_not_of(blanks);
    if (first == std::string_view::npos) return {};
    const auto last = text.find_last_not_of(blanks);
    return text.substr(first, last - first + 1);
}

std::optional<double> parse_double(std::string_view field) {
    field = trim(field);
    if (!field.empty() && field.front() == '+') field.remove_prefix(1);
    if (field.empty()) return std::nullopt;
    double value = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
    return value;
}

std::vector<std::string_view> split_fields(std::string_view line) {
    std::vector<std::string_view> fields;
    if (line.find(',') != std::string_view::npos) {
        std::size_t start = 0;
        while (true) {
            const auto comma = line.find(',', start);
            fields.push_back(trim(line.substr(start, comma - start)));
            if (comma == std::string_view::npos) break;
            start = comma + 1;
        }
        return fields;
    }
    constexpr std::string_view blanks = " \t\r\n";
    std::size_t pos = line.find_first_not_of(blanks);
    while (pos != std::string_view::npos) {
        const auto end = line.find_first_of(blanks, pos);
        fields.push_back(line.substr(pos, end - pos));
        pos = line.find_first_not_of(blanks, end);
    }
    return fields;
}

std::string format_number(double value) {
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

std::array<double, 3> parse_colon_triple(std::string_view text, std::string_view option, std::string_view unit) {
    std::vector<double> parts;
    std::size_t start = 0;
    while (true) {
        const auto colon = text.find(':', start);
        const auto field = text.substr(start, colon == std::string_view::npos ? std::string_view::npos : colon - start);
        const auto value = parse_double(field);
        if (!value || !std::isfinite(*value)) {
            throw InputError(std::string(option) + ": '" + std::string(field) + "' is not a finite number (expected FIRST:LAST:STEP in " +
                             std::string(unit) + ")");
        }
        parts.push_back(*value);
        if (colon == std::string_view::npos) break;
        start = colon + 1;
    }
    if (parts.size() != 3) {
        throw InputError(std::string(option) + ": '" + std::string(text) + "' must have the form FIRST:LAST:STEP (" + std::string(unit) + ")");
    }
    return {parts[0], parts[1], parts[2]};
}

std::vector<double> parse_radii_mm(std::string_view text, std::string_view option) {
    const auto [first, last, step] = parse_colon_triple(text, option, "mm");
    if (first < 0.0) throw InputError(std::string(option) + ": FIRST = " + format_number(first) + " mm is outside [0, inf)");
    if (step <= 0.0) throw InputError(std::string(option) + ": STEP = " + format_number(step) + " mm is outside (0, inf)");
    if (last < first) throw InputError(std::string(option) + ": LAST = " + format_number(last) + " mm is below FIRST = " + format_number(first) + " mm");
    const double count = std::floor((last - first) / step + 1e-9) + 1.0;
    if (count > 1e6) throw InputError(std::string(option) + ": " + format_number(count) + " radii is outside [1, 1000000]");
    std::vector<double> radii;
    for (int i = 0; i < static_cast<int>(count); ++i) radii.push_back(first + i * step);
    return radii;
}

}  // namespace skinspec
