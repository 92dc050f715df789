#include "inverse/iad/inverse_adding_doubling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "skinspec/version.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double b_min = 1e-6;
constexpr double b_max = 1e6;  // adding-doubling's thickest layer (T < e^-1e6): an infinitely thick slab
constexpr double g_bound = 0.99;
constexpr std::size_t max_iterations = 100;
constexpr std::size_t kept_grids = 8;
constexpr double fd_step = 1e-5;
constexpr std::size_t starts = 3;
constexpr std::size_t rows_per_run = 16;

bool same_setup(const SlabSetup& a, const SlabSetup& b) {
    return std::all_of(setup_fields().begin(), setup_fields().end(), [&](const SetupField& f) { return a.*(f.member) == b.*(f.member); });
}

// The unknowns of a search as a point x in a box: (a, ln b), (a, g) at a fixed b, or (a) at b = b_max.
struct Problem {
    IadUnknowns unknowns;
    double b_fixed = b_max;
    double g_fixed = 0.0;
    std::vector<double> lo, hi;
    SlabOptics optics(const std::vector<double>& x) const {
        switch (unknowns) {
            case IadUnknowns::albedo_thickness: return {x[0], std::exp(x[1]), g_fixed};
            case IadUnknowns::albedo_anisotropy: return {x[0], b_fixed, x[1]};
            case IadUnknowns::albedo_only: break;
        }
        return {x[0], b_fixed, g_fixed};
    }
};

Problem make_problem(IadUnknowns unknowns, double b, double g) {
    switch (unknowns) {
        case IadUnknowns::albedo_thickness: return {unknowns, b, g, {0.0, std::log(b_min)}, {1.0, std::log(b_max)}};
        case IadUnknowns::albedo_anisotropy: return {unknowns, b, g, {0.0, -g_bound}, {1.0, g_bound}};
        case IadUnknowns::albedo_only: break;
    }
    return {unknowns, b_max, g, {0.0}, {1.0}};
}

// The grid a search starts from: albedos dense near 1 (where R and T change fastest), b over twelve decades.
std::vector<std::vector<double>> start_grid(const Problem& p) {
    const std::vector<double> albedos{0.0, 0.2, 0.4, 0.6, 0.75, 0.85, 0.9, 0.94, 0.97, 0.985, 0.993, 0.997, 0.999, 1.0};
    std::vector<std::vector<double>> points;
    for (const double a : albedos) {
        if (p.unknowns == IadUnknowns::albedo_only) {
            points.push_back({a});
        } else if (p.unknowns == IadUnknowns::albedo_thickness) {
            for (double log10_b = -3.0; log10_b <= 3.01; log10_b += 0.5) points.push_back({a, log10_b * std::log(10.0)});
        } else {
            for (const double g : {-0.5, 0.0, 0.3, 0.6, 0.8, 0.9, 0.95}) points.push_back({a, g});
        }
    }
    return points;
}

struct Grid {
    SlabSetup setup;
    IadUnknowns unknowns;
    double b_fixed;
    std::vector<std::vector<double>> points;
    std::vector<PredictedMeasurement> predicted;
};

}  // namespace

std::string_view to_string(IadUnknowns unknowns) {
    switch (unknowns) {
        case IadUnknowns::albedo_thickness: return "a,b (g assumed)";
        case IadUnknowns::albedo_anisotropy: return "a,g (b from M_U)";
        case IadUnknowns::albedo_only: return "a (b infinite)";
    }
    return "";
}

struct SlabInverter::State {
    IadSettings settings;
    AdCache cache;
    std::vector<Grid> grids;
    std::size_t evaluations = 0;

    PredictedMeasurement predict(const SlabOptics& optics, const SlabSetup& setup) {
        ++evaluations;
        return predicted_measurement(slab_reflectances(optics, setup, settings.channels, cache), setup);
    }

