#pragma once
// Which materials may share traced paths (absorption replay), derived from the field table: a field declared
// absorption_only (materials/material_fields.cpp) changes mu_a and nothing else, so two stacks that agree in every
// other field trace alike and one trace, re-weighted per stack, serves both. Every other field (geometry,
// scattering in any description, indices, model switches, names) separates them, so a new field is safe by default.
#include <cstddef>
#include <string>
#include <vector>

#include "materials/layer_stack.hpp"

namespace skinspec {

// Whose paths: the BioSpec walk's, or the volumetric walk's, where a description matched to the BioSpec one
// (model.volumetric_matched_to_biospec) scales the dermis's mu_s by what the absorbers do: no field changes mu_a alone.
enum class TracedPaths { biospec, volumetric };

// A stack with its absorption-only fields, name and description cleared: equal keys trace alike.
struct PathKey {
    LayerStack stack;
    std::size_t hash = 0;  // of the key's numbers: unequal hashes, unequal keys
    bool operator==(const PathKey& other) const { return hash == other.hash && stack == other.stack; }
};
PathKey path_key(const LayerStack& stack, TracedPaths paths);

// Whether `key` ("epidermis.melanosome_fraction", "model.baseline_absorption") names an absorption-only field.
bool is_absorption_only_key(const std::string& key);

// The first field besides absorption in which two stacks differ, as --set names it ("papillary_dermis.thickness_cm",
// "model.dermal_rayleigh", "the number of layers"); empty when one trace serves both.
std::string path_difference(const LayerStack& a, const LayerStack& b, TracedPaths paths);

// InputError "absorption sets 'A' and 'B' differ in FIELD, which changes paths" unless every stack traces like the
// first (the walks' check before replaying a group; the first's key is computed once).
void require_shared_paths(const std::vector<const LayerStack*>& stacks, TracedPaths paths);

}  // namespace skinspec
