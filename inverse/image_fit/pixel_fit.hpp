#pragma once
// Per-pixel inversion of a skin image through an AlbedoLut (docs/FIT_IMAGE.md): the two fields whose modelled
// channel values are closest to the pixel's in least squares, found by a coarse search over the table's nodes and
// Levenberg-Marquardt steps on its bicubic interpolation within the table's bounds; their standard uncertainties
// from the noise through the Jacobian at the solution (linear propagation: sigma^2 (J^T J)^-1); and the pixels the
// model cannot explain flagged (not skin, or skin beyond the table), not forced.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "inverse/image_fit/albedo_lut.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

enum class PixelStatus : std::uint8_t {
    fitted = 0,         // explained by the model within gamut_sigma noise
    outside_gamut = 1,  // the closest model value is further than gamut_sigma noise (hair, eyebrows, background, shadow)
    outside_range = 2,  // the best fit lies on the table's edge: the pixel may need a value beyond it
    invalid = 3,        // a channel negative or not finite, or every channel 0
    not_fitted = 4,     // the run was stopped before this pixel
};
std::string_view to_string(PixelStatus status);

struct PixelFitSettings {
    // Standard deviation of each channel value (the image's units, white = 1); unset: estimated from the fits'
    // residuals (needs more channels than the two unknowns).
    std::optional<double> noise;
    double gamut_sigma = 4.0;  // a residual (RMS per degree of freedom) above this many noise sigmas is outside gamut
    const CancelFlag* cancel = nullptr;
    std::function<void(std::size_t rows_done, std::size_t rows)> on_progress;  // from worker threads, serialised
};

struct PixelFit {
    LutPoint at;            // index coordinates in the table
    double u_value = 0.0;   // the fields' values (the table's u and v sweeps); 0 for invalid and not fitted pixels
    double v_value = 0.0;
    double u_stderr = 0.0;  // standard uncertainties (0 for invalid and not fitted pixels)
    double v_stderr = 0.0;
    double residual = 0.0;  // RMS over the channels of model - pixel (the image's units)
    PixelStatus status = PixelStatus::not_fitted;
};

struct ImageFit {
    int width = 0;
    int height = 0;
    std::vector<PixelFit> pixels;  // row-major
    double noise = 0.0;            // the noise used for the uncertainties and the gamut test
    bool noise_estimated = false;
    bool partial = false;          // stopped: the pixels not reached are not_fitted
    std::size_t count(PixelStatus status) const;
};

// InputError for a noise or gamut_sigma that is not finite and > 0, or no noise given with too few channels (2) to
// estimate it from the residuals.
void check_pixel_fit_settings(const PixelFitSettings& settings, std::size_t channels);

// InputError unless `values` are width x height pixels of `channels` values each (width, height > 0).
void check_image_size(std::size_t values, int width, int height, std::size_t channels);

// Bytes fit_image_pixels and edited_values hold per pixel of `channels` values (for a memory check before the work).
double pixel_fit_bytes_per_pixel(std::size_t channels);

// `values`: width x height pixels, lut.channel_count() interleaved values each (white = 1). InputError as
// check_image_size and check_pixel_fit_settings.
ImageFit fit_image_pixels(const AlbedoLut& lut, const std::vector<float>& values, int width, int height, const PixelFitSettings& settings);

// An edit of a fitted field: FIELD=*S scales it by S, FIELD=V sets it to V.
struct FieldEdit {
    std::string field;
    bool scale = false;
    double amount = 0.0;
};
// "FIELD=*S" or "FIELD=V" for FIELD one of the table's two fields; InputError naming --edit otherwise.
FieldEdit parse_field_edit(std::string_view text, const std::string& u_field, const std::string& v_field);

// The image re-rendered after the edits: each fitted pixel's values times the model's ratio (edited / fitted), so
// that what the model does not explain (pores, freckle edges, noise) is kept; the other pixels unchanged, and so is
// a fitted pixel whose edited fields leave the table (the model was not computed there; it is counted).
struct EditedImage {
    std::vector<float> values;
    std::size_t rendered = 0;      // fitted pixels re-rendered
    std::size_t beyond_table = 0;  // fitted pixels left unchanged: an edited field outside the table's range
};
EditedImage edited_values(const AlbedoLut& lut, const ImageFit& fit, const std::vector<float>& values, const std::vector<FieldEdit>& edits);

}  // namespace skinspec
