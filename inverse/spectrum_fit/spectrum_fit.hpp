#pragma once
// Fitting measured reflectance spectra with the BioSpec walk (docs/SPECTRUM_FIT.md). The walk's paths are traced
// once per wavelength without absorption (path recording, transport/biospec/biospec_walk.hpp); the model R for
// any values of the free parameters is then a re-weighting of the same paths (common random numbers), a smooth
// function of them, so a bounded optimiser (NLopt BOBYQA, from the best points of a quasi-random scan) can
// minimise the weighted squared residual. Free parameters change absorption only, or the thickness of a layer
// whose paths scale with it (no Rayleigh scattering), so one set of paths serves every spectrum.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "materials/layer_stack.hpp"
#include "materials/material_fields.hpp"
#include "spectral/cie.hpp"
#include "spectral/colorimetry.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "transport/adding_doubling/biospec_adding_doubling.hpp"
#include "transport/biospec/biospec_options.hpp"
#include "transport/biospec/biospec_walk.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

struct FitParameter {
    std::string key;  // a --set key addressing layer fields, e.g. "epidermis.melanosome_fraction", "dermis.oxygen_saturation"
    std::optional<double> lo, hi;  // unset: default_fit_bounds
};

struct WavelengthWeight {
    double from_nm, to_nm, weight;  // residuals at wavelengths in [from, to] count `weight` times
};

// How the fit evaluates the model: re-weighting the BioSpec walk's paths traced once (Monte Carlo, common random
// numbers), or solved exactly at every evaluation, no noise, no traced paths, any free field: the BioSpec model
// (biospec-adding-doubling) or the volumetric description (adding-doubling; e.g. with the layers' own measured
// scattering, model.volumetric_matched_to_biospec = false).
enum class FitEngine { replayed_walk, biospec_adding_doubling, adding_doubling };

// The engines by the name --mode and Python's mode= take, declared once (help, parsing, messages, provenance).
struct FitEngineChoice {
    std::string_view name;
    FitEngine engine;
    std::string_view doc;
};
const std::vector<FitEngineChoice>& fit_engines();
// InputError naming `origin` ("--mode", "mode") and the allowed names.
FitEngine parse_fit_engine(std::string_view name, std::string_view origin);
std::string_view to_string(FitEngine engine);
inline bool traces_rays(FitEngine engine) { return engine == FitEngine::replayed_walk; }

struct SpectrumFitSettings {
    std::vector<FitParameter> free;
    FitEngine engine = FitEngine::replayed_walk;
    std::size_t channels = AdOptions{}.channels;  // exact engines: the quadrature (adding-doubling's default)
    double window_from_nm = 0.0;  // default: every given wavelength
    double window_to_nm = std::numeric_limits<double>::infinity();
    std::vector<WavelengthWeight> weights;
    std::uint64_t rays_per_wavelength = 20'000;
    std::uint64_t seed = 1;
    MeasurementGeometry geometry = MeasurementGeometry::sci;
    double incidence_deg = 0.0;
    BiospecOptions walk;
    static constexpr std::size_t scan_points = 64;  // quasi-random points over the bounds before the local searches
    // Local searches, from the best scan points: 8 found the best of 16 within 5 % on 200 of 200 synthetic skins
    // (docs/SPECTRUM_FIT.md), 4 missed it on 3 (up to 2.2x the RMS).
    std::size_t starts = 8;
    IlluminantKind illuminant = IlluminantKind::d65;
    ObserverKind observer = ObserverKind::cie1931_2deg;
    const CancelFlag* cancel = nullptr;
    std::vector<std::string> wavelength_sources;  // per given wavelength, where it came from ("file.csv:12"), for messages
};

// The default free parameters: melanosome fraction, papillary and reticular blood fraction, oxygen saturation.
std::vector<FitParameter> default_free_parameters();
// Default bounds of a free field given its current value: the field table's fit_bounds (a fraction's physiological
// range, ...), else a factor-of-two band around a positive value, else [0, 1].
std::pair<double, double> default_fit_bounds(const NumberField<TissueLayer>& field, double current);

