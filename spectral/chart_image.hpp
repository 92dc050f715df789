#pragma once
// Colour-chart images (spectral/image_files.hpp, OpenImageIO): a grid of flat patches. Two renderings of the same patches:
//  - scene-linear OpenEXR in a named working space (half or float), with the OpenEXR `chromaticities`
//    attribute and the colour-space name set, no labels;
//  - display-referred PNG (8-bit) or TIFF (16-bit) through the OpenColorIO display/view transform, with a
//    text label drawn on each patch.
// Both carry the given metadata (model, parameters, seed, version) as string attributes.
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "spectral/color_management.hpp"
#include "spectral/image_files.hpp"

namespace skinspec {

struct ChartLayout {
    std::size_t columns = 1;
    std::size_t rows = 1;
    int patch_px = 112;
    int gap_px = 8;
    int left_px = 0;  // margins for axis labels (display charts)
    int top_px = 0;
};

// Axis labels of a display chart: titles (with units) above the grid, a value per column above it and a
// value per row to its left. Empty: no margins.
struct ChartAxes {
    std::string column_title;
    std::vector<std::string> column_values;
    std::string row_title;
    std::vector<std::string> row_values;
};

// Largest chart written (pixels, margins excluded): 1e8 pixels is 1.2 GB as float RGB in memory.
inline constexpr double max_chart_pixels = 1e8;
// InputError naming the chart's size when it exceeds max_chart_pixels (checked before any work).
void check_chart_size(const ChartLayout& layout);

// Published xy of red, green, blue and white for `space` (data/ocio/chromaticities.toml); InputError for a
// space without RGB primaries.
std::array<float, 8> space_chromaticities(std::string_view space);

// Throws InputError when `file` cannot be written (folder missing or not writable, or an existing file
// without `overwrite`), or its extension is not one of `extensions`. Writes nothing.
void check_output_path(const std::filesystem::path& file, bool overwrite, const std::vector<std::string>& extensions);

// Image files of one picture in one working space: linear OpenEXR (.exr) or display-referred PNG / TIFF through an
// OCIO display and view.
struct ImageOutputs {
    std::vector<std::filesystem::path> files;  // .exr, .png, .tif, .tiff
    std::string space = "ACEScg";              // the linear working space
    bool half = false;                         // EXR in half float
    std::string display = "sRGB";
    std::string view = "Standard";
    bool overwrite = false;
};
// Every file checked before any work (the space, display and view, extension, folder, existing files unless
// overwrite); returns `outputs` with the space's canonical name.
ImageOutputs check_image_outputs(const ImageOutputs& outputs);

// Packed RGB floats, row-major.
struct LinearImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
};

// read_data_image (spectral/image_files.hpp) gives the stored values of any image, no colour conversion.
// Float data (no colour tagging) as OpenEXR, with the metadata.
void write_data_image(const std::filesystem::path& file, const DataImage& image, const ImageMetadata& metadata);
// Any image OpenImageIO reads, as scene-linear `working_space` RGB: 8/16-bit files are taken as sRGB-encoded,
// float files (EXR) as already in `working_space`; grey images are replicated to RGB.
LinearImage read_linear_image(const std::filesystem::path& file, std::string_view working_space, const ColorManagement& cm);
// The same of an image already read (read_data_image).
LinearImage linear_image(const DataImage& in, std::string_view working_space, const ColorManagement& cm);

// A labelled grid of equally sized panels (linear `working_space`), display-referred through the OCIO
// display/view, row-major, as PNG or TIFF.
void write_image_grid(const std::filesystem::path& file, const std::vector<LinearImage>& panels, std::size_t columns,
                      const std::vector<std::string>& labels, std::string_view working_space, std::string_view display,
                      std::string_view view, const ImageMetadata& metadata, const ColorManagement& cm);

// One scene-linear image in `working_space` as OpenEXR (chromaticities, colour space, metadata).
void write_linear_image(const std::filesystem::path& file, const LinearImage& image, std::string_view working_space, bool half_float,
                        const ImageMetadata& metadata, const ColorManagement& cm);
// One scene-linear image in `working_space`, display-referred through the OCIO display/view, as PNG or TIFF.
void write_display_image(const std::filesystem::path& file, const LinearImage& image, std::string_view working_space, std::string_view display,
                         std::string_view view, const ImageMetadata& metadata, const ColorManagement& cm);
// `patches` are linear RGB in `working_space`, row-major, columns x rows.
void write_linear_chart(const std::filesystem::path& file, const ChartLayout& layout, const std::vector<RGB>& patches,
                        std::string_view working_space, bool half_float, const ImageMetadata& metadata,
                        const ColorManagement& cm);
void write_display_chart(const std::filesystem::path& file, const ChartLayout& layout, const std::vector<RGB>& patches,
                         const std::vector<std::string>& labels, std::string_view working_space, std::string_view display,
                         std::string_view view, const ImageMetadata& metadata, const ColorManagement& cm, const ChartAxes& axes = {});

}  // namespace skinspec
