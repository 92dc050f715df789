#include "materials/model_options.hpp"

#include "spectral/input_error.hpp"

namespace skinspec {

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
    throw InputError(std::string(what) + ": '" + std::string(name) + "' is not a model variant (allowed: biospec, biospec-2004)");
}

}  // namespace skinspec
