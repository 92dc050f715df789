#include "inverse/spectrum_fit/spectrum_fit.hpp"

#include <algorithm>
#include <functional>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include <mutex>

#include <Eigen/Dense>
#include <nlopt.hpp>
#include <tbb/parallel_for.h>

#include "spectral/ciede2000.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "transport/adding_doubling/adding_doubling_spectrum.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"
#include "transport/rte/rte_model.hpp"
#include "transport/biospec/biospec_solver.hpp"
#include "transport/random_stream.hpp"

namespace skinspec {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Radical inverse of i in `base` (Halton 1960): the scan's quasi-random points, the same for every run.
double radical_inverse(std::size_t i, std::size_t base) {
    double f = 1.0, r = 0.0;
    for (; i > 0; i /= base) {
        f /= static_cast<double>(base);
        r += f * static_cast<double>(i % base);
    }
    return r;
}

constexpr std::size_t primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};

}  // namespace

const std::vector<FitEngineChoice>& fit_engines() {
    static const std::vector<FitEngineChoice> engines{
        {"biospec", FitEngine::replayed_walk, "the BioSpec walk's paths traced once and re-weighted (default; Monte Carlo)"},
        {"biospec-adding-doubling", FitEngine::biospec_adding_doubling, "the BioSpec model solved exactly at every evaluation (no noise, any layer field free)"},
        {"adding-doubling", FitEngine::adding_doubling,
         "the volumetric description solved exactly at every evaluation (e.g. the layers' own measured scattering with "
         "--set model.volumetric_matched_to_biospec=false)"},
    };
    return engines;
}

FitEngine parse_fit_engine(std::string_view name, std::string_view origin) {
    std::string allowed;
    for (const auto& e : fit_engines()) {
        if (e.name == name) return e.engine;
        allowed += (allowed.empty() ? "" : ", ") + std::string(e.name);
    }
    throw InputError(std::string(origin) + ": '" + std::string(name) + "' is not a fit mode (allowed: " + allowed + ")");
}

std::string_view to_string(FitEngine engine) {
    for (const auto& e : fit_engines()) {
        if (e.engine == engine) return e.name;
    }
    return "biospec";
}

std::vector<FitParameter> default_free_parameters() {
    return {{"epidermis.melanosome_fraction", {}, {}},
            {"papillary_dermis.blood_fraction", {}, {}},
            {"reticular_dermis.blood_fraction", {}, {}},
            {"dermis.oxygen_saturation", {}, {}}};
}

std::pair<double, double> default_fit_bounds(const NumberField<TissueLayer>& field, double current) {
    if (field.fit_bounds) return *field.fit_bounds;             // the field table's range (materials/material_fields.cpp)
    if (current > 0.0) return {0.5 * current, 2.0 * current};   // thicknesses, concentrations: a factor-of-two band
    return {0.0, 1.0};
}

std::vector<ResidualBand> residual_bands(const std::vector<SpectrumFit>& fits) {
    // Shared spec "Measured skin to compare with": the blue and its Soret dip, the haemoglobin Q bands, the early
    // red edge, the red plateau.
    std::vector<ResidualBand> bands{{"blue 400-450 nm", 400.0, 450.0, 0.0, 0},
                                    {"540-580 nm", 540.0, 580.0, 0.0, 0},
                                    {"590-600 nm", 590.0, 600.0, 0.0, 0},
                                    {"red 610-700 nm", 610.0, 700.0, 0.0, 0}};
    for (auto& b : bands) {
        double sum = 0.0;
        for (const auto& f : fits) {
            for (std::size_t w = 0; w < f.wavelength_nm.size(); ++w) {
                if (f.wavelength_nm[w] < b.from_nm || f.wavelength_nm[w] > b.to_nm) continue;
                sum += f.fitted[w] - f.measured[w];
                ++b.samples;
            }
        }
        b.mean_residual = b.samples > 0 ? sum / static_cast<double>(b.samples) : 0.0;
    }
    return bands;
}

