#pragma once
// Prahl's adding-doubling totals for Henyey-Greenstein slabs (data/reference/adding_doubling_slabs.csv,
// about 1e-3 relative): the independent reference of the volumetric walk's validation, tests and benchmark.
#include <vector>

#include "transport/rte/rte_model.hpp"

namespace skinspec {

struct AddingDoublingSlab {
    double albedo = 0.0;             // a = mu_s / (mu_a + mu_s)
    double optical_thickness = 0.0;  // b = (mu_a + mu_s) d
    double g = 0.0;
    double refractive_index = 1.0;   // slab in air (n = 1 both sides)
    double diffuse_reflectance = 0.0;  // specular excluded
    double total_transmittance = 0.0;
    double absorbed = 0.0;

    // The slab as one RTE layer of thickness `thickness_cm` (any thickness: only b matters).
    RteStack stack(double thickness_cm = 0.1) const;
};

// InputError naming the file and line for a malformed table.
std::vector<AddingDoublingSlab> adding_doubling_slabs();

}  // namespace skinspec
