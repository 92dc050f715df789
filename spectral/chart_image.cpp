#include "spectral/chart_image.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <unistd.h>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "spectral/data_paths.hpp"
#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/memory_budget.hpp"

namespace skinspec {
namespace {

constexpr float background_linear = 0.18f;  // neutral mid grey between patches
constexpr const char* label_font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct ChartSize {
    int width;
    int height;
};

ChartSize chart_size(const ChartLayout& layout) {
    return {layout.left_px + static_cast<int>(layout.columns) * (layout.patch_px + layout.gap_px) + layout.gap_px,
            layout.top_px + static_cast<int>(layout.rows) * (layout.patch_px + layout.gap_px) + layout.gap_px};
}

PixelRect patch_rect(const ChartLayout& layout, std::size_t index) {
    const int column = static_cast<int>(index % layout.columns);
    const int row = static_cast<int>(index / layout.columns);
    const int x = layout.left_px + layout.gap_px + column * (layout.patch_px + layout.gap_px);
    const int y = layout.top_px + layout.gap_px + row * (layout.patch_px + layout.gap_px);
    return {x, y, x + layout.patch_px, y + layout.patch_px};
}

DataImage rgb_image(int width, int height, const std::array<float, 3>& fill) {
    DataImage image{width, height, 3, std::vector<float>(static_cast<std::size_t>(width) * height * 3), true, {}, {}};
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) std::copy(fill.begin(), fill.end(), &image.values[p * 3]);
    return image;
}

void fill_rect(DataImage& image, const PixelRect& rect, const std::array<float, 3>& colour) {
    for (int y = std::max(0, rect.y0); y < std::min(image.height, rect.y1); ++y) {
        for (int x = std::max(0, rect.x0); x < std::min(image.width, rect.x1); ++x) {
            std::copy(colour.begin(), colour.end(), &image.values[(static_cast<std::size_t>(y) * image.width + x) * 3]);
        }
    }
}

std::array<float, 3> to_float(const RGB& c) { return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])}; }

DataImage filled_chart(const ChartLayout& layout, const std::vector<RGB>& colours, const std::array<float, 3>& background) {
    const auto size = chart_size(layout);
    auto image = rgb_image(size.width, size.height, background);
    for (std::size_t i = 0; i < colours.size(); ++i) fill_rect(image, patch_rect(layout, i), to_float(colours[i]));
    return image;
}

void write(const DataImage& image, const std::filesystem::path& file, PixelFormat format, const ImageAttributes& attributes) {
    write_atomically(file, [&](const std::filesystem::path& temporary) { write_image_file(temporary, image, format, attributes, file); });
}

// `text` with its lines broken at spaces so that each fits `width_px` in type of `font_px` (0.62 em a character,
// DejaVu Sans's average); a word longer than the width is broken where it reaches the edge.
std::string wrapped_to(const std::string& text, int width_px, int font_px) {
    const auto max_chars = static_cast<std::size_t>(std::max(4.0, (width_px - 8) / (0.62 * font_px)));
    std::string out, line;
    const auto flush = [&] {
        out += (out.empty() ? "" : "\n") + line;
        line.clear();
    };
    std::size_t start = 0;
    while (start <= text.size()) {
        const auto end = std::min(text.find('\n', start), text.size());
        std::size_t word_start = start;
        while (word_start < end) {
            const auto word_end = std::min(text.find(' ', word_start), end);
            auto word = text.substr(word_start, word_end - word_start);
            if (!line.empty() && line.size() + 1 + word.size() > max_chars) flush();
            while (word.size() > max_chars) {  // a word wider than the image is broken across lines
                line += word.substr(0, max_chars);
                word.erase(0, max_chars);
                flush();
            }
            line += (line.empty() ? "" : " ") + word;
            word_start = word_end + 1;
        }
        flush();
        start = end + 1;
    }
    return out;
}