SpectrumFitter::SpectrumFitter(const LayerStack& base, const std::vector<double>& wavelength_nm, const SpectrumFitSettings& settings)
    : base_(base), settings_(settings) {
    if (settings.free.empty()) throw InputError("--free: no free parameters");
    if (settings.starts < 1 || settings.starts > SpectrumFitSettings::scan_points) {
        throw InputError("--starts " + std::to_string(settings.starts) + " is outside [1, " + std::to_string(SpectrumFitSettings::scan_points) +
                         "] (the local searches start from the best points of a " + std::to_string(SpectrumFitSettings::scan_points) + "-point scan)");
    }
    if (!(settings.window_from_nm < settings.window_to_nm)) {
        throw InputError("--window " + format_number(settings.window_from_nm) + ":" + format_number(settings.window_to_nm) + ": FROM must be below TO");
    }
    for (const auto& p : settings.free) {
        auto handle = layer_field(base, p.key, "--free");
        if (const auto why = unread_in_layers(base, p.key)) throw InputError("--free '" + p.key + "': " + *why + " (the fit would not move it)");
        const auto& f = *handle.field;
        if (!f.absorption_only && settings.engine == FitEngine::replayed_walk) {
            const bool scalable = f.key == "thickness_cm" && std::all_of(handle.layers.begin(), handle.layers.end(), [&](std::size_t k) {
                return crossing_in_effect(base.layers[k], base.model) != CrossingScattering::rayleigh_cosine;
            });
            if (!scalable) {
                std::string allowed;
                for (const auto& g : layer_number_fields()) {
                    if (g.absorption_only) allowed += std::string(g.key) + ", ";
                }
                throw InputError("--free '" + p.key + "': a fit re-weights traced paths, so a free field must change absorption only (" +
                                 allowed + "or thickness_cm of a layer without Rayleigh scattering); --mode biospec-adding-doubling takes any");
            }
        }
        for (const auto& other : keys_) {
            if (other == p.key) throw InputError("--free '" + p.key + "' is given twice");
        }
        const auto [lo0, hi0] = default_fit_bounds(f, handle.get(base));
        const double lo = p.lo.value_or(lo0), hi = p.hi.value_or(hi0);
        if (!f.range.contains(lo) || !f.range.contains(hi)) {
            throw InputError("--bounds " + p.key + "=" + format_number(lo) + ":" + format_number(hi) + ": outside the field's range " + f.range.text());
        }
        if (!(lo < hi)) throw InputError("--bounds " + p.key + "=" + format_number(lo) + ":" + format_number(hi) + ": LO must be below HI");
        keys_.push_back(p.key);
        bounds_.emplace_back(lo, hi);
        log_scale_.push_back(lo > 0.0 && hi / lo > 10.0);
        handles_.push_back(std::move(handle));
    }
    for (std::size_t i = 0; i < wavelength_nm.size(); ++i) {
        const double nm = wavelength_nm[i];
        if (nm < settings.window_from_nm || nm > settings.window_to_nm) continue;
        used_.push_back(i);
        wavelengths_nm_.push_back(nm);
        double w = 1.0;
        for (const auto& ww : settings.weights) {
            if (nm >= ww.from_nm && nm <= ww.to_nm) w = ww.weight;
        }
        weights_.push_back(w);
    }
    if (std::none_of(weights_.begin(), weights_.end(), [](double w) { return w > 0.0; })) {
        throw InputError("--weight: every measured wavelength of the window has weight 0; nothing is left to fit");
    }
    if (used_.size() < 5) {
        const bool windowed = settings.window_from_nm > 0.0 || std::isfinite(settings.window_to_nm);
        throw InputError(std::to_string(used_.size()) + " measured wavelengths to fit" +
                         (windowed ? " in --window " + format_number(settings.window_from_nm) + ":" + format_number(settings.window_to_nm) : "") +
                         "; a fit needs at least 5");
    }
    // Every chromophore table must cover every fitted wavelength at both ends of the bounds.
    for (const bool upper : {false, true}) {
        auto stack = base_;
        for (std::size_t p = 0; p < handles_.size(); ++p) handles_[p].set(stack, upper ? bounds_[p].second : bounds_[p].first);
        for (std::size_t at = 0; at < wavelengths_nm_.size(); ++at) {
            const double nm = wavelengths_nm_[at];
            for (const auto& layer : stack.layers) {
                try {
                    absorption_per_cm(layer, nm, stack.model);
                } catch (const InputError& e) {
                    const auto& sources = settings.wavelength_sources;
                    const std::string where = used_[at] < sources.size() ? sources[used_[at]] + ": " : std::string();
                    throw InputError(where + "wavelength " + format_number(nm) + " nm is outside the model's tables (layer '" + layer.name + "'): " + e.what());
                }
            }
        }
    }
    if (!traces_rays(settings.engine)) {
        if (settings.geometry == MeasurementGeometry::zero_45) {
            throw InputError("--geometry 0-45: " + std::string(to_string(settings.engine)) + " computes hemispherical totals (the walk measures 0-45)");
        }
        exact_model({}, nullptr);  // refuses what the exact model cannot solve, before any fit
        return;
    }
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list(wavelengths_nm_);
    request.geometry = settings.geometry;
    request.incidence_deg = settings.incidence_deg;
    request.seed = settings.seed;
    request.max_rays_per_wavelength = settings.rays_per_wavelength;
    request.cancel = settings.cancel;
    auto paths = record_biospec_paths(base_, request, settings.walk);
    if (!paths) {
        cancelled_ = true;
        return;
    }
    paths_ = std::move(*paths);
    thin_paths();
}

