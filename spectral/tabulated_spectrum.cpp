#include "spectral/tabulated_spectrum.hpp"

#include <algorithm>
#include <cmath>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

std::string_view to_string(OutOfRangePolicy policy) {
    switch (policy) {
        case OutOfRangePolicy::error: return "error";
        case OutOfRangePolicy::zero: return "zero";
        case OutOfRangePolicy::hold: return "hold";
    }
    return "?";
}

OutOfRangePolicy parse_out_of_range_policy(std::string_view text, std::string_view what) {
    for (const auto policy : {OutOfRangePolicy::error, OutOfRangePolicy::zero, OutOfRangePolicy::hold}) {
        if (trim(text) == to_string(policy)) return policy;
    }
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is not an out-of-range policy (allowed: error, zero, hold)");
}

TabulatedSpectrum::TabulatedSpectrum(std::string name, std::vector<double> wavelengths_nm, std::vector<double> values,
                                     OutOfRangePolicy outside)
    : name_(std::move(name)), wavelengths_nm_(std::move(wavelengths_nm)), values_(std::move(values)), outside_(outside) {
    if (wavelengths_nm_.size() != values_.size()) {
        throw InputError(name_ + ": " + std::to_string(wavelengths_nm_.size()) + " wavelengths but " +
                         std::to_string(values_.size()) + " values (allowed: equal counts)");
    }
    if (wavelengths_nm_.size() < 2) {
        throw InputError(name_ + ": " + std::to_string(wavelengths_nm_.size()) + " point(s) (allowed: at least 2)");
    }
    for (std::size_t i = 0; i < values_.size(); ++i) {
        if (!std::isfinite(wavelengths_nm_[i]) || !std::isfinite(values_[i])) {
            throw InputError(name_ + ": non-finite entry at " + format_number(wavelengths_nm_[i]) +
                             " nm (allowed: finite numbers)");
        }
        if (i > 0 && !(wavelengths_nm_[i] > wavelengths_nm_[i - 1])) {
            throw InputError(name_ + ": wavelength " + format_number(wavelengths_nm_[i]) + " nm follows " +
                             format_number(wavelengths_nm_[i - 1]) + " nm (allowed: strictly increasing)");
        }
    }
}

double TabulatedSpectrum::operator()(double wavelength_nm) const {
    if (!in_domain(wavelength_nm)) {
        switch (outside_) {
            case OutOfRangePolicy::zero: return 0.0;
            case OutOfRangePolicy::hold: return wavelength_nm < domain_min_nm() ? values_.front() : values_.back();
            case OutOfRangePolicy::error:
                throw InputError(name_ + ": wavelength " + format_number(wavelength_nm) +
                                 " nm is outside the tabulated domain [" + format_number(domain_min_nm()) + ", " +
                                 format_number(domain_max_nm()) + "] nm");
        }
    }
    const auto upper = std::upper_bound(wavelengths_nm_.begin(), wavelengths_nm_.end(), wavelength_nm);
    if (upper == wavelengths_nm_.end()) return values_.back();
    const auto i = static_cast<std::size_t>(upper - wavelengths_nm_.begin());
    const double t = (wavelength_nm - wavelengths_nm_[i - 1]) / (wavelengths_nm_[i] - wavelengths_nm_[i - 1]);
    return values_[i - 1] + t * (values_[i] - values_[i - 1]);
}

std::vector<double> TabulatedSpectrum::sample(const WavelengthGrid& grid) const {
    std::vector<double> out(grid.size());
    for (std::size_t i = 0; i < grid.size(); ++i) out[i] = (*this)(grid[i]);
    return out;
}

}  // namespace skinspec
