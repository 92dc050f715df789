// libskinspec_images.so: image files through OpenImageIO for spectral/image_files.hpp. It uses nothing of
// skinspec but that header's plain types, so it links only OpenImageIO and is loaded on demand.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "spectral/image_files.hpp"

namespace skinspec {
namespace {

OIIO::TypeDesc type_of(PixelFormat format) {
    switch (format) {
        case PixelFormat::uint8: return OIIO::TypeDesc::UINT8;
        case PixelFormat::uint16: return OIIO::TypeDesc::UINT16;
        case PixelFormat::half: return OIIO::TypeDesc::HALF;
        case PixelFormat::float32: return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::FLOAT;
}

OIIO::ImageBuf wrap(DataImage& image) {
    return OIIO::ImageBuf(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT), image.values.data());
}

std::string read(const std::string& file, double max_bytes, DataImage& out) {
    // ImageInput, not ImageBuf: an ImageBuf reads through OIIO's shared image cache, which keeps the first spec it
    // saw for a file name; a file rewritten with another size under the same name then overflowed the pixel
    // buffer (found by fuzz_fit_images, docs/STABILITY.md).
    auto in = OIIO::ImageInput::open(file);
    if (!in) return "cannot be read as an image (" + OIIO::geterror() + ")";
    const auto spec = in->spec();
    if (spec.width < 2 || spec.height < 2 || spec.nchannels < 1) return "image smaller than 2 x 2 pixels";
    // The header's size, before allocating: a small file may declare a huge image.
    const double bytes = static_cast<double>(spec.width) * spec.height * spec.nchannels * sizeof(float);
    if (bytes > max_bytes) {
        return "image of " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels x " + std::to_string(spec.nchannels) +
               " channels needs " + std::to_string(static_cast<long long>(bytes / 1e6)) + " MB as floats, more than the " +
               std::to_string(static_cast<long long>(max_bytes / 1e6)) + " MB available";
    }
    out = DataImage{spec.width, spec.height, spec.nchannels,
                    std::vector<float>(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels),
                    spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF, spec.channelnames, {}};
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.values.data())) {
        return "cannot be read as an image (" + in->geterror() + ")";
    }
    for (const auto& attribute : spec.extra_attribs) {
        if (attribute.type() == OIIO::TypeDesc::STRING) out.metadata.emplace_back(attribute.name().string(), attribute.get_string());
    }
    return {};
}

std::string write(const std::string& file, const DataImage& image, PixelFormat format, const ImageAttributes& attributes) {
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    if (!image.channel_names.empty()) spec.channelnames = image.channel_names;
    if (attributes.chromaticities) spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), attributes.chromaticities->data());
    for (const auto& [key, value] : attributes.strings) spec.attribute(key, value);
    OIIO::ImageBuf buf(spec);
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.values.data());
    buf.set_write_format(type_of(format));
    if (!buf.write(file)) return buf.geterror();
    return {};
}

std::string render_text(DataImage& image, int x, int y, const std::string& text, int font_px, const std::string& font,
                        const std::array<float, 3>& colour) {
    auto buf = wrap(image);
    if (!OIIO::ImageBufAlgo::render_text(buf, x, y, text, font_px, font, colour)) return buf.geterror();
    return {};
}

constexpr ImageModuleFunctions functions{image_module_interface_version, &read, &write, &render_text};

}  // namespace
}  // namespace skinspec

extern "C" __attribute__((visibility("default"))) const skinspec::ImageModuleFunctions* skinspec_image_module() { return &skinspec::functions; }
