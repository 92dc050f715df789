#include "spectral/chart_image.hpp"

#include <algorithm>
#include <cmath>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "spectral/data_paths.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

constexpr float background_linear = 0.18f;  // neutral mid grey between patches
constexpr const char* label_font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

OIIO::ImageSpec chart_spec(const ChartLayout& layout, OIIO::TypeDesc format) {
    const int width = layout.left_px + static_cast<int>(layout.columns) * (layout.patch_px + layout.gap_px) + layout.gap_px;
    const int height = layout.top_px + static_cast<int>(layout.rows) * (layout.patch_px + layout.gap_px) + layout.gap_px;
    return OIIO::ImageSpec(width, height, 3, format);
}

OIIO::ROI patch_roi(const ChartLayout& layout, std::size_t index) {
    const int column = static_cast<int>(index % layout.columns);
    const int row = static_cast<int>(index / layout.columns);
    const int x = layout.left_px + layout.gap_px + column * (layout.patch_px + layout.gap_px);
    const int y = layout.top_px + layout.gap_px + row * (layout.patch_px + layout.gap_px);
    return OIIO::ROI(x, x + layout.patch_px, y, y + layout.patch_px, 0, 1, 0, 3);
}

OIIO::ImageBuf filled_chart(const ChartLayout& layout, const std::vector<RGB>& colours, const float background[3]) {
    OIIO::ImageBuf buf(chart_spec(layout, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::fill(buf, {background[0], background[1], background[2]});
    for (std::size_t i = 0; i < colours.size(); ++i) {
        const float c[3] = {static_cast<float>(colours[i][0]), static_cast<float>(colours[i][1]), static_cast<float>(colours[i][2])};
        OIIO::ImageBufAlgo::fill(buf, {c[0], c[1], c[2]}, patch_roi(layout, i));
    }
    return buf;
}

void set_metadata(OIIO::ImageBuf& buf, const ImageMetadata& metadata) {
    for (const auto& [key, value] : metadata) buf.specmod().attribute(key, value);
}

void write(OIIO::ImageBuf& buf, const std::filesystem::path& file, OIIO::TypeDesc format) {
    buf.set_write_format(format);
    write_atomically(file, [&](const std::filesystem::path& temporary) {
        if (!buf.write(temporary.string())) throw InputError(file.string() + ": cannot be written (" + buf.geterror() + ")");
    });
}

// Draws `label` (lines separated by '\n') at the top-left of `roi`, in black or white for contrast.
void draw_label(OIIO::ImageBuf& buf, const OIIO::ROI& roi, const std::string& label, int font_px, double background_luma) {
    const float ink = background_luma > 0.5 ? 0.0f : 1.0f;
    const float colour[3] = {ink, ink, ink};
    std::size_t line_start = 0;
    for (int line = 0;; ++line) {
        const auto end = label.find('\n', line_start);
        const auto text = label.substr(line_start, end - line_start);
        if (!OIIO::ImageBufAlgo::render_text(buf, roi.xbegin + 4, roi.ybegin + 4 + font_px * (line + 1), text, font_px,
                                             label_font, colour)) {
            throw InputError("cannot draw labels: " + buf.geterror() + " (install fonts-dejavu-core)");
        }
        if (end == std::string::npos) break;
        line_start = end + 1;
    }
}

}  // namespace

std::array<float, 8> space_chromaticities(std::string_view space) {
    static const toml::table table = toml::parse_file(data_file("ocio/chromaticities.toml").string());
    const auto* values = table.get_as<toml::array>(space);
    if (!values || values->size() != 8) {
        std::string allowed;
        for (const auto& [key, node] : table) allowed += (allowed.empty() ? "" : ", ") + std::string(key.str());
        throw InputError("colour space '" + std::string(space) + "' has no RGB primaries for an image (allowed: " + allowed + ")");
    }
    std::array<float, 8> out{};
    for (std::size_t i = 0; i < 8; ++i) out[i] = static_cast<float>(values->get(i)->value<double>().value_or(0.0));
    return out;
}

void check_chart_size(const ChartLayout& layout) {
    const auto spec = chart_spec(layout, OIIO::TypeDesc::FLOAT);
    const double pixels = static_cast<double>(layout.columns) * (layout.patch_px + layout.gap_px) *
                          static_cast<double>(layout.rows) * (layout.patch_px + layout.gap_px);
    if (pixels > max_chart_pixels || spec.width <= 0 || spec.height <= 0) {
        throw InputError(fmt::format("a chart of {} x {} patches at {} px is {:.3g} pixels, more than the {:.3g} an image may have "
                                     "(use a smaller --patch-size or fewer steps)", layout.columns, layout.rows, layout.patch_px, pixels,
                                     max_chart_pixels));
    }
}

void check_output_path(const std::filesystem::path& file, bool overwrite, const std::vector<std::string>& extensions) {
    const auto ext = file.extension().string();
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
        std::string allowed;
        for (const auto& e : extensions) allowed += (allowed.empty() ? "" : ", ") + e;
        throw InputError(file.string() + ": extension '" + ext + "' is not supported (allowed: " + allowed + ")");
    }
    const auto folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(folder)) throw InputError(file.string() + ": folder " + folder.string() + " does not exist");
    if (access(folder.c_str(), W_OK) != 0) throw InputError(file.string() + ": folder " + folder.string() + " is not writable");
    if (std::filesystem::exists(file) && !overwrite) throw InputError(file.string() + ": exists already (use --overwrite to replace it)");
}

