#include "materials/path_key.hpp"

#include <algorithm>
#include <bit>
#include <functional>
#include <type_traits>
#include <variant>

#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

void mix(std::size_t& hash, double value) {
    hash ^= std::hash<std::uint64_t>{}(std::bit_cast<std::uint64_t>(value)) + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2);
}

bool absorbers_scatter_in(const LayerStack& stack, TracedPaths paths) {
    return paths == TracedPaths::volumetric && stack.model.volumetric_matched_to_biospec;
}

}  // namespace

PathKey path_key(const LayerStack& stack, TracedPaths paths) {
    PathKey key{stack, 0};
    auto& s = key.stack;
    s.name.clear();
    s.description.clear();
    s.model.variant.clear();  // a variant only names switch values; the switches themselves are compared
    const bool absorbers_scatter = absorbers_scatter_in(s, paths);
    for (auto& layer : s.layers) {
        for (const auto& f : layer_number_fields()) {
            if (f.absorption_only && !absorbers_scatter) layer.*f.member = 0.0;
            else mix(key.hash, layer.*f.member);
        }
    }
    for (const auto& f : model_fields()) {
        std::visit(
            [&](auto member) {
                using T = std::remove_cvref_t<decltype(s.model.*member)>;
                if (f.absorption_only && !absorbers_scatter) s.model.*member = T{};
                else if constexpr (std::is_same_v<T, double>) mix(key.hash, s.model.*member);
            },
            f.member);
    }
    for (const auto& f : surface_fields()) mix(key.hash, s.*f.member);
    for (const auto& f : bottom_fields()) mix(key.hash, s.*f.member);
    mix(key.hash, static_cast<double>(s.layers.size()));
    return key;
}

bool is_absorption_only_key(const std::string& key) {
    const auto dot = key.find('.');
    if (dot == std::string::npos) return false;
    const auto head = key.substr(0, dot);
    const auto name = key.substr(dot + 1);
    if (head == "model") {
        return std::any_of(model_fields().begin(), model_fields().end(), [&](const ModelField& f) { return f.key == name && f.absorption_only; });
    }
    if (head == "surface" || head == "bottom") return false;
    return std::any_of(layer_number_fields().begin(), layer_number_fields().end(),
                       [&](const NumberField<TissueLayer>& f) { return f.key == name && f.absorption_only; });
}

std::string path_difference(const LayerStack& a, const LayerStack& b, TracedPaths paths) {
    if (path_key(a, paths) == path_key(b, paths)) return {};
    if (a.layers.size() != b.layers.size()) return "the number of layers";
    for (std::size_t k = 0; k < a.layers.size(); ++k) {
        if (a.layers[k].name != b.layers[k].name) return "the name of layer " + std::to_string(k + 1);
    }
    // Named by the keys --set uses, read through the same field table as the files (a key only one holds differs).
    const Material ma = a, mb = b;
    auto keys = material_keys(ma);
    for (const auto& k : material_keys(mb)) {
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    }
    for (const auto& k : keys) {
        if (k == "name" || k == "description" || k == "model.variant" || (is_absorption_only_key(k) && !absorbers_scatter_in(a, paths))) continue;
        try {
            if (material_field(ma, k) != material_field(mb, k)) return k;
        } catch (const InputError&) {
            return k;
        }
    }
    return "a field";
}

void require_shared_paths(const std::vector<const LayerStack*>& stacks, TracedPaths paths) {
    if (stacks.size() < 2) return;
    const auto first = path_key(*stacks.front(), paths);
    for (const auto* stack : stacks) {
        if (path_key(*stack, paths) == first) continue;
        throw InputError("absorption sets '" + stacks.front()->name + "' and '" + stack->name + "' differ in " +
                         path_difference(*stacks.front(), *stack, paths) + ", which changes paths (trace them separately)");
    }
}

}  // namespace skinspec
