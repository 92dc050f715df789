#pragma once
// Line plots through PLplot (pngcairo / svgcairo devices): one line per curve with a shaded band of
// +-2 standard errors, axis labels with units and a legend. Used for spectra and goniometer curves.
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
    int marker = 0;              // 0: none; 1-8: a distinct symbol at every point (and in the legend)
};

// A linear y axis starts at 0, or is symmetric about 0 when a value (minus its band) is negative. Logarithmic axes: a log y axis spans at most eight decades below the largest value, and a curve is broken
// (not drawn along the floor) where it falls below; a log x axis spans the positive x values (points at
// x <= 0 are left out). The legend always stands beside the axes, so it never hides data.
struct PlotStyle {
    bool log_x = false;
    bool log_y = false;
};

// .png or .svg by extension; InputError otherwise or when the file cannot be written.
void write_line_plot(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                     const std::string& y_label, const std::vector<PlotCurve>& curves, PlotStyle style = {});

}  // namespace skinspec
