#pragma once
// CIE standard observers and illuminants, loaded once from skinspec's data/cie tables (1 nm, 360-830 nm).
#include <string_view>
#include <vector>

#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

enum class ObserverKind { cie1931_2deg, cie1964_10deg };
enum class IlluminantKind { d65, d50, a, e };

struct Observer {
    ObserverKind kind;
    TabulatedSpectrum xbar;
    TabulatedSpectrum ybar;
    TabulatedSpectrum zbar;
};

struct Illuminant {
    IlluminantKind kind;
    TabulatedSpectrum power;  // relative spectral power
};

// Loaded on first use (thread-safe) and kept for the process lifetime.
const Observer& observer(ObserverKind kind);
const Illuminant& illuminant(IlluminantKind kind);

// Display names ("CIE 1931 2-degree", "D65") and the short names users type ("2", "10"; "D65", "D50", "A", "E").
std::string_view display_name(ObserverKind kind);
std::string_view short_name(ObserverKind kind);
std::string_view short_name(IlluminantKind kind);
const std::vector<ObserverKind>& all_observers();
const std::vector<IlluminantKind>& all_illuminants();
// Case-insensitive; InputError naming `what`, the text and the allowed names otherwise.
ObserverKind parse_observer(std::string_view text, std::string_view what);
IlluminantKind parse_illuminant(std::string_view text, std::string_view what);

}  // namespace skinspec
