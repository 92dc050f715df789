#pragma once
// A spectrum tabulated at strictly increasing wavelengths (nm), piecewise-linear between samples, with an
// explicit domain [front, back] and an explicit policy for wavelengths outside it.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/wavelength_grid.hpp"

namespace skinspec {

enum class OutOfRangePolicy {
    error,  // evaluating outside the domain throws InputError naming the spectrum and the wavelength
    zero,   // 0 outside the domain
    hold,   // the nearest end value outside the domain
};

std::string_view to_string(OutOfRangePolicy policy);
// "error" | "zero" | "hold"; `what` names the field in the error message.
OutOfRangePolicy parse_out_of_range_policy(std::string_view text, std::string_view what);

class TabulatedSpectrum {
public:
    // `name` identifies the spectrum in error messages (e.g. "CIE illuminant D65").
    TabulatedSpectrum(std::string name, std::vector<double> wavelengths_nm, std::vector<double> values,
                      OutOfRangePolicy outside);

    double operator()(double wavelength_nm) const;
    std::vector<double> sample(const WavelengthGrid& grid) const;

    const std::string& name() const { return name_; }
    std::span<const double> wavelengths_nm() const { return wavelengths_nm_; }
    std::span<const double> values() const { return values_; }
    double domain_min_nm() const { return wavelengths_nm_.front(); }
    double domain_max_nm() const { return wavelengths_nm_.back(); }
    bool in_domain(double wavelength_nm) const {
        return wavelength_nm >= domain_min_nm() && wavelength_nm <= domain_max_nm();
    }
    OutOfRangePolicy outside() const { return outside_; }

private:
    std::string name_;
    std::vector<double> wavelengths_nm_;
    std::vector<double> values_;
    OutOfRangePolicy outside_;
};

}  // namespace skinspec
