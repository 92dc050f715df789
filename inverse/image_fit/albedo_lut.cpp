#include "inverse/image_fit/albedo_lut.hpp"

#include <algorithm>
#include <cmath>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// Catmull-Rom weights of the nodes i-1, i, i+1, i+2 at t in [0, 1] of cell [i, i+1], and their derivatives
// (Catmull & Rom 1974; the cardinal spline of tension 0.5, e.g. Keys 1981 Eq. 15 with a = -0.5).
struct CubicWeights {
    std::array<double, 4> w;
    std::array<double, 4> dw;
};

CubicWeights catmull_rom(double t) {
    const double t2 = t * t, t3 = t2 * t;
    return {{0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0), 0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)},
            {0.5 * (-3.0 * t2 + 4.0 * t - 1.0), 0.5 * (9.0 * t2 - 10.0 * t), 0.5 * (-9.0 * t2 + 8.0 * t + 1.0), 0.5 * (3.0 * t2 - 2.0 * t)}};
}

// The cell of `x` in [0, n - 1] and the position within it.
std::pair<std::size_t, double> cell(double x, std::size_t n) {
    const auto i = std::min(static_cast<std::size_t>(std::max(0.0, std::floor(x))), n - 2);
    return {i, x - static_cast<double>(i)};
}

}  // namespace

AlbedoLut::AlbedoLut(ParameterSweep u, ParameterSweep v, std::vector<std::string> channels, std::vector<double> values)
    : u_(std::move(u)), v_(std::move(v)), channels_(std::move(channels)), values_(std::move(values)) {
    for (const auto* s : {&u_, &v_}) {
        if (s->steps < 2) throw InputError(s->field + ": the look-up table needs at least 2 values per axis, got " + std::to_string(s->steps));
    }
    const std::size_t k = channels_.size();
    if (k == 0 || k > max_lut_channels) {
        throw InputError("the look-up table has " + std::to_string(k) + " channels; allowed 1 to " + std::to_string(max_lut_channels));
    }
    if (values_.size() != u_.steps * v_.steps * k) throw std::logic_error("AlbedoLut: values do not match the axes and channels");
    for (std::size_t i = 0; i < values_.size(); ++i) {
        if (!(std::isfinite(values_[i]) && values_[i] > 0.0)) {
            const std::size_t node = i / k;
            throw InputError("the model's " + channels_[i % k] + " is " + format_number(values_[i]) + " at " + u_.field + " = " +
                             format_number(u_.values()[node % u_.steps]) + ", " + v_.field + " = " + format_number(v_.values()[node / u_.steps]) +
                             " (allowed: finite and > 0; a colour outside the working space's gamut has a negative component: choose a "
                             "wider space)");
        }
    }
    const std::size_t nu = u_.steps + 2, nv = v_.steps + 2;
    padded_.assign(nu * nv * k, 0.0);
    const auto at = [&](std::size_t i, std::size_t j) { return &padded_[(j * nu + i) * k]; };
    for (std::size_t j = 0; j < v_.steps; ++j) {
        for (std::size_t i = 0; i < u_.steps; ++i) std::copy_n(&values_[(j * u_.steps + i) * k], k, at(i + 1, j + 1));
    }
    // Ghost columns, then ghost rows (which fills the corners from the ghost columns).
    for (std::size_t j = 1; j + 1 < nv; ++j) {
        for (std::size_t c = 0; c < k; ++c) {
            at(0, j)[c] = 2.0 * at(1, j)[c] - at(2, j)[c];
            at(nu - 1, j)[c] = 2.0 * at(nu - 2, j)[c] - at(nu - 3, j)[c];
        }
    }
    for (std::size_t i = 0; i < nu; ++i) {
        for (std::size_t c = 0; c < k; ++c) {
            at(i, 0)[c] = 2.0 * at(i, 1)[c] - at(i, 2)[c];
            at(i, nv - 1)[c] = 2.0 * at(i, nv - 2)[c] - at(i, nv - 3)[c];
        }
    }
}

double AlbedoLut::node(std::size_t column, std::size_t row, std::size_t channel) const {
    return values_[(row * u_.steps + column) * channels_.size() + channel];
}

LutSample AlbedoLut::sample(LutPoint p) const {
    const std::size_t k = channels_.size(), nu = u_.steps + 2;
    const auto [i, s] = cell(p.u, u_.steps);
    const auto [j, t] = cell(p.v, v_.steps);
    const auto wu = catmull_rom(s), wv = catmull_rom(t);
    LutSample out;
    // Padded node (i + a, j + b) is node (i - 1 + a, j - 1 + b).
    for (std::size_t b = 0; b < 4; ++b) {
        for (std::size_t a = 0; a < 4; ++a) {
            const double* n = &padded_[((j + b) * nu + i + a) * k];
            const double w = wu.w[a] * wv.w[b], wdu = wu.dw[a] * wv.w[b], wdv = wu.w[a] * wv.dw[b];
            for (std::size_t c = 0; c < k; ++c) {
                out.value[c] += w * n[c];
                out.d_du[c] += wdu * n[c];
                out.d_dv[c] += wdv * n[c];
            }
        }
    }
    return out;
}

double AlbedoLut::value_at(const ParameterSweep& sweep, double index) {
    const double f = index / static_cast<double>(sweep.steps - 1);
    if (sweep.log) return std::exp(std::log(sweep.first) + f * (std::log(sweep.last) - std::log(sweep.first)));
    return sweep.first + f * (sweep.last - sweep.first);
}

double AlbedoLut::index_of(const ParameterSweep& sweep, double value) {
    const double n = static_cast<double>(sweep.steps - 1);
    if (sweep.log) return n * (std::log(value) - std::log(sweep.first)) / (std::log(sweep.last) - std::log(sweep.first));
    return n * (value - sweep.first) / (sweep.last - sweep.first);
}

double AlbedoLut::value_per_index(const ParameterSweep& sweep, double index) {
    const double n = static_cast<double>(sweep.steps - 1);
    if (sweep.log) return value_at(sweep, index) * (std::log(sweep.last) - std::log(sweep.first)) / n;
    return (sweep.last - sweep.first) / n;
}

}  // namespace skinspec
