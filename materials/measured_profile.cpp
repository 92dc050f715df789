#include "materials/measured_profile.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <string>

#include "spectral/data_paths.hpp"
#include "spectral/data_table.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

constexpr std::string_view column_prefix = "cumulative_percent_within_";
constexpr double deg = std::numbers::pi / 180.0;

// Linear interpolation of y(x) over increasing xs.
double interpolate(std::span<const double> xs, std::span<const double> ys, double x) {
    if (x <= xs.front()) return ys.front();
    if (x >= xs.back()) return ys.back();
    const auto i = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
    const double t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
    return ys[i - 1] + t * (ys[i] - ys[i - 1]);
}

}  // namespace

InverseCdfTable::InverseCdfTable(std::span<const double> angles_deg, std::span<const double> cumulative, std::size_t entries)
    : size_(entries), theta_deg_(entries), cos_(entries), sin_(entries) {
    if (entries == 0) throw InputError("inverse CDF table: 0 entries (allowed: at least 1)");
    for (std::size_t i = 1; i < cumulative.size(); ++i) {
        if (cumulative[i] < cumulative[i - 1]) throw InputError("inverse CDF table: cumulative data decrease");
    }
    // Linear inversion: theta where the piecewise-linear C reaches the entry's probability.
    for (std::size_t j = 0; j < entries; ++j) {
        const double p = (static_cast<double>(j) + 0.5) / static_cast<double>(entries) * cumulative.back();
        std::size_t k = 1;
        while (k + 1 < cumulative.size() && cumulative[k] < p) ++k;
        const double c0 = cumulative[k - 1];
        const double c1 = cumulative[k];
        const double t = c1 > c0 ? (p - c0) / (c1 - c0) : 0.0;
        theta_deg_[j] = angles_deg[k - 1] + std::clamp(t, 0.0, 1.0) * (angles_deg[k] - angles_deg[k - 1]);
        cos_[j] = std::cos(theta_deg_[j] * deg);
        sin_[j] = std::sin(theta_deg_[j] * deg);
    }
}

double InverseCdfTable::mean_cos() const {
    double sum = 0.0;
    for (const double c : cos_) sum += c;
    return sum / static_cast<double>(size_);
}

MeasuredProfile::MeasuredProfile(const char* file) : tabulated_tables_(std::make_shared<TabulatedTables>()) {
    const auto table = DataTable::read(data_file(file));
    const auto wavelengths = table.column("wavelength_nm");
    wavelengths_nm_.assign(wavelengths.begin(), wavelengths.end());
    for (const auto& name : table.column_names()) {
        if (name.rfind(column_prefix, 0) != 0) continue;
        std::string angle = name.substr(column_prefix.size());
        angle = angle.substr(0, angle.size() - 3);  // strip "deg"
        angles_deg_.push_back(std::stod(angle));
        const auto percent = table.column(name);
        std::vector<double> fraction(percent.size());
        std::transform(percent.begin(), percent.end(), fraction.begin(), [](double v) { return v / 100.0; });
        by_angle_.emplace_back(name, wavelengths_nm_, std::move(fraction), OutOfRangePolicy::hold);
    }
}

const MeasuredProfile& MeasuredProfile::stratum_corneum() {
    static const MeasuredProfile profile("scattering/bruls_vanderleun_stratum_corneum.csv");
    return profile;
}

const MeasuredProfile& MeasuredProfile::epidermis() {
    static const MeasuredProfile profile("scattering/bruls_vanderleun_epidermis.csv");
    return profile;
}

std::vector<double> MeasuredProfile::cumulative(double wavelength_nm) const {
    std::vector<double> c(by_angle_.size());
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = by_angle_[i](wavelength_nm);  // hold = clamped outside
    return c;
}

double MeasuredProfile::cdf(double wavelength_nm, double theta_deg) const {
    return interpolate(angles_deg_, cumulative(wavelength_nm), theta_deg);
}

double MeasuredProfile::pdf_theta(double wavelength_nm, double theta_deg) const {
    if (theta_deg < angles_deg_.front() || theta_deg >= angles_deg_.back()) return 0.0;
    const auto c = cumulative(wavelength_nm);
    const auto i = static_cast<std::size_t>(std::upper_bound(angles_deg_.begin(), angles_deg_.end(), theta_deg) - angles_deg_.begin());
    return (c[i] - c[i - 1]) / (angles_deg_[i] - angles_deg_[i - 1]);
}

InverseCdfTable MeasuredProfile::inverse_table(double wavelength_nm, std::size_t entries) const {
    return InverseCdfTable(angles_deg_, cumulative(wavelength_nm), entries);
}

struct MeasuredProfile::TabulatedTables {
    std::mutex mutex;
    std::map<std::pair<std::size_t, std::size_t>, std::shared_ptr<const InverseCdfTable>> tables;  // (index, entries)
};

std::shared_ptr<const InverseCdfTable> MeasuredProfile::tabulated_inverse_table(std::size_t index, std::size_t entries) const {
    const std::lock_guard lock(tabulated_tables_->mutex);
    auto& table = tabulated_tables_->tables[{index, entries}];
    if (!table) table = std::make_shared<const InverseCdfTable>(inverse_table(wavelengths_nm_.at(index), entries));
    return table;
}

std::shared_ptr<const InverseCdfTable> MeasuredProfile::shared_inverse_table(double wavelength_nm, std::size_t entries) const {
    if (wavelength_nm <= wavelengths_nm_.front()) return tabulated_inverse_table(0, entries);
    if (wavelength_nm >= wavelengths_nm_.back()) return tabulated_inverse_table(wavelengths_nm_.size() - 1, entries);
    return std::make_shared<const InverseCdfTable>(inverse_table(wavelength_nm, entries));
}

MeasuredProfile::Mixture MeasuredProfile::mixture(double wavelength_nm) const {
    const auto& w = wavelengths_nm_;
    if (wavelength_nm <= w.front()) return {0, 0, 0.0};
    if (wavelength_nm >= w.back()) return {w.size() - 1, w.size() - 1, 0.0};
    const auto upper = static_cast<std::size_t>(std::upper_bound(w.begin(), w.end(), wavelength_nm) - w.begin());
    return {upper - 1, upper, (wavelength_nm - w[upper - 1]) / (w[upper] - w[upper - 1])};
}

}  // namespace skinspec
