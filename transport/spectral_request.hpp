#pragma once
// What a caller asks a spectral solver for, and what it gets back. Shared by every solver: solvers compute
// the requested quantities and nothing more, and say what they did.
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "materials/model_options.hpp"
#include "materials/swept_values.hpp"
#include "spectral/wavelength_grid.hpp"

namespace skinspec {

struct Quantities {
    bool reflectance = true;     // R (total) and R_specular (first-surface reflection)
    bool transmittance = false;  // T
    bool absorptance = false;    // A per layer (and A_surface)
    bool angular = false;        // BRDF / BTDF per polar bin (virtual goniometer)
};

// "R,T,A,brdf" (any of them, comma-separated; "angular" = brdf); InputError naming `what` for anything else.
Quantities parse_quantities(std::string_view text, std::string_view what);

// How R is measured (CIE 15:2004 Sec. 5 geometries; docs/SOLVERS.md "Measurement geometry"):
enum class MeasurementGeometry {
    sci,      // specular component included: all light leaving the top (directional-hemispherical)
    sce,      // specular component excluded: without the first-surface reflection
    zero_45,  // 0/45: normal incidence, reflectance factor of the light leaving at 40-50 deg (annular), relative
              // to a perfect diffuser: R = F(40-50 deg) / (sin^2 50 deg - sin^2 40 deg)
};
std::string_view to_string(MeasurementGeometry geometry);
MeasurementGeometry parse_measurement_geometry(std::string_view text, std::string_view what);
// The exit polar-angle band of 0/45, deg.
inline constexpr double zero_45_band_lo_deg = 40.0;
inline constexpr double zero_45_band_hi_deg = 50.0;

struct Progress {
    std::uint64_t rays_done = 0;
    std::uint64_t rays_expected = 0;  // estimate of the rays the whole request needs (0: unknown)
    std::size_t wavelengths_done = 0;
    std::size_t wavelengths_total = 0;
    std::size_t wavelengths_in_progress = 1;  // units worked on at once beside those done (all of them in a round of the walks)
};

struct Estimate {
    double value = 0.0;
    double stderr = 0.0;
};

// The fewest rays per wavelength a Monte Carlo result may be computed from (a fixed count or a budget). Its standard
// error is estimated from the rays' own spread, and that estimate's relative standard deviation is about
// 1 / sqrt(2 (n - 1)) for n rays (7 % at 100); one ray has no spread at all (it reported R +- 0), and a few rays
// that all miss report 0 +- 0.
inline constexpr std::uint64_t minimum_rays_per_wavelength = 100;
// The most: 2^50 (about 1.1e15), far beyond any run's time, and exact in a double (Python's numbers).
inline constexpr std::uint64_t maximum_rays_per_wavelength = std::uint64_t{1} << 50;

// Cooperative cancellation: solvers check it between batches of rays.
using CancelFlag = std::atomic<bool>;

struct SpectralRequest {
    WavelengthGrid wavelengths = WavelengthGrid::list({550.0});
    Quantities quantities;
    double incidence_deg = 0.0;                  // polar angle of the collimated incident beam, [0, 90)
    MeasurementGeometry geometry = MeasurementGeometry::sci;  // what R is (0/45 needs incidence 0)
    std::optional<double> stderr_target;         // stop a wavelength once R's (and T's) standard error is below
    // Per-wavelength targets recomputed after every round from the current estimates of R (or T) at all
    // wavelengths; replaces stderr_target when set (e.g. a colour tolerance, layers/color_precision.hpp).
    std::function<std::vector<double>(const std::vector<Estimate>& estimates, const std::vector<std::uint64_t>& rays)>
        stderr_targets;
    std::uint64_t max_rays_per_wavelength = 100'000;  // the budget (exact ray count without a target)
    std::uint64_t rays_per_batch = 4096;               // each batch has its own random stream
    std::uint64_t initial_batches = 8;                 // first round with a target
    std::uint64_t seed = 1;
    // Polar bin edges (deg) of the virtual goniometer: default 0, 2.5, 7.5, ..., 87.5, 90 (Baranoski et al. 2005 Sec. 4).
    std::vector<double> angular_bin_edges_deg;
    std::function<void(const Progress&)> on_progress;  // called from worker threads, serialised by the solver
    const CancelFlag* cancel = nullptr;
};

std::vector<double> default_angular_bin_edges_deg();



struct WavelengthResult {
    double wavelength_nm = 0.0;
    Estimate reflectance;           // R in the request's geometry (SCI: total, specular included)
    Estimate specular_reflectance;  // first-surface reflection only
    Estimate transmittance;
    std::vector<Estimate> absorptance_layers;
    Estimate absorptance_surface;  // rays dropped by the skin-fold compatibility behaviour
    std::vector<Estimate> brdf_per_sr;  // per polar bin, Eq. 10 of Baranoski et al. 2005
    std::vector<Estimate> btdf_per_sr;
    std::uint64_t rays = 0;
    std::uint64_t truncated_rays = 0;  // rays that hit the event limit (their weight counted as absorbed)
    bool converged = true;             // stderr target met (always true without a target)
};

// Integers stay integers (seeds, ray counts) in every output.
using SettingValue = std::variant<bool, std::uint64_t, double, std::string>;
using ResultSettings = std::map<std::string, SettingValue>;

// A finding outside a solver's trusted range. Results keep every finding; commands print one summary per
// kind (summarise_warnings) and write the full list to JSON.
struct ResultWarning {
    std::string kind;   // what was found, e.g. "reduced albedo below 0.9: diffusion is not trustworthy"
    std::string subject;  // e.g. "epidermis"
    std::string at;       // e.g. "400 nm" or "band R"
    double value = 0.0;   // the offending value (albedo, mean free paths, ...)
};
// One line per kind, in order of first appearance:
// "KIND: epidermis at 31 of them (400 nm to 700 nm, values 0.62 to 0.89); papillary_dermis at 400 nm (0.87)".
std::vector<std::string> summarise_warnings(const std::vector<const ResultWarning*>& warnings);
std::vector<std::string> summarise_warnings(const std::vector<ResultWarning>& warnings);  // of a list: the same

// InputError "incidence angle A deg is outside [0, 90)" unless 0 <= A < 90 (every solver's one incidence check).
void check_incidence_deg(double incidence_deg);

// Every [model] switch of `model` (materials/material_fields.hpp, model_settings), as result settings.
ResultSettings model_result_settings(const ModelOptions& model);

// What a result was computed from, so that a script can re-run or audit it.
struct Provenance {
    std::string solver;
    // The material as `materials save` writes it, before `overrides` (a sweep's members share their base's text).
    std::shared_ptr<const std::string> material_toml;
    std::vector<std::pair<std::string, std::string>> overrides;  // the request's own --set KEY=VALUE, in order
    SweptValues varied;  // a sweep member's fields and values (--vary), applied after `overrides`
    std::string version;
};
// Every KEY=VALUE a result was computed with, in the order applied: the request's own, then the swept values as
// --vary wrote them (exact, shortest round-trip form).
std::vector<std::pair<std::string, std::string>> all_overrides(const Provenance& provenance);

// A deterministic solver's statement of its own error on a request: `R`, an absolute error of R taken as common to
// every wavelength (colour uncertainties propagate it fully correlated), what it means, and, when the solver
// compared its colour with a reference, that colour difference.
struct StatedError {
    double R = 0.0;
    std::shared_ptr<const std::string> meaning;  // one text shared by the results it describes (a sweep's members)
    std::optional<double> delta_e2000;  // CIEDE2000 (D65, 2 degrees) from the reference named in `meaning`
};

struct SpectralResult {
    std::string model;
    std::string material;
    ResultSettings settings;  // every option of the solve that affects the numbers, seed included
    // The material model's switches (layered materials), one copy shared by every result of the same model (a
    // sweep's 4096 members built the same 20-entry map each: 17 % of a dipole sweep's time).
    std::shared_ptr<const ResultSettings> model_settings;
    std::vector<std::string> layer_names;
    std::vector<double> angular_bin_edges_deg;
    Quantities quantities;
    std::vector<WavelengthResult> wavelengths;  // finished wavelengths, in grid order
    bool partial = false;                       // cut short by cancellation
    bool has_uncertainty = true;                // false for deterministic solvers (diffusion): no stderr, no rays
    std::vector<std::string> bands;             // band names (e.g. R, G, B) when rows are bands, not wavelengths
    std::vector<ResultWarning> warnings;        // inputs outside the solver's trusted range
    std::optional<StatedError> stated_error;    // deterministic solvers (Monte Carlo results carry standard errors)
    Provenance provenance;
};

// settings and model_settings together: what a result records of how it was computed.
ResultSettings all_settings(const SpectralResult& result);

// How a result is named beside others: its material, and a sweep member's swept values in --vary order
// ("biospec-lightly: 0.01, 0.2").
std::string result_label(const SpectralResult& result);

}  // namespace skinspec