    const Grid& grid(const Problem& p, const SlabSetup& setup) {
        for (const auto& g : grids) {
            if (g.unknowns == p.unknowns && g.b_fixed == p.b_fixed && same_setup(g.setup, setup)) return g;
        }
        Grid g{setup, p.unknowns, p.b_fixed, start_grid(p), {}};
        for (const auto& x : g.points) {
            if (settings.cancel && settings.cancel->load()) break;
            g.predicted.push_back(predict(p.optics(x), setup));
        }
        if (settings.cancel && settings.cancel->load()) {
            static const Grid empty{};
            return empty;
        }
        if (grids.size() == kept_grids) grids.erase(grids.begin());
        grids.push_back(std::move(g));
        return grids.back();
    }
};

SlabInverter::SlabInverter(IadSettings settings) : state_(std::make_unique<State>()) { state_->settings = settings; }
SlabInverter::~SlabInverter() = default;
SlabInverter::SlabInverter(SlabInverter&&) noexcept = default;
SlabInverter& SlabInverter::operator=(SlabInverter&&) noexcept = default;

PredictedMeasurement SlabInverter::predict(const SlabOptics& optics, const SlabSetup& setup) {
    validate(setup, "");
    return state_->predict(optics, setup);
}

namespace {

// The residuals the search drives to zero: M_R, and M_T unless the slab is infinitely thick, each over
// max(measured, 1e-3) (iad scales by max(measured, 0.01)): a thick sample's T of 0.003 counts as much as its R, or
// the search settles on T = 0 where R alone matches.
struct Target {
    double m_r;
    std::optional<double> m_t;
    static double scale(double measured) { return std::max(measured, 1e-3); }
    std::vector<double> residuals(const PredictedMeasurement& p) const {
        std::vector<double> r{(p.m_r - m_r) / scale(m_r)};
        if (m_t) r.push_back((p.m_t - *m_t) / scale(*m_t));
        return r;
    }
    double largest_difference(const PredictedMeasurement& p) const {
        return std::max(std::abs(p.m_r - m_r), m_t ? std::abs(p.m_t - *m_t) : 0.0);
    }
};

double largest(const std::vector<double>& r) {
    double m = 0.0;
    for (const double x : r) m = std::max(m, std::abs(x));
    return m;
}

// The optical thickness whose unscattered transmission is M_U (monotonic in b: bisection in ln b); check_measurement
// has made sure a clear sample transmits more.
double thickness_from_unscattered(double m_u, const SlabSetup& setup) {
    double lo = std::log(b_min), hi = std::log(b_max);
    for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
        const double mid = 0.5 * (lo + hi);
        (unscattered(std::exp(mid), setup).t > m_u ? lo : hi) = mid;
    }
    return std::exp(0.5 * (lo + hi));
}

}  // namespace

void check_measurement(const SlabMeasurement& m) {
    validate(m.setup, m.source);
    const auto in_unit = [&](const char* name, const std::optional<double>& v) {
        if (v && !(std::isfinite(*v) && *v >= 0.0 && *v <= 1.0)) {
            throw InputError(m.source + ": " + name + " = " + format_number(*v) + " is outside [0, 1]");
        }
    };
    in_unit("M_R", m.m_r);
    in_unit("M_T", m.m_t);
    in_unit("M_U", m.m_u);
    if (!m.m_r) throw InputError(m.source + ": no M_R: the reflection is needed (M_T or M_U alone leave the albedo free)");
    if (m.m_u && *m.m_u > 0.0 && !(m.m_t && *m.m_t > 0.0)) throw InputError(m.source + ": M_U without M_T: give the total transmission too");
    if (m.m_u && *m.m_u > 0.0) {
        const double clear = unscattered(b_min, m.setup).t;
        if (*m.m_u >= clear) {
            throw InputError(m.source + ": M_U = " + format_number(*m.m_u) + " is at or above the unscattered transmission of a clear sample between these faces (" +
                             fmt::format("{:.6g}", clear) + "): no attenuation can produce it");
        }
    }
}

