#include "inverse/image_fit/pixel_fit.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

#include "spectral/input_error.hpp"
#include "spectral/parallel_indices.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

// A fit in index coordinates before the noise is known: the sum of squared residuals and J^T J at the solution.
struct RawFit {
    LutPoint at;
    double sse = 0.0;
    double jtj_uu = 0.0, jtj_uv = 0.0, jtj_vv = 0.0;
    bool valid = false;
    bool reached = false;
};

constexpr int max_iterations = 40;
// Index distance from an edge within which a fit is on it.
constexpr double edge_index = 1e-6;

double squared_residual(const LutSample& s, const float* pixel, std::size_t k) {
    double sse = 0.0;
    for (std::size_t c = 0; c < k; ++c) {
        const double r = s.value[c] - pixel[c];
        sse += r * r;
    }
    return sse;
}

// The nodes a fit starts from: about 8 per axis, both edges included.
struct StartNodes {
    std::vector<std::size_t> columns, rows;
};

std::vector<std::size_t> spread_nodes(std::size_t n) {
    const std::size_t stride = std::max<std::size_t>(1, (n - 1) / 7);
    std::vector<std::size_t> at;
    for (std::size_t i = 0; i < n; i += stride) at.push_back(i);
    if (at.back() != n - 1) at.push_back(n - 1);
    return at;
}

RawFit fit_pixel(const AlbedoLut& lut, const float* pixel, const StartNodes& start) {
    const std::size_t k = lut.channel_count();
    RawFit out;
    out.reached = true;
    bool any_positive = false;
    for (std::size_t c = 0; c < k; ++c) {
        if (!std::isfinite(pixel[c]) || pixel[c] < 0.0f) return out;
        any_positive = any_positive || pixel[c] > 0.0f;
    }
    if (!any_positive) return out;
    out.valid = true;
    const std::size_t nu = lut.u().steps, nv = lut.v().steps;
    // Start: the best of the coarse nodes.
    double best = std::numeric_limits<double>::infinity();
    const auto visit = [&](std::size_t i, std::size_t j) {
        double sse = 0.0;
        for (std::size_t c = 0; c < k; ++c) {
            const double r = lut.node(i, j, c) - pixel[c];
            sse += r * r;
        }
        if (sse < best) {
            best = sse;
            out.at = {static_cast<double>(i), static_cast<double>(j)};
        }
    };
    for (const auto j : start.rows) {
        for (const auto i : start.columns) visit(i, j);
    }
    // Levenberg-Marquardt (Marquardt 1963) on the spline, each step projected onto the table's box.
    const double umax = static_cast<double>(nu - 1), vmax = static_cast<double>(nv - 1);
    auto s = lut.sample(out.at);
    double sse = squared_residual(s, pixel, k);
    double lambda = 1e-3;
    for (int it = 0; it < max_iterations; ++it) {
        double a = 0.0, b = 0.0, d = 0.0, gu = 0.0, gv = 0.0;
        for (std::size_t c = 0; c < k; ++c) {
            const double r = s.value[c] - pixel[c];
            a += s.d_du[c] * s.d_du[c];
            b += s.d_du[c] * s.d_dv[c];
            d += s.d_dv[c] * s.d_dv[c];
            gu += s.d_du[c] * r;
            gv += s.d_dv[c] * r;
        }
        const double a_damped = a + lambda * (a + 1e-12), d_damped = d + lambda * (d + 1e-12);
        const double det = a_damped * d_damped - b * b;
        if (!(det > 0.0)) break;
        double du = -(d_damped * gu - b * gv) / det, dv = -(a_damped * gv - b * gu) / det;
        // A coordinate on a bound that the step would take outside stays there; the other takes its own step.
        const bool hold_u = (out.at.u <= 0.0 && du < 0.0) || (out.at.u >= umax && du > 0.0);
        const bool hold_v = (out.at.v <= 0.0 && dv < 0.0) || (out.at.v >= vmax && dv > 0.0);
        if (hold_u && hold_v) break;
        if (hold_u) {
            du = 0.0;
            dv = -gv / d_damped;
        } else if (hold_v) {
            dv = 0.0;
            du = -gu / a_damped;
        }
        const LutPoint next{std::clamp(out.at.u + du, 0.0, umax), std::clamp(out.at.v + dv, 0.0, vmax)};
        const double step = std::hypot(next.u - out.at.u, next.v - out.at.v);
        const auto s_next = lut.sample(next);
        const double sse_next = squared_residual(s_next, pixel, k);
        if (sse_next <= sse) {
            out.at = next;
            s = s_next;
            sse = sse_next;
            lambda = std::max(1e-9, lambda / 4.0);
            if (step < 1e-7) break;
        } else {
            lambda *= 8.0;
            if (lambda > 1e9) break;
        }
    }
    out.sse = sse;
    for (std::size_t c = 0; c < k; ++c) {
        out.jtj_uu += s.d_du[c] * s.d_du[c];
        out.jtj_uv += s.d_du[c] * s.d_dv[c];
        out.jtj_vv += s.d_dv[c] * s.d_dv[c];
    }
    return out;
}

