#pragma once
// Image files (any format OpenImageIO reads or writes) as plain float buffers. OpenImageIO and the ~260 shared
// libraries it brings (codecs, OpenCV, FFmpeg, DICOM) live in a module, libskinspec_images.so (images/), loaded on
// the first image read or written: a command that touches no image does not pay their start-up time or memory.
#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace skinspec {

// The image module is missing, broken or from another build: an installation fault, not bad input.
class ImageModuleError : public std::runtime_error {
public:
    explicit ImageModuleError(const std::string& message) : std::runtime_error(message) {}
};

using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// Float pixels, row-major, channels interleaved; 8/16-bit integer files read as [0, 1].
struct DataImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> values;
    bool floating_point = false;  // read from a half or float file
    std::vector<std::string> channel_names;
    ImageMetadata metadata;  // read: the file's string attributes (e.g. skinspec:geometry, colorspace); not written
};

// How pixels are stored in the file written.
enum class PixelFormat { uint8, uint16, half, float32 };

struct ImageAttributes {
    ImageMetadata strings;                              // string attributes (metadata, colour-space names)
    std::optional<std::array<float, 8>> chromaticities;  // OpenEXR chromaticities: xy of R, G, B, white
};

// Rectangle [x0, x1) x [y0, y1) of pixels.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Starts loading the image module on a thread of its own (once; later calls do nothing): a command that will write an
// image calls it once its outputs are checked, so that the ~0.3-0.5 s of loading overlaps its work instead of
// following it, or following a stop request (a stopped swatch took 0.5 s to write its partial chart, 1.2 s on a
// loaded machine, where 1 s is allowed). Its failure is reported where the module is first used, as before.
void load_image_module_in_background();

// The stored values of any image OpenImageIO reads, as floats, no colour conversion (irradiance maps, masks);
// InputError when missing, unreadable, smaller than 2 x 2 pixels or larger than the memory available (its header says
// how large, so the refusal comes before the pixels are allocated).
DataImage read_data_image(const std::filesystem::path& file);
// Writes `image` to `file` as it is: the caller makes the write atomic (spectral/atomic_file.hpp). The format is
// chosen by `file`'s extension; `reported_name` is the name errors give.
void write_image_file(const std::filesystem::path& file, const DataImage& image, PixelFormat format, const ImageAttributes& attributes,
                      const std::filesystem::path& reported_name);
// Draws `text` with its baseline at (x, y) in `font` (a TrueType file) at `font_px`, in `colour` (RGB images).
void render_text(DataImage& image, int x, int y, const std::string& text, int font_px, const std::string& font, const std::array<float, 3>& colour);

// The functions the module exports (one C symbol, skinspec_image_module, returns them). Errors are returned as
// text (empty: none), so that no exception crosses the module boundary.
struct ImageModuleFunctions {
    int interface_version;
    // Refuses (as text) an image whose float pixels would take more than `max_bytes`, before allocating them.
    std::string (*read)(const std::string& file, double max_bytes, DataImage& out);
    std::string (*write)(const std::string& file, const DataImage& image, PixelFormat format, const ImageAttributes& attributes);
    std::string (*render_text)(DataImage& image, int x, int y, const std::string& text, int font_px, const std::string& font,
                               const std::array<float, 3>& colour);
};
inline constexpr int image_module_interface_version = 3;

}  // namespace skinspec
