#pragma once
// Parsing a value that is one of a set of names (an enum with to_string): the one message for every such option,
// "WHAT: 'TEXT' is not NOUN (allowed: a, b, c)".
#include <array>
#include <string>
#include <string_view>

#include "spectral/input_error.hpp"

namespace skinspec {

// `noun` carries its article ("a phase function"); `kinds` are tried in order, matched by their to_string.
template <class Kind, std::size_t N>
Kind parse_named_choice(std::string_view text, std::string_view what, const std::array<Kind, N>& kinds, std::string_view noun) {
    std::string allowed;
    for (const auto k : kinds) {
        if (text == to_string(k)) return k;
        allowed += (allowed.empty() ? "" : ", ") + std::string(to_string(k));
    }
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is not " + std::string(noun) + " (allowed: " + allowed + ")");
}

}  // namespace skinspec