IadResult SlabInverter::invert(const SlabMeasurement& m, const MeasurementUncertainty& uncertainty, const IadResult* previous) {
    auto& s = *state_;
    const auto& setup = m.setup;
    check_measurement(m);

    IadUnknowns unknowns = IadUnknowns::albedo_thickness;
    double b = b_max;
    if (!m.m_t || *m.m_t == 0.0) unknowns = IadUnknowns::albedo_only;
    else if (m.m_u && *m.m_u > 0.0) {
        unknowns = IadUnknowns::albedo_anisotropy;
        b = thickness_from_unscattered(*m.m_u, setup);
    }
    const auto problem = make_problem(unknowns, b, setup.g);
    const Target target{*m.m_r, unknowns == IadUnknowns::albedo_only ? std::nullopt : m.m_t};
    const std::size_t evaluations_before = s.evaluations;
    IadResult out;
    out.unknowns = unknowns;
    const auto cancelled = [&] { return s.settings.cancel && s.settings.cancel->load(); };

    struct Point {
        std::vector<double> x;
        PredictedMeasurement predicted;
        std::vector<double> r;
    };
    const auto evaluate = [&](const std::vector<double>& at) {
        const auto p = s.predict(problem.optics(at), setup);
        return Point{at, p, target.residuals(p)};
    };
    // Forward-difference Jacobian, stepping inwards at a bound. Adding-doubling's R and T jump by ~1e-6 relative where
    // the layer's doublings change (depths 2^k / 256: the thin layer's error), so the step is 1e-5, not 1e-7.
    const auto jacobian = [&](const Point& at) {
        Eigen::MatrixXd j(static_cast<Eigen::Index>(at.r.size()), static_cast<Eigen::Index>(at.x.size()));
        for (std::size_t k = 0; k < at.x.size(); ++k) {
            auto step = at.x;
            double h = fd_step * std::max(1.0, std::abs(at.x[k]));
            if (step[k] + h > problem.hi[k]) h = -h;
            step[k] += h;
            const auto r1 = evaluate(step).r;
            for (std::size_t i = 0; i < at.r.size(); ++i) j(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = (r1[i] - at.r[i]) / h;
        }
        return j;
    };
    const auto cost = [](const std::vector<double>& r) {
        double c = 0.0;
        for (const double v : r) c += v * v;
        return c;
    };
    // Levenberg-Marquardt in the box (the step projected onto it) from x.
    const auto search = [&](const std::vector<double>& start) {
        auto at = evaluate(start);
        double lambda = 1e-3;
        for (std::size_t it = 0; it < max_iterations && largest(at.r) > 1e-3 * s.settings.tolerance && !cancelled(); ++it) {
            const auto j = jacobian(at);
            const Eigen::Map<const Eigen::VectorXd> rv(at.r.data(), static_cast<Eigen::Index>(at.r.size()));
            const Eigen::MatrixXd jtj = j.transpose() * j;
            const Eigen::VectorXd jtr = j.transpose() * rv;
            bool improved = false;
            while (lambda < 1e12) {
                Eigen::MatrixXd a = jtj;
                a.diagonal() += lambda * (jtj.diagonal().array() + 1e-12).matrix();
                const Eigen::VectorXd dx = a.ldlt().solve(-jtr);
                auto trial = at.x;
                for (std::size_t k = 0; k < trial.size(); ++k) trial[k] = std::clamp(trial[k] + dx(static_cast<Eigen::Index>(k)), problem.lo[k], problem.hi[k]);
                if (trial == at.x) break;
                auto next = evaluate(trial);
                if (cost(next.r) < cost(at.r)) {
                    // Settled when the cost stops falling (an unreachable measurement creeps along a bound).
                    improved = cost(next.r) < (1.0 - 1e-6) * cost(at.r);
                    at = std::move(next);
                    lambda = std::max(lambda / 10.0, 1e-12);
                    break;
                }
                lambda *= 10.0;
            }
            if (!improved) break;
        }
        return at;
    };
    // Starts: the previous row's result (a spectrum's neighbours are close); unless it fits, the grid points closest to
    // the measurement, the best three, until one fits (the grid is computed once per setup, when first needed).
    std::optional<Point> best;
    const auto fits_from = [&](const std::vector<double>& start) {
        auto found = search(start);
        if (!best || cost(found.r) < cost(best->r)) best = std::move(found);
        return target.largest_difference(best->predicted) <= s.settings.tolerance;
    };
    bool fitted = false;
    if (previous && previous->reachable && previous->unknowns == unknowns) {
        const auto& o = previous->optics;
        if (unknowns == IadUnknowns::albedo_thickness) fitted = fits_from({o.albedo, std::log(o.optical_thickness)});
        else if (unknowns == IadUnknowns::albedo_anisotropy) fitted = fits_from({o.albedo, std::clamp(o.g, -g_bound, g_bound)});
        else fitted = fits_from({o.albedo});
    }
    if (!fitted && !cancelled()) {
        const auto& grid = s.grid(problem, setup);
        std::vector<std::size_t> order(grid.points.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return cost(target.residuals(grid.predicted[i])) < cost(target.residuals(grid.predicted[j])); });
        for (std::size_t k = 0; k < std::min<std::size_t>(starts, order.size()) && !cancelled(); ++k) {
            if (fits_from(grid.points[order[k]])) break;
        }
    }
    if (cancelled() || !best) {
        out.cancelled = true;
        return out;
    }

    out.optics = problem.optics(best->x);
    out.fitted = best->predicted;
    out.residual = target.largest_difference(out.fitted);
    out.reachable = out.residual <= s.settings.tolerance;
    const double d = setup.sample_thickness_mm;
    if (unknowns == IadUnknowns::albedo_only) {
        out.optics.optical_thickness = inf;
    } else {
        const double bb = out.optics.optical_thickness;
        out.mu_a_per_mm = (1.0 - out.optics.albedo) * bb / d;
        out.mu_s_per_mm = out.optics.albedo * bb / d;
        out.mu_s_reduced_per_mm = out.optics.albedo * bb * (1.0 - out.optics.g) / d;
    }
    if (unknowns == IadUnknowns::albedo_anisotropy) out.fitted_m_u = unscattered(out.optics.optical_thickness, setup).t;
    if (!out.reachable) {
        out.unreachable = fmt::format(
            "{}: M_R = {}{} cannot be produced by a slab of index {} {}with g {}: the closest (relative to each measurement) is M_R = {:.5f}{} (a = {:.6g}, b = {})",
            m.source, format_number(*m.m_r), target.m_t ? ", M_T = " + format_number(*target.m_t) : std::string(), format_number(setup.sample_index),
            setup.slide_index != 1.0 && setup.slide_thickness_mm > 0.0 ? "between slides of index " + format_number(setup.slide_index) + " " : "",
            unknowns == IadUnknowns::albedo_anisotropy ? "in (-0.99, 0.99)" : "= " + format_number(setup.g), out.fitted.m_r,
            target.m_t ? fmt::format(", M_T = {:.5f}", out.fitted.m_t) : std::string(), out.optics.albedo,
            std::isinf(out.optics.optical_thickness) ? std::string("inf") : fmt::format("{:.6g}", out.optics.optical_thickness));
    }

    // Uncertainties: the measurements' through the inverse Jacobian of (M_R, M_T, M_U) in (a, ln b, g).
    if (uncertainty.given() && out.reachable) {
        std::vector<double> vars{out.optics.albedo};
        if (unknowns != IadUnknowns::albedo_only) vars.push_back(std::log(out.optics.optical_thickness));
        if (unknowns == IadUnknowns::albedo_anisotropy) vars.push_back(out.optics.g);
        const auto rows_at = [&](const std::vector<double>& v) {
            const SlabOptics o{v[0], v.size() > 1 ? std::exp(v[1]) : b_max, v.size() > 2 ? v[2] : setup.g};
            const auto p = s.predict(o, setup);
            std::vector<double> rows{p.m_r};
            if (v.size() > 1) rows.push_back(p.m_t);
            if (v.size() > 2) rows.push_back(unscattered(o.optical_thickness, setup).t);
            return rows;
        };
        // At the solution: the forward solution the search ended on (not solved again).
        std::vector<double> rows0{out.fitted.m_r};
        if (vars.size() > 1) rows0.push_back(out.fitted.m_t);
        if (vars.size() > 2) rows0.push_back(*out.fitted_m_u);
        const auto n = static_cast<Eigen::Index>(vars.size());
        Eigen::MatrixXd j(n, n);
        for (Eigen::Index k = 0; k < n; ++k) {
            auto step = vars;
            const auto kk = static_cast<std::size_t>(k);
            double h = fd_step * std::max(1.0, std::abs(vars[kk]));
            if ((kk == 0 && vars[kk] + h > 1.0) || (kk == 2 && vars[kk] + h > g_bound)) h = -h;
            step[kk] += h;
            const auto rows1 = rows_at(step);
            for (Eigen::Index i = 0; i < n; ++i) j(i, k) = (rows1[static_cast<std::size_t>(i)] - rows0[static_cast<std::size_t>(i)]) / h;
        }
        Eigen::VectorXd sigma(n);
        sigma(0) = uncertainty.m_r;
        if (n > 1) sigma(1) = uncertainty.m_t;
        if (n > 2) sigma(2) = uncertainty.m_u;
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(j);
        const auto stderr_of = [&](const Eigen::VectorXd& gradient) {
            if (!lu.isInvertible()) return gradient.isZero(0.0) ? 0.0 : inf;
            // var(q) = grad^T J^-1 S^2 J^-T grad
            const Eigen::VectorXd w = lu.transpose().solve(gradient);
            return std::sqrt((w.array() * sigma.array()).square().sum());
        };
        const double a = out.optics.albedo;
        Eigen::VectorXd ga = Eigen::VectorXd::Zero(n);
        ga(0) = 1.0;
        out.albedo_stderr = stderr_of(ga);
        if (n > 1) {
            const double bb = out.optics.optical_thickness, g = out.optics.g;
            Eigen::VectorXd mua = Eigen::VectorXd::Zero(n), musr = Eigen::VectorXd::Zero(n);
            mua(0) = -bb / d;
            mua(1) = (1.0 - a) * bb / d;
            musr(0) = bb * (1.0 - g) / d;
            musr(1) = a * bb * (1.0 - g) / d;
            if (n > 2) {
                musr(2) = -a * bb / d;
                Eigen::VectorXd gg = Eigen::VectorXd::Zero(n);
                gg(2) = 1.0;
                out.g_stderr = stderr_of(gg);
            }
            out.mu_a_stderr_per_mm = stderr_of(mua);
            out.mu_s_reduced_stderr_per_mm = stderr_of(musr);
        }
    }
    out.evaluations = s.evaluations - evaluations_before;
    return out;
}