// Draws `label` (lines separated by '\n') at the top-left of `rect`, in black or white for contrast.
void draw_label(DataImage& image, const PixelRect& rect, const std::string& label, int font_px, double background_luma) {
    const float ink = background_luma > 0.5 ? 0.0f : 1.0f;
    std::size_t line_start = 0;
    for (int line = 0;; ++line) {
        const auto end = label.find('\n', line_start);
        // Lines below the rectangle are not drawn (OpenImageIO asserts on text outside the image).
        const int baseline = rect.y0 + 4 + font_px * (line + 1);
        if (baseline > std::min(rect.y1, image.height - 1)) break;
        render_text(image, rect.x0 + 4, baseline, label.substr(line_start, end - line_start), font_px, label_font, {ink, ink, ink});
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
    const auto size = chart_size(layout);
    const double pixels = static_cast<double>(layout.columns) * (layout.patch_px + layout.gap_px) *
                          static_cast<double>(layout.rows) * (layout.patch_px + layout.gap_px);
    if (pixels > max_chart_pixels || size.width <= 0 || size.height <= 0) {
        throw InputError(fmt::format("a chart of {} x {} patches at {} px is {:.3g} pixels, more than the {:.3g} an image may have "
                                     "(use a smaller --patch-size or fewer steps)", layout.columns, layout.rows, layout.patch_px, pixels,
                                     max_chart_pixels));
    }
    // ~57 bytes per pixel measured (working float RGB, the encoded copy, labels; 60 x 60 patches at 32 px: +212 MB).
    constexpr double bytes_per_pixel = 64.0;
    check_memory(pixels * bytes_per_pixel, fmt::format("a chart of {} x {} patches at {} px", layout.columns, layout.rows, layout.patch_px),
                 "use a smaller --patch-size or fewer steps");
}

void check_output_path(const std::filesystem::path& file, bool overwrite, const std::vector<std::string>& extensions) {
    const auto ext = file.extension().string();
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
        std::string allowed;
        for (const auto& e : extensions) allowed += (allowed.empty() ? "" : ", ") + e;
        throw InputError(file.string() + ": extension '" + ext + "' is not supported (allowed: " + allowed + ")");
    }
    const auto folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
    if (std::filesystem::exists(folder) && !std::filesystem::is_directory(folder)) throw InputError(file.string() + ": " + folder.string() + " is not a folder");
    if (!std::filesystem::is_directory(folder)) throw InputError(file.string() + ": folder " + folder.string() + " does not exist");
    if (access(folder.c_str(), W_OK) != 0) {
        throw InputError(file.string() + ": folder " + folder.string() + " is not writable (" + std::strerror(errno) + ")");
    }
    // The name and its temporary's (atomic_file.hpp) must fit the folder's file system, checked before any work.
    const long longest = pathconf(folder.c_str(), _PC_NAME_MAX);
    const std::size_t name = file.filename().string().size();
    if (longest > 0 && name + temporary_name_extra > static_cast<std::size_t>(longest)) {
        throw InputError(file.string() + ": the file name is " + std::to_string(name) + " characters, more than this folder takes for an output (at most " +
                         std::to_string(static_cast<std::size_t>(longest) - temporary_name_extra) + ")");
    }
    std::error_code error;
    const auto status = std::filesystem::symlink_status(file, error);
    if (std::filesystem::is_directory(status)) throw InputError(file.string() + ": is a folder; an output is written to a file");
    if (std::filesystem::exists(status) && !overwrite) throw InputError(file.string() + ": exists already (use --overwrite to replace it)");
    OutputClaims::claim(file, overwrite);
}

ImageOutputs check_image_outputs(const ImageOutputs& outputs) {
    const auto& cm = ColorManagement::builtin();
    ImageOutputs out = outputs;
    out.space = cm.canonical_space(outputs.space, "--space");
    space_chromaticities(out.space);
    cm.check_display_view(outputs.display, outputs.view);
    for (const auto& file : outputs.files) check_output_path(file, outputs.overwrite, {".exr", ".png", ".tif", ".tiff"});
    if (!outputs.files.empty()) load_image_module_in_background();
    return out;
}

// Scene-linear output: chromaticities and colour-space name of `space`, the metadata, half or float.
void write_scene_linear(const DataImage& image, const std::filesystem::path& file, std::string_view working_space, bool half_float,
                        const ImageMetadata& metadata, const ColorManagement& cm) {
    const std::string space = cm.canonical_space(working_space, "--space");
    ImageAttributes attributes{{{"oiio:ColorSpace", space}, {"colorspace", space}}, space_chromaticities(space)};
    attributes.strings.insert(attributes.strings.end(), metadata.begin(), metadata.end());
    write(image, file, half_float ? PixelFormat::half : PixelFormat::float32, attributes);
}

// Display-referred output: the display's name and the metadata, 8-bit PNG or 16-bit TIFF.
void write_display_referred(const DataImage& image, const std::filesystem::path& file, std::string_view display, const ImageMetadata& metadata) {
    ImageAttributes attributes{{{"oiio:ColorSpace", std::string(display)}}, std::nullopt};
    attributes.strings.insert(attributes.strings.end(), metadata.begin(), metadata.end());
    write(image, file, file.extension() == ".png" ? PixelFormat::uint8 : PixelFormat::uint16, attributes);
}

void write_linear_chart(const std::filesystem::path& file, const ChartLayout& layout, const std::vector<RGB>& patches,
                        std::string_view working_space, bool half_float, const ImageMetadata& metadata, const ColorManagement& cm) {
    write_scene_linear(filled_chart(layout, patches, {background_linear, background_linear, background_linear}), file, working_space, half_float,
                       metadata, cm);
}

void write_linear_image(const std::filesystem::path& file, const LinearImage& image, std::string_view working_space, bool half_float,
                        const ImageMetadata& metadata, const ColorManagement& cm) {
    write_scene_linear(DataImage{image.width, image.height, 3, image.rgb, true, {}, {}}, file, working_space, half_float, metadata, cm);
}

