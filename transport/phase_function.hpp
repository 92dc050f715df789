#pragma once
// The phase functions of the volumetric walk behind one small value type: Henyey-Greenstein, two-term HG,
// isotropic, Rayleigh, and tabulated (inverse-CDF table of a measured cumulative profile). Each model's
// formula lives in its own header; this only dispatches.
#include <memory>
#include <string>

#include "materials/measured_profile.hpp"

namespace skinspec {

struct PhaseFunction {
    enum class Kind { henyey_greenstein, two_term_hg, isotropic, rayleigh, tabulated };
    Kind kind = Kind::henyey_greenstein;
    double g = 0.0;       // HG, or the first term of two-term HG
    double g2 = 0.0;      // second term of two-term HG
    double weight = 1.0;  // u of two-term HG
    std::shared_ptr<const InverseCdfTable> table;  // tabulated

    static PhaseFunction henyey_greenstein(double g) { return {Kind::henyey_greenstein, g, 0.0, 1.0, nullptr}; }
    static PhaseFunction isotropic() { return {Kind::isotropic, 0.0, 0.0, 1.0, nullptr}; }

    std::string describe() const;
    // The mean cosine of the scattering angle: g for HG and for a tabulated phase (which carries its table's), the
    // weighted mean of two-term HG's, 0 for the isotropic and Rayleigh phases (symmetric about 90 deg).
    double mean_cosine() const;
};

}  // namespace skinspec