IadRun invert_rows(const std::vector<SlabMeasurement>& rows, const MeasurementUncertainty& uncertainty, const IadSettings& settings,
                   const std::function<void(std::size_t, std::size_t)>& progress) {
    for (const auto& r : rows) check_measurement(r);
    std::vector<std::optional<IadResult>> results(rows.size());
    tbb::enumerable_thread_specific<SlabInverter> inverters([&] { return SlabInverter(settings); });
    std::size_t done = 0;
    std::mutex report;
    const auto cancelled = [&] { return settings.cancel && settings.cancel->load(); };
    const std::size_t runs = (rows.size() + rows_per_run - 1) / rows_per_run;
    tbb::parallel_for(std::size_t{0}, runs, [&](std::size_t run) {
        auto& inverter = inverters.local();
        const IadResult* previous = nullptr;
        for (std::size_t i = run * rows_per_run; i < std::min(rows.size(), (run + 1) * rows_per_run) && !cancelled(); ++i) {
            auto result = inverter.invert(rows[i], uncertainty, previous);
            if (result.cancelled) return;
            results[i] = std::move(result);
            previous = &*results[i];
            const std::lock_guard lock(report);
            ++done;
            if (progress) progress(done, rows.size());
        }
    });
    IadRun out;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!results[i]) {
            ++out.unfinished;
            continue;
        }
        out.evaluations += results[i]->evaluations;
        if (results[i]->reachable) out.rows.push_back({rows[i], std::move(*results[i])});
        else out.unreachable.push_back(results[i]->unreachable);
    }
    return out;
}

