#pragma once
// Data keyed by an enumeration, loaded once for all its values on first use (thread-safe static
// initialisation) and kept for the process lifetime. `kinds` lists the values in enumeration order.
#include <cstddef>
#include <vector>

namespace skinspec {

template <class Kind, class Load>
const auto& load_once(Kind kind, const std::vector<Kind>& kinds, Load load) {
    using Loaded = decltype(load(kind));
    static const std::vector<Loaded> loaded = [&] {
        std::vector<Loaded> all;
        for (const auto k : kinds) all.push_back(load(k));
        return all;
    }();
    return loaded[static_cast<std::size_t>(kind)];
}

}  // namespace skinspec