void SpectrumFitter::thin_paths() {
    // The floor: each layer's smallest effective absorption (mu_a times its thickness ratio) over the corners of the
    // bounds. Absorption is multilinear in the fractions and concentrations, so its extremes are corners; the
    // packaging factors make it only nearly so, and a floor above some evaluated absorption raises that
    // evaluation's variance, never its mean (ExitPaths::thin). Beyond 8 free fields (256 corners) nothing is thinned.
    const std::size_t free = handles_.size();
    if (free > max_thinning_fields) return;
    const std::size_t corners = std::size_t{1} << free, layers = base_.layers.size();
    std::vector<LayerStack> corner_stacks;
    for (std::size_t c = 0; c < corners; ++c) {
        auto stack = base_;
        for (std::size_t j = 0; j < free; ++j) handles_[j].set(stack, (c >> j) & 1 ? bounds_[j].second : bounds_[j].first);
        corner_stacks.push_back(std::move(stack));
    }
    tbb::parallel_for(std::size_t{0}, paths_.size(), [&](std::size_t w) {
        std::vector<double> floor(layers, std::numeric_limits<double>::infinity());
        for (const auto& stack : corner_stacks) {
            for (std::size_t k = 0; k < layers; ++k) {
                const double scale = stack.layers[k].thickness_cm / base_.layers[k].thickness_cm;
                floor[k] = std::min(floor[k], absorption_per_cm(stack.layers[k], wavelengths_nm_[w], stack.model) * scale);
            }
        }
        paths_[w].thin(floor, RandomStream::for_batch(settings_.seed, wavelengths_nm_[w], thinning_stream).bits64());
    });
}

std::uint64_t SpectrumFitter::rays() const {
    std::uint64_t n = 0;
    for (const auto& p : paths_) n += p.rays;
    return n;
}

std::vector<Estimate> SpectrumFitter::model(const std::vector<double>& parameters, std::vector<std::vector<double>>* jacobian) const {
    return traces_rays(settings_.engine) ? replayed_model(parameters, jacobian) : exact_model(parameters, jacobian);
}

// `parameters` empty: the base material's own values.
BiospecAdOptions SpectrumFitter::exact_options(bool accuracy_check) const {
    BiospecAdOptions options;
    options.ad = AdOptions{settings_.channels, accuracy_check};
    options.fold_into_skin = settings_.walk.fold_into_skin;
    options.thin_layer_hg = settings_.walk.thin_layer_hg;
    return options;
}

LayerStack SpectrumFitter::stack_at(const std::vector<double>& parameters) const {
    auto stack = base_;
    for (std::size_t p = 0; p < parameters.size(); ++p) handles_[p].set(stack, parameters[p]);
    return stack;
}

std::vector<Estimate> SpectrumFitter::exact_model(const std::vector<double>& parameters, std::vector<std::vector<double>>* jacobian) const {
    // One cache per thread: the measured profiles' moments and redistribution matrices outlive the evaluations.
    thread_local AdCache cache;
    const auto options = exact_options(false);
    const bool excluded = settings_.geometry == MeasurementGeometry::sce;
    const auto values = [&](const std::vector<double>& at) {
        const auto stack = stack_at(at);
        std::vector<double> r;
        for (const double nm : wavelengths_nm_) {
            const auto t = settings_.engine == FitEngine::biospec_adding_doubling
                               ? solve_biospec_adding_doubling(stack, nm, settings_.incidence_deg, options, &cache).totals
                               : solve_adding_doubling(rte_stack_from(stack, nm), AdIncidence{false, settings_.incidence_deg}, options.ad, &cache);
            r.push_back(t.diffuse_reflectance + (excluded ? 0.0 : t.specular_reflectance));
        }
        return r;
    };
    const auto at = values(parameters);
    std::vector<Estimate> out;
    for (const double r : at) out.push_back({r, 0.0});
    if (!jacobian) return out;
    jacobian->assign(at.size(), std::vector<double>(parameters.size(), 0.0));
    for (std::size_t j = 0; j < parameters.size(); ++j) {
        const auto [lo, hi] = bounds_[j];
        double step = 1e-5 * std::max(std::abs(parameters[j]), hi - lo);
        if (parameters[j] + step > hi) step = -step;
        auto moved = parameters;
        moved[j] += step;
        const auto r = values(moved);
        for (std::size_t w = 0; w < at.size(); ++w) (*jacobian)[w][j] = (r[w] - at[w]) / step;
    }
    return out;
}

