#include "transport/phase_function.hpp"

#include <fmt/format.h>


namespace skinspec {

std::string PhaseFunction::describe() const {
    switch (kind) {
        case Kind::henyey_greenstein: return fmt::format("henyey_greenstein(g={})", g);
        case Kind::two_term_hg: return fmt::format("two_term_hg(g1={}, g2={}, u={})", g, g2, weight);
        case Kind::isotropic: return "isotropic";
        case Kind::rayleigh: return "rayleigh";
        case Kind::tabulated: return "tabulated";
    }
    return "?";
}

double PhaseFunction::mean_cosine() const {
    switch (kind) {
        case Kind::henyey_greenstein:
        case Kind::tabulated: return g;
        case Kind::two_term_hg: return weight * g + (1.0 - weight) * g2;
        case Kind::isotropic:
        case Kind::rayleigh: return 0.0;
    }
    return 0.0;
}

}  // namespace skinspec