void write_display_image(const std::filesystem::path& file, const LinearImage& image, std::string_view working_space, std::string_view display,
                         std::string_view view, const ImageMetadata& metadata, const ColorManagement& cm) {
    auto pixels = image.rgb;
    cm.display_view_pixels(pixels, cm.canonical_space(working_space, "--space"), display, view);
    for (auto& p : pixels) p = std::clamp(p, 0.0f, 1.0f);  // display-referred: the display cannot show more
    write_display_referred(DataImage{image.width, image.height, 3, std::move(pixels), false, {}, {}}, file, display, metadata);
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
    const auto background = to_float(cm.display_view({background_linear, background_linear, background_linear}, space, display, view));
    // Margins for the axes: the titles and the column values on top, the row values on the left.
    auto framed = layout;
    const int axis_px = std::max(12, layout.patch_px / 8);
    std::size_t widest = 0;
    for (const auto& v : axes.row_values) widest = std::max(widest, v.size());
    if (widest > 0) framed.left_px = static_cast<int>(std::ceil(0.62 * axis_px * static_cast<double>(widest))) + layout.gap_px;
    // The titles, wrapped to the chart's width (one row of a few patches is narrower than a field's description).
    std::string titles;
    if (!axes.column_title.empty()) titles += "columns: " + axes.column_title;
    if (!axes.row_title.empty()) {
        if (!titles.empty()) titles += '\n';
        titles += "rows: " + axes.row_title;
    }
    titles = wrapped_to(titles, chart_size(framed).width, axis_px);
    const auto title_lines = titles.empty() ? 0 : 1 + static_cast<int>(std::count(titles.begin(), titles.end(), '\n'));
    if (title_lines > 0 || !axes.column_values.empty()) framed.top_px = axis_px * (title_lines + (axes.column_values.empty() ? 0 : 1)) + axis_px / 2;
    auto image = filled_chart(framed, encoded, background);
    const double background_luma = 0.2126 * background[0] + 0.7152 * background[1] + 0.0722 * background[2];
    if (!titles.empty()) draw_label(image, PixelRect{0, 0, image.width, framed.top_px}, titles, axis_px, background_luma);
    for (std::size_t c = 0; c < axes.column_values.size() && c < layout.columns; ++c) {
        const auto rect = patch_rect(framed, c);
        draw_label(image, PixelRect{rect.x0 - 4, framed.top_px - axis_px - axis_px / 3, rect.x1, framed.top_px}, axes.column_values[c], axis_px,
                   background_luma);
    }
    for (std::size_t r = 0; r < axes.row_values.size() && r < layout.rows; ++r) {
        const auto rect = patch_rect(framed, r * layout.columns);
        draw_label(image, PixelRect{0, rect.y0 + layout.patch_px / 2 - axis_px, framed.left_px, rect.y1}, axes.row_values[r], axis_px,
                   background_luma);
    }
    const int font_px = std::max(9, layout.patch_px / 9);
    for (std::size_t i = 0; i < labels.size() && i < encoded.size(); ++i) {
        const double luma = 0.2126 * encoded[i][0] + 0.7152 * encoded[i][1] + 0.0722 * encoded[i][2];
        draw_label(image, patch_rect(framed, i), labels[i], font_px, luma);
    }
    write_display_referred(image, file, display, metadata);
}

void write_data_image(const std::filesystem::path& file, const DataImage& image, const ImageMetadata& metadata) {
    write(image, file, PixelFormat::float32, ImageAttributes{metadata, std::nullopt});
}

LinearImage read_linear_image(const std::filesystem::path& file, std::string_view working_space, const ColorManagement& cm) {
    return linear_image(read_data_image(file), working_space, cm);
}

LinearImage linear_image(const DataImage& in, std::string_view working_space, const ColorManagement& cm) {
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
    auto image = rgb_image(static_cast<int>(columns) * (w + gap) + gap, static_cast<int>(rows) * (h + gap) + gap, {0.5f, 0.5f, 0.5f});
    for (std::size_t i = 0; i < panels.size(); ++i) {
        auto pixels = panels[i].rgb;
        cm.display_view_pixels(pixels, working_space, display, view);
        const int x0 = gap + static_cast<int>(i % columns) * (w + gap);
        const int y0 = gap + static_cast<int>(i / columns) * (h + gap);
        double luma = 0.0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const float* p = &pixels[(static_cast<std::size_t>(y) * w + x) * 3];
                float* q = &image.values[(static_cast<std::size_t>(y0 + y) * image.width + x0 + x) * 3];
                for (int c = 0; c < 3; ++c) q[c] = std::clamp(p[c], 0.0f, 1.0f);
                if (y < 40 && x < 120) luma += (0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2]) / (40.0 * 120.0);
            }
        }
        const int font_px = std::clamp(w / 10, 8, 13);  // smaller type on a small image
        if (i < labels.size()) draw_label(image, PixelRect{x0, y0, x0 + w, y0 + h}, wrapped_to(labels[i], w, font_px), font_px, luma);
    }
    write_display_referred(image, file, display, metadata);
}

}  // namespace skinspec
