#pragma once
// Wavelength grids in nanometres: a range with a step, or an explicit list. Always finite, positive and
// strictly increasing (checked on construction).
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace skinspec {

class WavelengthGrid {
public:
    // first, first + step, ... up to and including last (within 1e-9 steps of rounding).
    // `what` names the option or field in error messages.
    static WavelengthGrid range(double first_nm, double last_nm, double step_nm,
                                std::string_view what = "wavelength grid");
    static WavelengthGrid list(std::vector<double> wavelengths_nm, std::string_view what = "wavelength grid");
    // "400:700:10" (first:last:step), "550" (one wavelength) or "436,546" (a list).
    static WavelengthGrid parse(std::string_view text, std::string_view what);

    std::span<const double> nm() const { return wavelengths_nm_; }
    std::size_t size() const { return wavelengths_nm_.size(); }
    double operator[](std::size_t i) const { return wavelengths_nm_[i]; }
    double front() const { return wavelengths_nm_.front(); }
    double back() const { return wavelengths_nm_.back(); }

private:
    explicit WavelengthGrid(std::vector<double> nm) : wavelengths_nm_(std::move(nm)) {}
    std::vector<double> wavelengths_nm_;
};

}  // namespace skinspec
