#include "spectral/cie.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"
#include "spectral/input_error.hpp"
#include "spectral/load_once.hpp"

namespace skinspec {
namespace {

bool equal_ignoring_case(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

std::string_view observer_file(ObserverKind kind) {
    return kind == ObserverKind::cie1931_2deg ? "cie/observer_cie1931_2deg.csv" : "cie/observer_cie1964_10deg.csv";
}

std::string_view illuminant_file(IlluminantKind kind) {
    switch (kind) {
        case IlluminantKind::d65: return "cie/illuminant_d65.csv";
        case IlluminantKind::d50: return "cie/illuminant_d50.csv";
        case IlluminantKind::a: return "cie/illuminant_a.csv";
        case IlluminantKind::e: return "cie/illuminant_e.csv";
    }
    return "";
}

Observer load_observer(ObserverKind kind) {
    const auto table = DataTable::read(data_file(observer_file(kind)));
    const std::string name(display_name(kind));
    return Observer{kind, table.spectrum("xbar", name + " xbar"), table.spectrum("ybar", name + " ybar"),
                    table.spectrum("zbar", name + " zbar")};
}

Illuminant load_illuminant(IlluminantKind kind) {
    const auto table = DataTable::read(data_file(illuminant_file(kind)));
    return Illuminant{kind, table.spectrum("power", "CIE illuminant " + std::string(short_name(kind)))};
}

template <class Kind>
std::string allowed_names(const std::vector<Kind>& kinds) {
    std::string names;
    for (const auto k : kinds) names += (names.empty() ? "" : ", ") + std::string(short_name(k));
    return names;
}

template <class Kind>
Kind parse_kind(std::string_view text, std::string_view what, const std::vector<Kind>& kinds, std::string_view noun) {
    for (const auto k : kinds) {
        if (equal_ignoring_case(text, short_name(k))) return k;
    }
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is not a known " + std::string(noun) +
                     " (allowed: " + allowed_names(kinds) + ")");
}

}  // namespace

const Observer& observer(ObserverKind kind) { return load_once(kind, all_observers(), load_observer); }

const Illuminant& illuminant(IlluminantKind kind) { return load_once(kind, all_illuminants(), load_illuminant); }

std::string_view display_name(ObserverKind kind) {
    return kind == ObserverKind::cie1931_2deg ? "CIE 1931 2-degree" : "CIE 1964 10-degree";
}

std::string_view short_name(ObserverKind kind) { return kind == ObserverKind::cie1931_2deg ? "2" : "10"; }

std::string_view short_name(IlluminantKind kind) {
    switch (kind) {
        case IlluminantKind::d65: return "D65";
        case IlluminantKind::d50: return "D50";
        case IlluminantKind::a: return "A";
        case IlluminantKind::e: return "E";
    }
    return "?";
}

const std::vector<ObserverKind>& all_observers() {
    static const std::vector<ObserverKind> kinds{ObserverKind::cie1931_2deg, ObserverKind::cie1964_10deg};
    return kinds;
}

const std::vector<IlluminantKind>& all_illuminants() {
    static const std::vector<IlluminantKind> kinds{IlluminantKind::d65, IlluminantKind::d50, IlluminantKind::a,
                                                    IlluminantKind::e};
    return kinds;
}

ObserverKind parse_observer(std::string_view text, std::string_view what) {
    return parse_kind(text, what, all_observers(), "observer");
}

IlluminantKind parse_illuminant(std::string_view text, std::string_view what) {
    return parse_kind(text, what, all_illuminants(), "illuminant");
}

}  // namespace skinspec
