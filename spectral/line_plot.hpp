#pragma once
// Line plots through PLplot (pngcairo / svgcairo devices): one line per curve with a shaded band of
// +-2 standard errors, axis labels with units and a legend. Used for spectra and goniometer curves.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "spectral/color_management.hpp"

namespace skinspec {

struct PlotCurve {
    std::string label;
    std::vector<double> x;
    std::vector<double> value;
    std::vector<double> stderr;  // band: value +- 2 stderr; empty: no band
    RGB colour;                  // display-encoded sRGB, 0-1
    bool dashed = false;
    int marker = 0;              // 0: none (a curve of one point gets a dot); 1-8: a distinct symbol at every point
};

// A colour (10, the "tab10" palette) and a marker (1-8) for the k-th of several series: no two of the first 80
// share both, so each series reads apart from the others in colour or shape.
struct SeriesStyle {
    RGB colour;
    int marker;
};
SeriesStyle distinct_series_style(std::size_t k);

// A linear y axis starts at 0, or is symmetric about 0 when a value (minus its band) is negative. Logarithmic axes: a log y axis spans at most eight decades below the largest value, and a curve is broken
// (not drawn along the floor) where it falls below; a log x axis spans the positive x values (points at
// x <= 0 are left out). The legend always stands beside the axes, so it never hides data.
struct PlotStyle {
    bool log_x = false;
    bool log_y = false;
};

// One set of axes of a figure; a figure's panels are stacked, share the x axis's label and one legend, and each
// may have a title of its own (small multiples: what tells the panels apart).
struct PlotPanel {
    std::string y_label;
    std::vector<PlotCurve> curves;
    PlotStyle style;
    std::string title;
};

// Where the legend went and how, in pixels of the image (origin top left): what a caller or a test can check.
struct PlotLayout {
    int width_px = 0, height_px = 0;
    double legend_left_px = 0, legend_right_px = 0, legend_top_px = 0, legend_bottom_px = 0;
    int legend_columns = 1;
    std::size_t legend_entries = 0;  // entries listed (every k-th curve when there are more than fit, said in a last entry)
    double legend_text_scale = 0;
    std::vector<std::string> title_lines, x_label_lines, y_label_lines;
};

// Text that fits in `max_chars` per line: split at "; " or else at the space nearest the middle, into at most
// two lines (a longer line is left for the caller's smaller type).
std::vector<std::string> wrap_plot_text(const std::string& text, std::size_t max_chars);

// .png or .svg by extension; InputError otherwise or when the file cannot be written. The legend's columns and
// type size are chosen so that it lies inside the image (checked on the drawn legend; many curves are listed every
// k-th); a title or axis label too long for its place is wrapped.
PlotLayout write_figure(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                        const std::vector<PlotPanel>& panels);
PlotLayout write_line_plot(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                           const std::string& y_label, const std::vector<PlotCurve>& curves, PlotStyle style = {});

}  // namespace skinspec
