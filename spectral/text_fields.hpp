#pragma once
// Small helpers for the text formats skinspec reads (CSV tables, option values).
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skinspec {

// Leading and trailing blanks (space, tab, CR) removed.
std::string_view trim(std::string_view text);

// The whole field as a double (std::from_chars, no locale); nullopt when any character is left over or
// nothing parses. "nan"/"inf" parse: callers decide whether non-finite values are allowed.
std::optional<double> parse_double(std::string_view field);

// Fields separated by commas, or by runs of blanks when the line has no comma; each trimmed.
std::vector<std::string_view> split_fields(std::string_view line);

// "FIRST:LAST:STEP" as three finite numbers; InputError naming `option` and `unit` otherwise (ranges are
// checked by the caller).
std::array<double, 3> parse_colon_triple(std::string_view text, std::string_view option, std::string_view unit);

// "FIRST:LAST:STEP" radii in mm: FIRST >= 0, STEP > 0, LAST >= FIRST, at most a million; InputError naming `option`.
std::vector<double> parse_radii_mm(std::string_view text, std::string_view option);

// Shortest round-trip text of a double, for messages ("0.1", not "0.100000").
std::string format_number(double value);

}  // namespace skinspec
