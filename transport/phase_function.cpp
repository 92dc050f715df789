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

}  // namespace skinspec
