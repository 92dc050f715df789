#include "transport/biospec/biospec_options.hpp"

#include <string>

#include "spectral/input_error.hpp"

namespace skinspec {

std::string_view to_string(AbsorptionEstimator estimator) {
    return estimator == AbsorptionEstimator::weighted ? "weighted" : "random";
}

std::string_view to_string(FoldIntoSkin fold) { return fold == FoldIntoSkin::drop ? "drop" : "resample"; }

AbsorptionEstimator parse_absorption_estimator(std::string_view text, std::string_view what) {
    if (text == "weighted") return AbsorptionEstimator::weighted;
    if (text == "random") return AbsorptionEstimator::random_test;
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is not an estimator (allowed: weighted, random)");
}

FoldIntoSkin parse_fold_into_skin(std::string_view text, std::string_view what) {
    if (text == "drop") return FoldIntoSkin::drop;
    if (text == "resample") return FoldIntoSkin::resample;
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is not a fold behaviour (allowed: drop, resample)");
}

}  // namespace skinspec