std::vector<Estimate> SpectrumFitter::replayed_model(const std::vector<double>& parameters, std::vector<std::vector<double>>* jacobian) const {
    const auto stack = stack_at(parameters);
    const std::size_t layers = stack.layers.size(), n = paths_.size(), free = handles_.size();
    std::vector<double> scale(layers);
    for (std::size_t k = 0; k < layers; ++k) scale[k] = stack.layers[k].thickness_cm / base_.layers[k].thickness_cm;
    std::vector<std::vector<double>> mu(n, std::vector<double>(layers));
    for (std::size_t w = 0; w < n; ++w) {
        for (std::size_t k = 0; k < layers; ++k) mu[w][k] = absorption_per_cm(stack.layers[k], wavelengths_nm_[w], stack.model);
    }
    // d(mu_a,k scale_k) / dparameter_j per wavelength: a thickness scales the paths; any other field changes mu_a,
    // differentiated by a one-sided difference (mu_a is linear in every fraction and concentration).
    std::vector<std::vector<std::vector<double>>> d_effective;
    if (jacobian) {
        d_effective.assign(free, std::vector<std::vector<double>>(n, std::vector<double>(layers, 0.0)));
        for (std::size_t j = 0; j < free; ++j) {
            const auto& h = handles_[j];
            if (h.field->key == "thickness_cm") {
                for (std::size_t w = 0; w < n; ++w) {
                    for (const auto k : h.layers) d_effective[j][w][k] = mu[w][k] / base_.layers[k].thickness_cm;
                }
                continue;
            }
            const auto [lo, hi] = bounds_[j];
            double step = 1e-6 * std::max(std::abs(parameters[j]), hi - lo);
            if (parameters[j] + step > hi) step = -step;
            auto moved = stack;
            h.set(moved, parameters[j] + step);
            for (std::size_t w = 0; w < n; ++w) {
                for (const auto k : h.layers) {
                    d_effective[j][w][k] = (absorption_per_cm(moved.layers[k], wavelengths_nm_[w], moved.model) - mu[w][k]) / step * scale[k];
                }
            }
        }
        jacobian->assign(n, std::vector<double>(free, 0.0));
    }
    // dR/dm_k only where a free parameter reaches (the others would be multiplied by 0 below).
    std::vector<bool> reached(layers, false);
    for (const auto& h : handles_) {
        for (const auto k : h.layers) reached[k] = true;
    }
    std::vector<Estimate> out;
    out.reserve(n);
    std::vector<double> d_r;
    for (std::size_t w = 0; w < n; ++w) {
        out.push_back(paths_[w].reflectance(mu[w], scale, jacobian ? &d_r : nullptr, reached));
        if (!jacobian) continue;
        for (std::size_t j = 0; j < free; ++j) {
            double g = 0.0;
            for (std::size_t k = 0; k < layers; ++k) g += d_r[k] * d_effective[j][w][k];
            (*jacobian)[w][j] = g;
        }
    }
    return out;
}

