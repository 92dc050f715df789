#pragma once
// fit-image's whole computation, called by `skinspec fit-image` and skinspec.fit_image alike (docs/FIT_IMAGE.md):
// the model's table over the two fields (the swatch engine: a registered solver, stoppable, with progress), each node
// as the image's channels (linear RGB in a working space, or band reflectance factors), the per-pixel fit and the
// edits re-rendered.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "appearance/swatch_chart.hpp"
#include "inverse/image_fit/albedo_lut.hpp"
#include "inverse/image_fit/band_sensitivities.hpp"
#include "inverse/image_fit/pixel_fit.hpp"
#include "spectral/image_files.hpp"

namespace skinspec {

struct SkinImageRequest {
    SwatchRequest table;  // material, overrides, the two sweeps (u: columns, v: rows), solver, geometry, colour, cancel
    std::string space;    // an RGB image's linear working space (an OCIO colour space); unused with bands
    std::optional<BandSensitivities> bands;  // a multispectral image's bands
    // The image value of a perfect white diffuser (the albedo's calibration): one for every channel, or one per channel
    // (a white balance).
    std::vector<double> white{1.0};
    PixelFitSettings fit;
    std::vector<FieldEdit> edits;
};

// An image as the fit takes it: the request's channels per pixel, interleaved, in the image's own units.
// What an image states of itself where skinspec wrote it (swatch, swatch --lit, export lut): the geometry its colours
// were computed for (skinspec:geometry) and, for a float image, the linear colour space its values are in (colorspace).
// Unset where the file states nothing (or not a value skinspec knows: InputError names it). fit-image takes them
// unless --geometry / --space are given, so that it fits the image the way it was made (docs/PROFILES.md). `name`
// names the file in an error.
struct StatedImageSettings {
    std::optional<MeasurementGeometry> geometry;
    std::optional<std::string> space;  // canonical OCIO name
};
StatedImageSettings stated_image_settings(const DataImage& image, const std::string& name);

struct SkinImage {
    int width = 0;
    int height = 0;
    std::vector<float> values;
    StatedImageSettings stated;  // what the file says of itself (nothing for an array)
};

struct SkinImageFit {
    std::shared_ptr<const AlbedoLut> lut;  // null when stopped while the table was computed
    ImageFit fit;
    std::optional<EditedImage> edited;  // the image after the edits, in its own units; none when partial or no edit
    ResultSettings table_settings;             // the solver's and model's settings of the table
    std::vector<ResultWarning> warnings;       // the table's findings
    std::size_t table_nodes = 0;
    double worst_delta_e = 0.0;                // the largest colour uncertainty (CIEDE2000) of a node
    bool table_partial = false;                // stopped while the table was computed: nothing was fitted
    double table_seconds = 0.0;
    double seconds = 0.0;
    bool partial() const { return table_partial || fit.partial; }
};

// Checks what the request says that the table does not (the fit settings for its channels, the working space):
// InputError before any work.
void check_skin_image_request(const SkinImageRequest& request);

// An image file as the request's channels: an RGB image read into the working space (8/16-bit files decoded as sRGB,
// float files taken as in the space), a multispectral one as stored, with as many channels as bands (InputError).
SkinImage read_skin_image(const std::filesystem::path& file, const SkinImageRequest& request);

SkinImageFit fit_skin_image(const SkinImageRequest& request, const SkinImage& image);


// The maps as an image: the two fields, their standard uncertainties ("FIELD.stderr"), the RMS residual and the
// status (PixelStatus codes) per pixel.
DataImage skin_image_maps(const SkinImageFit& result);
// What the maps' and the edited image's files carry: the request, the model and the fit's noise.
ImageMetadata skin_image_metadata(const SkinImageFit& result, const SkinImageRequest& request, const std::string& image_name);
// The summary `fit-image --json` prints and skinspec.fit_image returns beside its arrays.
nlohmann::ordered_json skin_image_summary_json(const SkinImageFit& result, const SkinImageRequest& request, const std::string& image_name);

}  // namespace skinspec
