#pragma once
// Inverse adding-doubling (Prahl et al. 1993, Appl. Opt. 32:559; docs/IAD.md): the optical properties of a slab
// from what integrating spheres measured of it. The unknowns are found where the predicted measurements
// (inverse/iad/integrating_sphere.hpp over adding-doubling) equal the measured ones:
//   M_R and M_T            -> albedo a and optical thickness b, with the setup's g assumed;
//   M_R, M_T and M_U       -> b from the unscattered transmission alone, then a and g;
//   M_R alone (or M_T = 0) -> a of an infinitely thick slab (mu_a and mu_s' are not separable then).
// As in iad's files (its manual, "Three or more measurements"), M_U = 0 is no M_U and M_T = 0 no M_T.
// A start from a grid of forward solutions, then Levenberg-Marquardt within the physical box (0 <= a <= 1,
// 1e-6 <= b <= 1e6, |g| < 1). A measurement no slab can produce is reported with the closest one that can.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inverse/iad/integrating_sphere.hpp"
#include "inverse/iad/slab_measurement.hpp"
#include "inverse/iad/slab_reflectances.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

// Standard uncertainties of the measurements (absolute); all 0: none given, and none propagated.
struct MeasurementUncertainty {
    double m_r = 0.0, m_t = 0.0, m_u = 0.0;
    bool given() const { return m_r > 0.0 || m_t > 0.0 || m_u > 0.0; }
};

struct IadSettings {
    std::size_t channels = 24;  // adding-doubling quadrature (iad's default 8 points is ~5e-4 off in R; docs/IAD.md)
    // The largest |predicted - measured| of a fit; above it the measurement is unreachable. Adding-doubling's own
    // discontinuities (~1e-6 relative, where a layer's doublings change) stay well below it.
    double tolerance = 1e-5;
    const CancelFlag* cancel = nullptr;
};

enum class IadUnknowns { albedo_thickness, albedo_anisotropy, albedo_only };

struct IadResult {
    IadUnknowns unknowns = IadUnknowns::albedo_thickness;
    SlabOptics optics;  // b = +inf stands for an infinitely thick slab (albedo_only)
    // Per mm of the sample (thickness from the setup); unset when b is infinite.
    std::optional<double> mu_a_per_mm, mu_s_per_mm, mu_s_reduced_per_mm;
    // Standard uncertainties propagated from MeasurementUncertainty through the Jacobian at the solution (unset when
    // none were given; +inf where the measurements do not determine the quantity).
    std::optional<double> mu_a_stderr_per_mm, mu_s_reduced_stderr_per_mm, g_stderr, albedo_stderr;
    PredictedMeasurement fitted;
    std::optional<double> fitted_m_u;
    double residual = 0.0;  // the largest |predicted - measured|
    bool reachable = true;
    std::string unreachable;  // why not, with the closest reachable measurement
    std::size_t evaluations = 0;
    bool cancelled = false;
};

// InputError (naming m.source) for a setup outside its ranges or measurements that determine nothing: M_T or M_U
// without M_R, M_U without M_T, a value outside [0, 1], an M_U above what a clear sample between the faces transmits. invert() checks this first; a command checks
// every row before solving any.
void check_measurement(const SlabMeasurement& m);

// Solves rows one after another, keeping the forward grid of each distinct setup (an .rxt file's rows share one)
// and adding-doubling's phase matrices. Not thread-safe: one per thread.
class SlabInverter {
public:
    explicit SlabInverter(IadSettings settings);
    ~SlabInverter();
    SlabInverter(SlabInverter&&) noexcept;
    SlabInverter& operator=(SlabInverter&&) noexcept;
    // check_measurement first. `previous`: the
    // result of a neighbouring row (a spectrum's previous wavelength), tried as the first start.
    IadResult invert(const SlabMeasurement& m, const MeasurementUncertainty& uncertainty, const IadResult* previous = nullptr);
    // The forward model at `optics`: what the spheres would report (and the unscattered transmission).
    PredictedMeasurement predict(const SlabOptics& optics, const SlabSetup& setup);

private:
    struct State;
    std::unique_ptr<State> state_;
};

std::string_view to_string(IadUnknowns unknowns);

// One measurement and what was recovered from it.
struct IadRow {
    SlabMeasurement measurement;
    IadResult result;
};
// The numbers of a row, declared once: the CSV columns, the JSON keys, the terminal table and the Python keys come from
// this table. A value is unset where the row has none (no M_U measured, b infinite, no uncertainties given).
struct IadField {
    std::string_view key;
    std::string_view unit;
    std::function<std::optional<double>(const IadRow&)> value;
    std::string_view doc;
};
const std::vector<IadField>& iad_result_fields();

// Every row solved: the rows fitted (in order) and, for those no slab produces, why (SlabInverter::invert's text).
struct IadRun {
    std::vector<IadRow> rows;
    std::vector<std::string> unreachable;
    std::size_t unfinished = 0;   // rows not solved before settings.cancel
    std::size_t evaluations = 0;  // forward solutions
};
// In parallel runs of consecutive rows, each row starting from the one before it (a spectrum's neighbours are close):
// the runs are fixed, so the results do not depend on the thread count. `progress(done, total)` after each row,
// serialised. check_measurement on every row first.
IadRun invert_rows(const std::vector<SlabMeasurement>& rows, const MeasurementUncertainty& uncertainty, const IadSettings& settings,
                   const std::function<void(std::size_t, std::size_t)>& progress = {});

// The document `skinspec iad --json` prints and skinspec.iad returns (schema skinspec-iad/1): the setup (the header
// of `input` with the options), the settings, every row's iad_result_fields (null where unset) and the unreachable.
nlohmann::ordered_json iad_json(const IadRun& run, const SlabSetup& setup, const std::string& input, const IadSettings& settings,
                                const MeasurementUncertainty& uncertainty, bool partial, double seconds);

}  // namespace skinspec
