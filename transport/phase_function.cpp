#include "transport/phase_function.hpp"

#include <fmt/format.h>

#include "transport/rayleigh_phase.hpp"
#include "transport/two_term_hg.hpp"

namespace skinspec {

double PhaseFunction::sample_cos(RandomStream& random) const {
    switch (kind) {
        case Kind::henyey_greenstein: return hg_sample_cos(g, random.uniform());
        case Kind::two_term_hg: {
            const double term = random.uniform();
            return two_term_hg_sample_cos(g, g2, weight, term, random.uniform());
        }
        case Kind::isotropic: return 1.0 - 2.0 * random.uniform();
        case Kind::rayleigh: return rayleigh_sample_cos(random.uniform());
        case Kind::tabulated: return table->cos_theta(table->index(random.uniform()));
    }
    return 1.0;
}

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
