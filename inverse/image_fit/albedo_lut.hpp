#pragma once
// The forward model a skin photograph is inverted through (`skinspec fit-image`, docs/FIT_IMAGE.md): a skin's
// appearance tabulated over two material fields (by default melanosome fraction x dermal blood fraction, as the maps
// of Donner et al. 2008 and Aliaga et al. 2022 are indexed), K channel values per node (linear RGB of the albedo in a
// working space, or band reflectances of a multispectral camera), interpolated between the nodes by bicubic
// Catmull-Rom splines in the sweeps' index coordinates (for a ':log' sweep: evenly in the logarithm of the value).
// The spline passes through every node and has a continuous first derivative, which the pixel fit's Gauss-Newton
// steps need.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "materials/parameter_sweep.hpp"

namespace skinspec {

// The most channels a table holds (a multispectral camera's bands).
inline constexpr std::size_t max_lut_channels = 16;

// A point of the table in index coordinates: u in [0, u.steps - 1] (columns), v in [0, v.steps - 1] (rows).
struct LutPoint {
    double u = 0.0;
    double v = 0.0;
};

// The interpolated channel values at a point and their derivatives along u and v (index coordinates).
struct LutSample {
    std::array<double, max_lut_channels> value{};
    std::array<double, max_lut_channels> d_du{};
    std::array<double, max_lut_channels> d_dv{};
};

class AlbedoLut {
public:
    // `values`: node (column i, row j) channel k at (j * u.steps + i) * channels.size() + k. InputError when an axis
    // has fewer than 2 values, there are no or more than max_lut_channels channels, the sizes disagree, or a value is
    // not finite and positive (a colour outside the working space's gamut has a negative component; the edits
    // re-render by ratios of model values).
    AlbedoLut(ParameterSweep u, ParameterSweep v, std::vector<std::string> channels, std::vector<double> values);

    const ParameterSweep& u() const { return u_; }
    const ParameterSweep& v() const { return v_; }
    const std::vector<std::string>& channels() const { return channels_; }
    std::size_t channel_count() const { return channels_.size(); }
    double node(std::size_t column, std::size_t row, std::size_t channel) const;

    // Values (and derivatives) at `p`, which must lie within the table.
    LutSample sample(LutPoint p) const;

    // The field values at `p` and back: index coordinate <-> value of the sweep (log sweeps in the logarithm).
    static double value_at(const ParameterSweep& sweep, double index);
    static double index_of(const ParameterSweep& sweep, double value);
    // d value / d index at `index`.
    static double value_per_index(const ParameterSweep& sweep, double index);

private:
    ParameterSweep u_, v_;
    std::vector<std::string> channels_;
    std::vector<double> values_;
    // The nodes with one ghost node on every side (linear extrapolation of the two nearest), so that the spline of
    // every cell has its four neighbours: (steps + 2) per axis.
    std::vector<double> padded_;
};

}  // namespace skinspec