// Scene-linear output: chromaticities and colour-space name of `space`, the metadata, half or float.
void write_scene_linear(OIIO::ImageBuf& buf, const std::filesystem::path& file, std::string_view working_space, bool half_float,
                        const ImageMetadata& metadata, const ColorManagement& cm) {
    const std::string space = cm.canonical_space(working_space, "--space");
    const auto chromaticities = space_chromaticities(space);
    buf.specmod().attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities.data());
    buf.specmod().attribute("oiio:ColorSpace", space);
    buf.specmod().attribute("colorspace", space);
    set_metadata(buf, metadata);
    write(buf, file, half_float ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
}

void write_linear_chart(const std::filesystem::path& file, const ChartLayout& layout, const std::vector<RGB>& patches,
                        std::string_view working_space, bool half_float, const ImageMetadata& metadata, const ColorManagement& cm) {
    const float grey[3] = {background_linear, background_linear, background_linear};
    auto buf = filled_chart(layout, patches, grey);
    write_scene_linear(buf, file, working_space, half_float, metadata, cm);
}

void write_linear_image(const std::filesystem::path& file, const LinearImage& image, std::string_view working_space, bool half_float,
                        const ImageMetadata& metadata, const ColorManagement& cm) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT), const_cast<float*>(image.rgb.data()));
    OIIO::ImageBuf copy;
    copy.copy(buf);
    write_scene_linear(copy, file, working_space, half_float, metadata, cm);
}

void write_display_chart(const std::filesystem::path& file, const ChartLayout& layout, const std::vector<RGB>& patches,
                         const std::vector<std::string>& labels, std::string_view working_space, std::string_view display,
                         std::string_view view, const ImageMetadata& metadata, const ColorManagement& cm, const ChartAxes& axes) {
    const std::string space = cm.canonical_space(working_space, "--space");
    std::vector<RGB> encoded;
    for (const auto& p : patches) {
        auto e = cm.display_view(p, space, display, view);
        for (auto& c : e) c = std::clamp(c, 0.0, 1.0);  // display-referred: the display cannot show more
        encoded.push_back(e);
    }
    const auto grey = cm.display_view({background_linear, background_linear, background_linear}, space, display, view);
    const float background[3] = {static_cast<float>(grey[0]), static_cast<float>(grey[1]), static_cast<float>(grey[2])};
    // Margins for the axes: the titles and the column values on top, the row values on the left.
    auto framed = layout;
    const int axis_px = std::max(12, layout.patch_px / 8);
    const auto title_lines = static_cast<int>(!axes.column_title.empty()) + static_cast<int>(!axes.row_title.empty());
    if (title_lines > 0 || !axes.column_values.empty()) framed.top_px = axis_px * (title_lines + (axes.column_values.empty() ? 0 : 1)) + axis_px / 2;
    std::size_t widest = 0;
    for (const auto& v : axes.row_values) widest = std::max(widest, v.size());
    if (widest > 0) framed.left_px = static_cast<int>(std::ceil(0.62 * axis_px * static_cast<double>(widest))) + layout.gap_px;
    auto buf = filled_chart(framed, encoded, background);
    const double background_luma = 0.2126 * background[0] + 0.7152 * background[1] + 0.0722 * background[2];
    std::string titles;
    if (!axes.column_title.empty()) titles += "columns: " + axes.column_title;
    if (!axes.row_title.empty()) titles += (titles.empty() ? "" : "\n") + std::string("rows: ") + axes.row_title;
    if (!titles.empty()) draw_label(buf, OIIO::ROI(0, buf.spec().width, 0, framed.top_px), titles, axis_px, background_luma);
    for (std::size_t c = 0; c < axes.column_values.size() && c < layout.columns; ++c) {
        const auto roi = patch_roi(framed, c);
        draw_label(buf, OIIO::ROI(roi.xbegin - 4, roi.xend, framed.top_px - axis_px - axis_px / 3, framed.top_px), axes.column_values[c],
                   axis_px, background_luma);
    }
    for (std::size_t r = 0; r < axes.row_values.size() && r < layout.rows; ++r) {
        const auto roi = patch_roi(framed, r * layout.columns);
        draw_label(buf, OIIO::ROI(0, framed.left_px, roi.ybegin + layout.patch_px / 2 - axis_px, roi.yend), axes.row_values[r], axis_px,
                   background_luma);
    }
    const int font_px = std::max(9, layout.patch_px / 9);
    for (std::size_t i = 0; i < labels.size() && i < encoded.size(); ++i) {
        const double luma = 0.2126 * encoded[i][0] + 0.7152 * encoded[i][1] + 0.0722 * encoded[i][2];
        draw_label(buf, patch_roi(framed, i), labels[i], font_px, luma);
    }
    buf.specmod().attribute("oiio:ColorSpace", std::string(display));
    set_metadata(buf, metadata);
    const bool png = file.extension() == ".png";
    write(buf, file, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
}

DataImage read_data_image(const std::filesystem::path& file) {
    if (!std::filesystem::is_regular_file(file)) throw InputError(file.string() + ": image not found");
    // ImageInput, not ImageBuf: an ImageBuf reads through OIIO's shared image cache, which keeps the first spec it
    // saw for a file name; a file rewritten with another size under the same name then overflowed the pixel
    // buffer (found by fuzz_fit_images, docs/STABILITY.md).
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) throw InputError(file.string() + ": cannot be read as an image (" + OIIO::geterror() + ")");
    const auto spec = in->spec();
    if (spec.width < 2 || spec.height < 2 || spec.nchannels < 1) throw InputError(file.string() + ": image smaller than 2 x 2 pixels");
    DataImage out{spec.width, spec.height, spec.nchannels, std::vector<float>(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels),
                  spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF, spec.channelnames};
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.values.data())) {
        throw InputError(file.string() + ": cannot be read as an image (" + in->geterror() + ")");
    }
    return out;
}