bool on_edge(const AlbedoLut& lut, LutPoint p) {
    return p.u < edge_index || p.v < edge_index || p.u > static_cast<double>(lut.u().steps - 1) - edge_index ||
           p.v > static_cast<double>(lut.v().steps - 1) - edge_index;
}

// Degrees of freedom of a fit's residual (at least 1, so that two channels still give a per-channel RMS).
double residual_dof(std::size_t channels) { return std::max(1.0, static_cast<double>(channels) - 2.0); }

}  // namespace

std::string_view to_string(PixelStatus status) {
    switch (status) {
    case PixelStatus::fitted: return "fitted";
    case PixelStatus::outside_gamut: return "outside the model's gamut";
    case PixelStatus::outside_range: return "on the table's edge";
    case PixelStatus::invalid: return "invalid (negative, not finite or black)";
    case PixelStatus::not_fitted: return "not fitted (stopped)";
    }
    return "";
}

std::size_t ImageFit::count(PixelStatus status) const {
    return static_cast<std::size_t>(std::count_if(pixels.begin(), pixels.end(), [&](const PixelFit& p) { return p.status == status; }));
}

void check_image_size(std::size_t values, int width, int height, std::size_t channels) {
    if (width <= 0 || height <= 0 || values != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels) {
        throw InputError("the image has " + std::to_string(values) + " values for " + std::to_string(width) + " x " + std::to_string(height) +
                         " pixels of " + std::to_string(channels) + " channels");
    }
}

void check_pixel_fit_settings(const PixelFitSettings& settings, std::size_t channels) {
    if (settings.noise && !(std::isfinite(*settings.noise) && *settings.noise > 0.0)) {
        throw InputError("--noise " + format_number(*settings.noise) + " is outside (0, inf)");
    }
    if (!(std::isfinite(settings.gamut_sigma) && settings.gamut_sigma > 0.0)) {
        throw InputError("--gamut-sigma " + format_number(settings.gamut_sigma) + " is outside (0, inf)");
    }
    if (!settings.noise && channels <= 2) {
        throw InputError("--noise: with " + std::to_string(channels) + " channels and two fields to fit, no residual is left to estimate the noise from; give it");
    }
}

double pixel_fit_bytes_per_pixel(std::size_t channels) {
    // The raw fits, the residual list of the noise estimate, the final fits, an edit's copy of the values and its mark.
    return static_cast<double>(sizeof(RawFit) + sizeof(double) + sizeof(PixelFit) + channels * sizeof(float) + sizeof(char));
}