struct SpectrumFit {
    std::string name;
    std::vector<std::string> parameter_keys;
    std::vector<double> parameters;
    std::vector<double> parameter_stderr;  // +inf where the spectrum does not determine the parameter
    std::vector<bool> on_bound;
    double rms = 0.0;                      // unweighted, over the window
    std::vector<double> wavelength_nm;
    std::vector<double> measured;
    std::vector<double> fitted;
    std::vector<double> fitted_stderr;     // Monte Carlo standard error of the model at the optimum
    // adding_doubling: the stated accuracy of the fitted R (adding-doubling's own check at the optimum: twice the
    // largest change with every segment's channels doubled, at the first, middle, last and least absorbed fitted
    // wavelength). A systematic error of the model, not noise; unset for the replayed walk (its noise is fitted_stderr).
    std::optional<double> model_accuracy;
    Lab measured_lab, fitted_lab;
    double delta_e2000 = 0.0;
    std::size_t evaluations = 0;
    double seconds = 0.0;
    bool complete = true;  // false when a stop request cut its local searches short (fit_all leaves it out)
};

// Mean residual (fitted - measured) of many fits in the bands that show the model's systematic errors.
struct ResidualBand {
    std::string name;
    double from_nm, to_nm;
    double mean_residual;  // over the fits and the band's wavelengths; NaN-free: 0 with no wavelength inside
    std::size_t samples;
};
std::vector<ResidualBand> residual_bands(const std::vector<SpectrumFit>& fits);

class SpectrumFitter {
public:
    // Traces the paths of `base` at the measured wavelengths inside the window (replayed_walk). InputError for a free
    // field that is not one of a layer's absorption fields or a scalable thickness (replayed_walk; adding_doubling
    // takes any number field of a layer), bounds outside the field's range or with lo >= hi, and wavelengths outside
    // the model's tables.
    SpectrumFitter(const LayerStack& base, const std::vector<double>& wavelength_nm, const SpectrumFitSettings& settings);

    // One spectrum at the fitter's wavelengths (all given ones; those outside the window are left out).
    SpectrumFit fit(const std::string& name, const std::vector<double>& measured) const;
    // Many spectra in parallel, results in their order; once the settings' cancel flag is set no new fit starts
    // (those not fitted are nullopt). `on_fitted(done, total)` after each fit, serialised.
    std::vector<std::optional<SpectrumFit>> fit_all(const std::vector<std::string>& names, const std::vector<std::vector<double>>& measured,
                                                    const std::function<void(std::size_t, std::size_t)>& on_fitted) const;
    // The model at parameter values (in the order of the free keys), per fitted wavelength, with standard errors;
    // with `jacobian`, also dR_w / dparameter_j ([w][j]): from the same pass over the paths (replayed_walk), or by
    // forward differences of the exact model (adding_doubling).
    std::vector<Estimate> model(const std::vector<double>& parameters, std::vector<std::vector<double>>* jacobian = nullptr) const;

    const std::vector<double>& wavelengths_nm() const { return wavelengths_nm_; }
    const std::vector<std::string>& keys() const { return keys_; }
    const std::vector<std::pair<double, double>>& bounds() const { return bounds_; }
    std::uint64_t rays() const;
    bool cancelled() const { return cancelled_; }

private:
    std::vector<Estimate> replayed_model(const std::vector<double>& parameters, std::vector<std::vector<double>>* jacobian) const;
    std::vector<Estimate> exact_model(const std::vector<double>& parameters, std::vector<std::vector<double>>* jacobian) const;
    BiospecAdOptions exact_options(bool accuracy_check) const;
    // Analog absorption at the bounds' floor on the recorded exits (ExitPaths::thin), after they are traced.
    void thin_paths();
    static constexpr std::size_t max_thinning_fields = 8;
    static constexpr std::uint64_t thinning_stream = 0x7468696eULL;  // the thinning's random numbers: not the walk's batches
    LayerStack stack_at(const std::vector<double>& parameters) const;  // the base with the free fields set
    LayerStack base_;
    SpectrumFitSettings settings_;
    std::vector<LayerFieldHandle> handles_;
    std::vector<std::string> keys_;
    std::vector<std::pair<double, double>> bounds_;
    std::vector<bool> log_scale_;
    std::vector<std::size_t> used_;         // indices of the given wavelengths inside the window
    std::vector<double> wavelengths_nm_;    // the fitted wavelengths
    std::vector<double> weights_;
    std::vector<ExitPaths> paths_;
    bool cancelled_ = false;
};

}  // namespace skinspec
