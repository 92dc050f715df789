#pragma once
// Measured forward-scattering profiles of stratum corneum and epidermis (Bruls & van der Leun 1984), as
// cumulative fractions C(theta) of transmitted light within polar angle theta, tabulated at a few
// wavelengths (data/scattering/bruls_vanderleun_*.csv), and their randomized table look-up sampler
// (Baranoski, Krishnaswamy & Kimmel 2005 Sec. 4).
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "spectral/tabulated_spectrum.hpp"

namespace skinspec {

// Inverse-CDF table of the polar deflection: entry j holds C^-1((j + 1/2) / N), C piecewise-linear between
// the measured angles. Sampling takes the entry at floor(u N) (Baranoski et al. 2005 Sec. 4: "multiply this number by
// the table size; the integer part ... is used to access the corresponding scattering angle").
class InverseCdfTable {
public:
    InverseCdfTable(std::span<const double> angles_deg, std::span<const double> cumulative_fraction, std::size_t entries);

    std::size_t index(double u) const { return std::min(static_cast<std::size_t>(u * static_cast<double>(size_)), size_ - 1); }
    double cos_theta(std::size_t i) const { return cos_[i]; }
    double sin_theta(std::size_t i) const { return sin_[i]; }
    double theta_deg(std::size_t i) const { return theta_deg_[i]; }
    std::size_t size() const { return size_; }
    // The mean cosine of the table's distribution (g of the phase function the table samples).
    double mean_cos() const;

private:
    std::size_t size_;
    std::vector<double> theta_deg_;
    std::vector<double> cos_;
    std::vector<double> sin_;
};

class MeasuredProfile {
public:
    static const MeasuredProfile& stratum_corneum();
    static const MeasuredProfile& epidermis();

    // Tabulated polar angles (deg) and wavelengths (nm).
    std::span<const double> angles_deg() const { return angles_deg_; }
    std::span<const double> wavelengths_nm() const { return wavelengths_nm_; }
    // Cumulative fractions (0-1) at the tabulated angles for a wavelength: linear in wavelength between
    // tabulated profiles, the nearest profile outside them (clamped).
    std::vector<double> cumulative(double wavelength_nm) const;
    // C(theta) at any angle for a wavelength: piecewise-linear between the tabulated angles; 1 beyond the last.
    double cdf(double wavelength_nm, double theta_deg) const;
    // Density of theta in 1/deg (derivative of the piecewise-linear C).
    double pdf_theta(double wavelength_nm, double theta_deg) const;
    InverseCdfTable inverse_table(double wavelength_nm, std::size_t entries = 1000) const;
    // The same table, shared: outside the tabulated wavelengths the profile is the nearest end's (above 546 nm for
    // these data), so every such wavelength gets one table built once; inside, a table of its own.
    std::shared_ptr<const InverseCdfTable> shared_inverse_table(double wavelength_nm, std::size_t entries = 1000) const;

    // The profile at a wavelength as a mixture of two tabulated ones: C = (1 - w) C(lower) + w C(upper), since the
    // cumulative fractions are linear in wavelength between tabulated profiles (lower = upper, w = 0, at and beyond
    // the ends). Sampling the mixture (the upper table with probability w) samples the profile exactly.
    struct Mixture {
        std::size_t lower = 0;  // indices into wavelengths_nm()
        std::size_t upper = 0;
        double upper_weight = 0.0;
    };
    Mixture mixture(double wavelength_nm) const;
    // The table of tabulated wavelength `index`, built once per entry count.
    std::shared_ptr<const InverseCdfTable> tabulated_inverse_table(std::size_t index, std::size_t entries = 1000) const;

private:
    explicit MeasuredProfile(const char* file);
    std::vector<double> angles_deg_;
    std::vector<double> wavelengths_nm_;
    std::vector<TabulatedSpectrum> by_angle_;  // cumulative fraction at each angle, as a function of wavelength
    struct TabulatedTables;
    std::shared_ptr<TabulatedTables> tabulated_tables_;  // by (tabulated wavelength, entry count), built on first use
};

}  // namespace skinspec