ImageFit fit_image_pixels(const AlbedoLut& lut, const std::vector<float>& values, int width, int height, const PixelFitSettings& settings) {
    const std::size_t k = lut.channel_count();
    check_image_size(values.size(), width, height, k);
    check_pixel_fit_settings(settings, k);
    const auto rows = static_cast<std::size_t>(height), columns = static_cast<std::size_t>(width);
    std::vector<RawFit> raw(rows * columns);
    const StartNodes start{spread_nodes(lut.u().steps), spread_nodes(lut.v().steps)};
    std::atomic<bool> stopped{false};
    std::mutex progress;
    std::size_t rows_done = 0;
    parallel_indices(rows, [&](std::size_t row) {
        if (stopped.load() || (settings.cancel && settings.cancel->load())) {
            stopped = true;
            return;
        }
        for (std::size_t x = 0; x < columns; ++x) {
            const std::size_t i = row * columns + x;
            raw[i] = fit_pixel(lut, &values[i * k], start);
        }
        if (!settings.on_progress) return;
        const std::lock_guard lock(progress);
        settings.on_progress(++rows_done, rows);
    });

    ImageFit out;
    out.width = width;
    out.height = height;
    out.partial = stopped.load();
    if (settings.noise) {
        out.noise = *settings.noise;
    } else {
        // From the median sum of squared residuals (SSE) of the pixels fitted inside the table, with the pixels beyond
        // gamut_sigma noise left out and the median taken again until the noise settles (sigma clipping): a portrait's
        // suit, hair and background would otherwise set the noise. The median of SSE / sigma^2 is the chi-square
        // median of the residual's d degrees of freedom: 0.4549 for d = 1, d (1 - 2 / (9 d))^3 above (Wilson & Hilferty
        // 1931).
        std::vector<double> sses;
        for (const auto& r : raw) {
            if (r.valid && !on_edge(lut, r.at)) sses.push_back(r.sse);
        }
        if (sses.empty()) throw InputError("no pixel of the image is skin within the table's range: the noise cannot be estimated (give --noise)");
        const double d = residual_dof(k);
        const double chi2_median = d == 1.0 ? 0.454936 : d * std::pow(1.0 - 2.0 / (9.0 * d), 3.0);
        std::sort(sses.begin(), sses.end());
        std::size_t kept = sses.size();
        for (int round = 0; round < 100; ++round) {
            // A noiseless image (synthetic) still gets a positive noise.
            out.noise = std::max(std::sqrt(sses[(kept - 1) / 2] / chi2_median), 1e-9);
            const double limit = settings.gamut_sigma * settings.gamut_sigma * out.noise * out.noise * d;
            const auto inside = static_cast<std::size_t>(std::upper_bound(sses.begin(), sses.begin() + static_cast<std::ptrdiff_t>(kept), limit) - sses.begin());
            if (inside == kept || inside == 0) break;
            kept = inside;
        }
        out.noise_estimated = true;
    }
    const auto& u = lut.u();
    const auto& v = lut.v();
    out.pixels.resize(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const auto& r = raw[i];
        auto& p = out.pixels[i];
        if (!r.reached) continue;  // not_fitted
        if (!r.valid) {
            p.status = PixelStatus::invalid;
            continue;
        }
        p.at = r.at;
        p.u_value = AlbedoLut::value_at(u, r.at.u);
        p.v_value = AlbedoLut::value_at(v, r.at.v);
        p.residual = std::sqrt(r.sse / static_cast<double>(k));
        // sigma^2 (J^T J)^-1 in index coordinates, then to the fields' units.
        const double det = r.jtj_uu * r.jtj_vv - r.jtj_uv * r.jtj_uv;
        const double noise2 = out.noise * out.noise;
        const bool determined = det > 0.0 && std::isfinite(det);
        const double var_u = determined ? noise2 * r.jtj_vv / det : 0.0, var_v = determined ? noise2 * r.jtj_uu / det : 0.0;
        p.u_stderr = std::sqrt(var_u) * std::abs(AlbedoLut::value_per_index(u, r.at.u));
        p.v_stderr = std::sqrt(var_v) * std::abs(AlbedoLut::value_per_index(v, r.at.v));
        if (!determined || !std::isfinite(p.u_stderr) || !std::isfinite(p.v_stderr)) {
            p.u_stderr = p.v_stderr = 0.0;
            p.status = PixelStatus::outside_gamut;
        } else if (std::sqrt(r.sse / residual_dof(k)) > settings.gamut_sigma * out.noise) {
            p.status = PixelStatus::outside_gamut;
        } else if (on_edge(lut, r.at)) {
            p.status = PixelStatus::outside_range;
        } else {
            p.status = PixelStatus::fitted;
        }
    }
    return out;
}