SpectrumFit SpectrumFitter::fit(const std::string& name, const std::vector<double>& measured_all) const {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t p = keys_.size(), n = used_.size();
    std::vector<double> measured;
    for (const auto i : used_) measured.push_back(measured_all.at(i));
    const double weight_sum = std::accumulate(weights_.begin(), weights_.end(), 0.0);

    const auto to_value = [&](std::size_t i, double x) {
        const auto [lo, hi] = bounds_[i];
        return log_scale_[i] ? lo * std::pow(hi / lo, x) : lo + x * (hi - lo);
    };
    const auto values_of = [&](const std::vector<double>& x) {
        std::vector<double> v(p);
        for (std::size_t i = 0; i < p; ++i) v[i] = to_value(i, std::clamp(x[i], 0.0, 1.0));
        return v;
    };
    const auto slope = [&](std::size_t i, double x) {  // d value / d x
        const auto [lo, hi] = bounds_[i];
        return log_scale_[i] ? to_value(i, x) * std::log(hi / lo) : hi - lo;
    };
    std::size_t evaluations = 0;
    // Weighted mean squared residual and, when asked, its gradient in the unit box.
    const auto objective_with_gradient = [&](const std::vector<double>& x, std::vector<double>* gradient) {
        ++evaluations;
        std::vector<std::vector<double>> jac;
        const auto r = model(values_of(x), gradient ? &jac : nullptr);
        double s = 0.0;
        if (gradient) gradient->assign(p, 0.0);
        for (std::size_t w = 0; w < n; ++w) {
            const double residual = r[w].value - measured[w];
            s += weights_[w] * residual * residual;
            if (!gradient) continue;
            for (std::size_t i = 0; i < p; ++i) (*gradient)[i] += 2.0 * weights_[w] * residual * jac[w][i] * slope(i, std::clamp(x[i], 0.0, 1.0)) / weight_sum;
        }
        return s / weight_sum;
    };
    const auto objective = [&](const std::vector<double>& x) { return objective_with_gradient(x, nullptr); };

    // Scan: quasi-random points over the unit box, then local searches from the best distinct ones.
    std::vector<std::pair<double, std::vector<double>>> scanned;
    const auto stop_requested = [&] { return settings_.cancel && settings_.cancel->load(); };
    bool stopped = false;
    for (std::size_t j = 0; j < settings_.scan_points; ++j) {
        if (j > 0 && stop_requested()) {
            stopped = true;
            break;
        }
        std::vector<double> x(p);
        for (std::size_t i = 0; i < p; ++i) x[i] = j == 0 ? 0.5 : radical_inverse(j, primes[i % std::size(primes)]);
        scanned.emplace_back(objective(x), std::move(x));
    }
    std::sort(scanned.begin(), scanned.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<double> best_x = scanned.front().second;
    double best = scanned.front().first;
    const std::size_t starts = settings_.starts;
    // A local search checks the stop request at every evaluation (NLopt's forced stop).
    struct Search {
        const decltype(objective_with_gradient)& objective;
        const std::function<bool()> stop_requested;
    } search{objective_with_gradient, stop_requested};
    for (std::size_t s = 0; s < starts && !stopped; ++s) {
        // Bounded quasi-Newton on the analytic gradient of the replayed model (smooth: common random numbers).
        nlopt::opt opt(nlopt::LD_LBFGS, static_cast<unsigned>(p));
        opt.set_lower_bounds(std::vector<double>(p, 0.0));
        opt.set_upper_bounds(std::vector<double>(p, 1.0));
        opt.set_xtol_abs(1e-4);
        opt.set_ftol_rel(1e-7);
        opt.set_maxeval(300);
        opt.set_min_objective(
            [](const std::vector<double>& x, std::vector<double>& grad, void* data) {
                const auto& search = *static_cast<const Search*>(data);
                if (search.stop_requested()) throw nlopt::forced_stop();
                return search.objective(x, grad.empty() ? nullptr : &grad);
            },
            const_cast<void*>(static_cast<const void*>(&search)));
        auto x = scanned[s].second;
        double value = scanned[s].first;
        try {
            opt.optimize(x, value);
        } catch (const nlopt::forced_stop&) {
            stopped = true;
            break;
        } catch (const nlopt::roundoff_limited&) {
            value = objective(x);
        } catch (const std::runtime_error&) {  // NLopt's generic failure: keep the scan point
            x = scanned[s].second;
            value = scanned[s].first;
        }
        if (value < best) {
            best = value;
            best_x = x;
        }
    }

    SpectrumFit fit;
    fit.name = name;
    fit.parameter_keys = keys_;
    fit.parameters = values_of(best_x);
    for (std::size_t i = 0; i < p; ++i) fit.on_bound.push_back(best_x[i] < 1e-3 || best_x[i] > 1.0 - 1e-3);
    std::vector<std::vector<double>> d_model;  // dR_w / dparameter_j at the optimum, from the same pass
    const auto at_best = model(fit.parameters, &d_model);
    fit.wavelength_nm = wavelengths_nm_;
    fit.measured = measured;
    double sum_sq = 0.0, weighted_sq = 0.0;
    for (std::size_t w = 0; w < n; ++w) {
        fit.fitted.push_back(at_best[w].value);
        fit.fitted_stderr.push_back(at_best[w].stderr);
        const double r = at_best[w].value - measured[w];
        sum_sq += r * r;
        weighted_sq += weights_[w] * r * r;
    }
    fit.rms = std::sqrt(sum_sq / static_cast<double>(n));
    if (!traces_rays(settings_.engine)) {
        // The quadrature's error is systematic: stated beside the residual it is part of (the spectrum command's check).
        SpectralRequest request;
        request.wavelengths = WavelengthGrid::list(wavelengths_nm_);
        request.incidence_deg = settings_.incidence_deg;
        request.geometry = settings_.geometry;
        const auto checked = settings_.engine == FitEngine::biospec_adding_doubling
                                 ? solve_biospec_adding_doubling_spectrum(stack_at(fit.parameters), request, exact_options(true))
                                 : solve_adding_doubling_spectrum(stack_at(fit.parameters), request, exact_options(true).ad);
        if (checked.stated_error) fit.model_accuracy = checked.stated_error->R;
    }

    // Standard errors (sandwich form): Cov = A^-1 B A^-1, A = J^T W J, B = J^T W diag(s^2 + m_w^2) W J, with J the
    // model's Jacobian at the optimum (the analytic one of the replayed model), s^2 the residual variance per degree
    // of freedom and m_w the model's Monte Carlo standard error at wavelength w.
    Eigen::MatrixXd jacobian(n, p);
    for (std::size_t w = 0; w < n; ++w) {
        for (std::size_t i = 0; i < p; ++i) jacobian(static_cast<Eigen::Index>(w), static_cast<Eigen::Index>(i)) = d_model[w][i];
    }
    const double dof = n > p ? static_cast<double>(n - p) : 1.0;
    const double residual_variance = weighted_sq / (weight_sum / static_cast<double>(n)) / dof;
    Eigen::VectorXd w_vec(n), noise(n);
    for (std::size_t w = 0; w < n; ++w) {
        w_vec(static_cast<Eigen::Index>(w)) = weights_[w];
        noise(static_cast<Eigen::Index>(w)) = residual_variance + at_best[w].stderr * at_best[w].stderr;
    }
    const Eigen::MatrixXd wj = w_vec.asDiagonal() * jacobian;
    const Eigen::MatrixXd a = jacobian.transpose() * wj;
    const Eigen::MatrixXd b = wj.transpose() * noise.asDiagonal() * wj;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
    if (lu.isInvertible()) {
        const Eigen::MatrixXd a_inv = lu.inverse();
        const Eigen::MatrixXd cov = a_inv * b * a_inv;
        for (std::size_t i = 0; i < p; ++i) {
            const double v = cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
            fit.parameter_stderr.push_back(std::isfinite(v) && v >= 0.0 ? std::sqrt(v) : infinity);
        }
    } else {
        fit.parameter_stderr.assign(p, infinity);
    }

    const TristimulusWeights tristimulus(fit.wavelength_nm, settings_.illuminant, settings_.observer, OutOfRangePolicy::hold);
    fit.measured_lab = xyz_to_lab(tristimulus.integrate(fit.measured), tristimulus.white());
    fit.fitted_lab = xyz_to_lab(tristimulus.integrate(fit.fitted), tristimulus.white());
    fit.delta_e2000 = ciede2000(fit.measured_lab, fit.fitted_lab);
    fit.evaluations = evaluations;
    fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fit.complete = !stopped;
    return fit;
}

std::vector<std::optional<SpectrumFit>> SpectrumFitter::fit_all(const std::vector<std::string>& names,
                                                                const std::vector<std::vector<double>>& measured,
                                                                const std::function<void(std::size_t, std::size_t)>& on_fitted) const {
    std::vector<std::optional<SpectrumFit>> slots(measured.size());
    std::size_t done = 0;
    std::mutex progress_lock;
    tbb::parallel_for(std::size_t{0}, measured.size(), [&](std::size_t i) {
        if (settings_.cancel && settings_.cancel->load()) return;
        auto one = fit(names[i], measured[i]);
        if (!one.complete) return;  // cut short by a stop: not a fit, never written as one
        slots[i] = std::move(one);
        const std::lock_guard lock(progress_lock);
        if (on_fitted) on_fitted(++done, measured.size());
    });
    return slots;
}

}  // namespace skinspec
