#pragma once
// Help text shared by every command that takes --set, so they all say where the keys are.
namespace skinspec::cli {

inline constexpr const char* set_option_help =
    "Override a material field, KEY=VALUE (repeatable), e.g. epidermis.melanosome_fraction=0.1. KEY is a field of the "
    "material file: LAYER.FIELD (LAYER a layer name, or a suffix such as 'dermis' for all dermal layers), model.FIELD, "
    "surface.FIELD, bottom.FIELD; 'skinspec materials keys' lists every field with its unit and range";

}  // namespace skinspec::cli
