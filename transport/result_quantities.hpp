#pragma once
// The result quantities of a spectral result, one row each (docs/RESULTS_SCHEMA.md): the one place that says
// what a quantity is called, its unit, its shape per wavelength, which request brings it and where it is held.
// The CSV columns and JSON arrays (cli/spectral_output.cpp), the Python arrays (python/spectrum_binding.cpp,
// python/skinspec/results.py) and the process-to-process wire (solvers/result_wire.cpp) iterate this table, so a
// new quantity is one row here and one WavelengthResult member its solvers fill.
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "transport/spectral_request.hpp"

namespace skinspec {

enum class QuantityShape {
    scalar,     // one estimate per wavelength
    per_layer,  // one per layer (SpectralResult::layer_names)
    per_bin,    // one per polar bin (SpectralResult::angular_bin_edges_deg)
};

struct ResultQuantity {
    std::string_view key;          // JSON key and CSV column (scalars) or column prefix: "R", "A_layers", "BRDF_per_sr"
    std::string_view python_name;  // the Python attribute: "R", "A", "brdf_per_sr"
    std::string_view unit;         // "1" (fraction of incident flux) or "1/sr"
    std::string_view doc;
    QuantityShape shape;
    bool (*requested)(const Quantities& quantities);
    std::variant<Estimate WavelengthResult::*, std::vector<Estimate> WavelengthResult::*> member;

    // The estimates of one wavelength (one for a scalar).
    std::span<const Estimate> values(const WavelengthResult& w) const;
    // The CSV column of element `i`: "R", "A_epidermis", "BRDF_2.5-7.5deg_per_sr".
    std::string column(const SpectralResult& result, std::size_t i) const;
    // How many estimates a wavelength of `result` holds (1, the layers or the bins).
    std::size_t count(const SpectralResult& result) const;
    // The physical range's upper end: 1 for a fraction of the incident flux, unbounded per sr (the lower end is 0).
    double upper_bound() const;
};

const std::vector<ResultQuantity>& result_quantities();
// The rows a result holds (requested by its quantities), in table order.
std::vector<const ResultQuantity*> quantities_of(const SpectralResult& result);

}  // namespace skinspec