FieldEdit parse_field_edit(std::string_view text, const std::string& u_field, const std::string& v_field) {
    const auto eq = text.find('=');
    const auto field = std::string(trim(text.substr(0, eq)));
    if (eq == std::string_view::npos || (field != u_field && field != v_field)) {
        throw InputError("--edit '" + std::string(text) + "': expected FIELD=*SCALE or FIELD=VALUE with FIELD " + u_field + " or " + v_field);
    }
    auto amount = trim(text.substr(eq + 1));
    FieldEdit edit{field, !amount.empty() && amount.front() == '*', 0.0};
    if (edit.scale) amount.remove_prefix(1);
    const auto number = parse_double(amount);
    if (!number || !std::isfinite(*number) || !(*number > 0.0)) {
        throw InputError("--edit '" + std::string(text) + "': '" + std::string(amount) + "' is not a number in (0, inf)");
    }
    edit.amount = *number;
    return edit;
}

EditedImage edited_values(const AlbedoLut& lut, const ImageFit& fit, const std::vector<float>& values, const std::vector<FieldEdit>& edits) {
    const std::size_t k = lut.channel_count();
    const auto& u = lut.u();
    const auto& v = lut.v();
    for (const auto& e : edits) {
        if (e.field != u.field && e.field != v.field) throw std::logic_error("edited_values: " + e.field + " is not a field of the table (parse_field_edit)");
    }
    // A field's edited value as an index coordinate, or none outside the table (within rounding of an end: the end).
    const auto edited_index = [&](const ParameterSweep& sweep, double value) -> std::optional<double> {
        for (const auto& e : edits) {
            if (e.field == sweep.field) value = e.scale ? value * e.amount : e.amount;
        }
        const double lo = std::min(sweep.first, sweep.last), hi = std::max(sweep.first, sweep.last);
        if (value < lo && value > lo * (1.0 - 1e-12)) value = lo;
        if (value > hi && value < hi * (1.0 + 1e-12)) value = hi;
        if (value < lo || value > hi) return std::nullopt;
        return AlbedoLut::index_of(sweep, value);
    };
    EditedImage out{values, 0, 0};
    std::vector<char> rendered(fit.pixels.size(), 0);
    parallel_indices(fit.pixels.size(), [&](std::size_t i) {
        const auto& p = fit.pixels[i];
        if (p.status != PixelStatus::fitted) return;
        const auto eu = edited_index(u, p.u_value), ev = edited_index(v, p.v_value);
        if (!eu || !ev) return;
        const auto before = lut.sample(p.at), after = lut.sample({*eu, *ev});
        for (std::size_t c = 0; c < k; ++c) {
            const double ratio = after.value[c] / before.value[c];
            // The spline between positive nodes stays positive on skin's smooth albedo; a refusal, not a clamp, if not.
            if (!(std::isfinite(ratio) && ratio >= 0.0)) {
                throw InputError("--edit: the model's " + lut.channels()[c] + " is not positive between the table's nodes at pixel " +
                                 std::to_string(i % static_cast<std::size_t>(fit.width)) + ", " + std::to_string(i / static_cast<std::size_t>(fit.width)) +
                                 ": use a finer table");
            }
            out.values[i * k + c] = static_cast<float>(values[i * k + c] * ratio);
        }
        rendered[i] = 1;
    });
    out.rendered = static_cast<std::size_t>(std::count(rendered.begin(), rendered.end(), 1));
    out.beyond_table = fit.count(PixelStatus::fitted) - out.rendered;
    return out;
}

}  // namespace skinspec
