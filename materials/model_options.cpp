#include "materials/model_options.hpp"

#include <array>

#include "spectral/input_error.hpp"
#include "spectral/named_choice.hpp"

namespace skinspec {

std::string_view to_string(RayleighTurn turn) {
    switch (turn) {
        case RayleighTurn::sampled_depth: return "sampled_depth";
        case RayleighTurn::whole_crossing: return "whole_crossing";
        case RayleighTurn::no_absorption: return "no_absorption";
    }
    return "?";
}

RayleighTurn parse_rayleigh_turn(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what, std::array{RayleighTurn::sampled_depth, RayleighTurn::whole_crossing, RayleighTurn::no_absorption},
                        "a Rayleigh turn rule");
}

std::string_view to_string(FoldFormula formula) { return formula == FoldFormula::biospec_2004 ? "biospec_2004" : "authors_code"; }

FoldFormula parse_fold_formula(std::string_view text, std::string_view what) {
    return parse_named_choice(text, what, std::array{FoldFormula::biospec_2004, FoldFormula::authors_code}, "a fold formula");
}

const std::vector<std::string_view>& model_variant_names() {
    static const std::vector<std::string_view> names{"biospec", "biospec-2004", "biospec-authors-code"};
    return names;
}

ModelOptions model_variant(std::string_view name, std::string_view what) {
    ModelOptions options;
    if (name == "biospec") return options;
    if (name == "biospec-2004") {
        options.variant = "biospec-2004";
        options.dermal_rayleigh = false;
        options.molar_tables = DecadicConversion::omit_ln10;
        options.baseline_absorption = false;
        return options;
    }
    if (name == "biospec-authors-code") {
        options.variant = "biospec-authors-code";
        options.rayleigh_turn = RayleighTurn::no_absorption;
        options.swapped_upward_indices = true;
        options.bottom_exit_fresnel = false;
        options.redraw_reversals_in_stratum_corneum = false;
        options.fold_formula = FoldFormula::authors_code;
        return options;
    }
    std::string allowed;
    for (const auto n : model_variant_names()) allowed += (allowed.empty() ? "" : ", ") + std::string(n);
    throw InputError(std::string(what) + ": '" + std::string(name) + "' is not a model variant (allowed: " + allowed + ")");
}

}  // namespace skinspec
