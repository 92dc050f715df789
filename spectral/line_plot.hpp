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
    std::vector<double> stderr;  // band: value +- 2 stderr
    RGB colour;                  // display-encoded sRGB, 0-1
    bool dashed = false;
};

// Logarithmic axes: a log y axis spans at most eight decades below the largest value (smaller values sit on
// the floor); a log x axis spans the positive x values (points at x <= 0 are left out). Many curves: the
// legend goes to the right of the plot instead of inside it (a wider page).
struct PlotStyle {
    bool log_x = false;
    bool log_y = false;
    bool legend_outside = false;
};

// .png or .svg by extension; InputError otherwise or when the file cannot be written.
void write_line_plot(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                     const std::string& y_label, const std::vector<PlotCurve>& curves, PlotStyle style = {});

}  // namespace skinspec
