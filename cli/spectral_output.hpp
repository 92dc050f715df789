#pragma once
// Renderings of spectral results shared by every solver's command: the JSON schema of
// docs/RESULTS_SCHEMA.md, CSV with the same columns and units in the header, and readable tables.
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/color_output.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec::cli {

// Solvers' results, each with the colour of its reflectance (when the grid spans 400-700 nm) and its share of the
// solving time, held as columns: a sweep's results are solved into `results` in place (its 12,288 results moved
// into result-and-colour pairs were a fifth of its time, most of it fresh memory).
struct ReportedSpectrum {
    const SpectralResult& result;
    const ColorSummary* color;  // null: no colour
    double seconds;
};
struct ReportedSpectra {
    std::vector<SpectralResult> results;
    std::vector<std::shared_ptr<const ColorSummary>> colors;  // null: no colour
    std::vector<double> seconds;
    std::size_t size() const { return results.size(); }
    bool empty() const { return results.empty(); }
    ReportedSpectrum operator[](std::size_t i) const { return {results[i], colors[i].get(), seconds[i]}; }
    ReportedSpectrum front() const { return (*this)[0]; }
};

// Colour of the total reflectance, held outside the computed wavelengths, with its uncertainty from R's standard
// errors and the solver's stated error; nullopt unless the wavelengths have a colour (has_color_span).
std::optional<ColorSummary> reflectance_color(const SpectralResult& result, IlluminantKind illuminant, ObserverKind observer);

nlohmann::ordered_json to_json(const ReportedSpectra& spectra);
void write_csv(std::ostream& out, const ReportedSpectra& spectra);
std::string to_table(const ReportedSpectra& spectra);
// A sweep (--vary): one line per result with its field values, colour, worst standard error and rays.
void write_sweep_table(std::ostream& out, const ReportedSpectra& spectra);

// R (solid) and T (dashed, when computed) of every material with +-2 standard-error bands, drawn in the
// material's simulated sRGB colour, as PNG or SVG.
void write_plot(const std::string& file, const ReportedSpectra& spectra);

// One line on standard error per kind of warning (the full list goes to the JSON output), and the results' stated
// model error when it is above these (then diffusion's trust findings are left to the JSON).
inline constexpr double stated_color_error_worth_a_warning = 1.0;  // CIEDE2000
inline constexpr double stated_R_error_worth_a_warning = 0.01;     // without a colour
void print_warning_summary(const std::string& subject, const std::vector<ResultWarning>& warnings,
                           const std::vector<const SpectralResult*>& results = {});
// The same for results: their warnings together (a sweep's members), read in place.
void print_warning_summary(const std::string& subject, const std::vector<const SpectralResult*>& results);

}  // namespace skinspec::cli