nlohmann::ordered_json iad_json(const IadRun& run, const SlabSetup& setup, const std::string& input, const IadSettings& settings,
                                const MeasurementUncertainty& uncertainty, bool partial, double seconds) {
    using Json = nlohmann::ordered_json;
    Json setup_json = Json::object(), list = Json::array();
    for (const auto& f : setup_fields()) setup_json[std::string(f.key)] = setup.*(f.member);
    for (const auto& r : run.rows) {
        Json j{{"source", r.measurement.source}, {"unknowns", std::string(to_string(r.result.unknowns))}};
        for (const auto& f : iad_result_fields()) {
            const auto v = f.value(r);
            j[std::string(f.key)] = v ? Json(*v) : Json(nullptr);
        }
        list.push_back(std::move(j));
    }
    const Json measured = uncertainty.given() ? Json{{"m_r", uncertainty.m_r}, {"m_t", uncertainty.m_t}, {"m_u", uncertainty.m_u}} : Json(nullptr);
    return Json{{"skinspec_version", version}, {"schema", "skinspec-iad/1"}, {"input", input}, {"setup", setup_json}, {"channels", settings.channels},
                {"tolerance", settings.tolerance}, {"measurement_uncertainty", measured}, {"partial", partial}, {"seconds", seconds},
                {"rows", list}, {"unreachable", run.unreachable}};
}