void write_data_image(const std::filesystem::path& file, const DataImage& image, const ImageMetadata& metadata) {
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    if (!image.channel_names.empty()) spec.channelnames = image.channel_names;
    OIIO::ImageBuf buf(spec);
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.values.data());
    set_metadata(buf, metadata);
    write(buf, file, OIIO::TypeDesc::FLOAT);
}

LinearImage read_linear_image(const std::filesystem::path& file, std::string_view working_space, const ColorManagement& cm) {
    const auto in = read_data_image(file);
    LinearImage out{in.width, in.height, std::vector<float>(static_cast<std::size_t>(in.width) * in.height * 3)};
    for (std::size_t p = 0; p < static_cast<std::size_t>(in.width) * in.height; ++p) {
        for (int c = 0; c < 3; ++c) out.rgb[p * 3 + c] = in.values[p * in.channels + std::min(c, in.channels - 1)];
    }
    if (!in.floating_point) cm.convert_pixels(out.rgb, "sRGB", working_space);
    return out;
}

void write_image_grid(const std::filesystem::path& file, const std::vector<LinearImage>& panels, std::size_t columns,
                      const std::vector<std::string>& labels, std::string_view working_space, std::string_view display,
                      std::string_view view, const ImageMetadata& metadata, const ColorManagement& cm) {
    if (panels.empty()) throw InputError(file.string() + ": no panels");
    const int w = panels.front().width, h = panels.front().height, gap = 8;
    const auto rows = (panels.size() + columns - 1) / columns;
    OIIO::ImageBuf buf(OIIO::ImageSpec(static_cast<int>(columns) * (w + gap) + gap, static_cast<int>(rows) * (h + gap) + gap, 3,
                                       OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::fill(buf, {0.5f, 0.5f, 0.5f});
    for (std::size_t i = 0; i < panels.size(); ++i) {
        auto pixels = panels[i].rgb;
        cm.display_view_pixels(pixels, working_space, display, view);
        const int x0 = gap + static_cast<int>(i % columns) * (w + gap);
        const int y0 = gap + static_cast<int>(i / columns) * (h + gap);
        double luma = 0.0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                float* p = &pixels[(static_cast<std::size_t>(y) * w + x) * 3];
                for (int c = 0; c < 3; ++c) p[c] = std::clamp(p[c], 0.0f, 1.0f);
                buf.setpixel(x0 + x, y0 + y, p, 3);
                if (y < 40 && x < 120) luma += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / (40.0 * 120.0);
            }
        }
        if (i < labels.size()) draw_label(buf, OIIO::ROI(x0, x0 + w, y0, y0 + h), labels[i], 13, luma);
    }
    buf.specmod().attribute("oiio:ColorSpace", std::string(display));
    set_metadata(buf, metadata);
    write(buf, file, file.extension() == ".png" ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
}

}  // namespace skinspec