const std::vector<IadField>& iad_result_fields() {
    using R = IadRow;
    static const std::vector<IadField> fields{
        {"wavelength_nm", "nm", [](const R& r) { return r.measurement.wavelength_nm; }, "wavelength of the row (when the file gives one)"},
        {"m_r", "1", [](const R& r) { return r.measurement.m_r; }, "measured M_R"},
        {"m_r_fit", "1", [](const R& r) { return std::optional(r.result.fitted.m_r); }, "M_R predicted at the result"},
        {"m_t", "1", [](const R& r) { return r.measurement.m_t; }, "measured M_T"},
        {"m_t_fit", "1", [](const R& r) { return r.measurement.m_t ? std::optional(r.result.fitted.m_t) : std::nullopt; }, "M_T predicted at the result"},
        {"m_u", "1", [](const R& r) { return r.measurement.m_u; }, "measured unscattered transmission M_U"},
        {"m_u_fit", "1", [](const R& r) { return r.result.fitted_m_u; }, "M_U predicted at the result"},
        {"mu_a_per_mm", "1/mm", [](const R& r) { return r.result.mu_a_per_mm; }, "absorption coefficient"},
        {"mu_a_stderr_per_mm", "1/mm", [](const R& r) { return r.result.mu_a_stderr_per_mm; }, "its standard uncertainty"},
        {"mu_s_reduced_per_mm", "1/mm", [](const R& r) { return r.result.mu_s_reduced_per_mm; }, "reduced scattering coefficient mu_s (1 - g)"},
        {"mu_s_reduced_stderr_per_mm", "1/mm", [](const R& r) { return r.result.mu_s_reduced_stderr_per_mm; }, "its standard uncertainty"},
        {"mu_s_per_mm", "1/mm", [](const R& r) { return r.result.mu_s_per_mm; }, "scattering coefficient"},
        {"g", "1", [](const R& r) { return std::optional(r.result.optics.g); }, "anisotropy (fitted with M_U, else the one assumed)"},
        {"g_stderr", "1", [](const R& r) { return r.result.g_stderr; }, "its standard uncertainty (fitted g only)"},
        {"albedo", "1", [](const R& r) { return std::optional(r.result.optics.albedo); }, "single-scattering albedo a = mu_s / (mu_a + mu_s)"},
        {"albedo_stderr", "1", [](const R& r) { return r.result.albedo_stderr; }, "its standard uncertainty"},
        {"optical_thickness", "1", [](const R& r) { return std::isinf(r.result.optics.optical_thickness) ? std::nullopt : std::optional(r.result.optics.optical_thickness); },
         "b = (mu_a + mu_s) d (none: infinitely thick)"},
        {"residual", "1", [](const R& r) { return std::optional(r.result.residual); }, "largest |predicted - measured|"},
    };
    return fields;
}

}  // namespace skinspec
