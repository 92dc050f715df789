#include "spectral/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <plplot/plstream.h>

#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

int channel(double c) { return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); }

// Unicode glyphs (DejaVu has them) for PlotCurve::marker 1-8.
const char* marker_glyph(int marker) {
    static const char* glyphs[] = {"", "\u25CF", "\u25A0", "\u25B2", "\u25C6", "\u25CB", "\u25A1", "\u25B3", "\u25C7"};
    return glyphs[std::clamp(marker, 0, 8)];
}

// Index runs [first, last) of the points a curve draws: all of them, or on a log y axis the runs above the floor.
std::vector<std::pair<std::size_t, std::size_t>> visible_runs(const std::vector<double>& y, bool log_y, double floor) {
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= y.size(); ++i) {
        const bool visible = i < y.size() && (!log_y || (y[i] > 0.0 && std::log10(y[i]) >= floor));
        if (visible) continue;
        if (i > start) runs.emplace_back(start, i);
        start = i + 1;
    }
    return runs;
}

}  // namespace

void write_line_plot(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                     const std::string& y_label, const std::vector<PlotCurve>& curves, PlotStyle style) {
    const bool log_x = style.log_x, log_y = style.log_y;
    const auto ext = file.extension().string();
    if (ext != ".png" && ext != ".svg") throw InputError(file.string() + ": plot extension '" + ext + "' is not supported (allowed: .png, .svg)");
    if (curves.empty()) throw InputError(file.string() + ": nothing to plot");
    const auto band = [](const PlotCurve& c, std::size_t i) { return c.stderr.empty() ? 0.0 : 2.0 * c.stderr[i]; };
    double x_min = 1e300, x_max = -1e300, y_max = 0.0, y_low = 0.0;
    for (const auto& c : curves) {
        for (std::size_t i = 0; i < c.value.size(); ++i) {
            if (log_x && !(c.x[i] > 0.0)) continue;
            x_min = std::min(x_min, log_x ? std::log10(c.x[i]) : c.x[i]);
            x_max = std::max(x_max, log_x ? std::log10(c.x[i]) : c.x[i]);
            y_max = std::max(y_max, c.value[i] + band(c, i));
            y_low = std::min(y_low, c.value[i] - band(c, i));
        }
    }
    if (log_x && x_min > x_max) throw InputError(file.string() + ": no point with a positive x on the logarithmic x axis");
    if (log_x) {
        x_min = std::floor(x_min);
        x_max = std::ceil(x_max);
    }
    if (x_max <= x_min) x_max = x_min + 1.0;
    double y_min = 0.0;
    if (log_y) {
        // Plot log10 of the values on a log axis; the floor is eight decades below the top.
        y_max = std::ceil(std::log10(std::max(y_max, 1e-300)));
        double smallest = y_max;
        for (const auto& c : curves) {
            for (const double v : c.value) {
                if (v > 0.0) smallest = std::min(smallest, std::floor(std::log10(v)));
            }
        }
        y_min = std::max(smallest, y_max - 8.0);
        if (y_min >= y_max) y_min = y_max - 1.0;
    } else if (y_low < 0.0) {
        // Values of both signs (residuals): a symmetric axis, in steps of 0.01 below 0.1.
        const double m = std::max(y_max, -y_low) * 1.05;
        y_max = m < 0.1 ? std::ceil(m * 100.0) / 100.0 : m <= 1.0 ? std::ceil(m * 10.0) / 10.0 : m;
        y_min = -y_max;
    } else {
        y_max = y_max <= 1.0 ? std::max(0.05, std::ceil(y_max * 10.0 * 1.05) / 10.0) : y_max * 1.05;
    }
    const auto x_of = [&](double x) { return log_x ? std::log10(x) : x; };
    const auto y_of = [&](double v) { return log_y ? std::clamp(v > 0.0 ? std::log10(v) : y_min, y_min, y_max) : std::clamp(v, y_min, y_max); };

    write_atomically(file, [&](const std::filesystem::path& temporary) {
        auto pls = std::make_unique<plstream>();
        pls->sdev(ext == ".png" ? "pngcairo" : "svgcairo");
        pls->sfnam(temporary.string().c_str());
        pls->spage(0.0, 0.0, 1400, 800, 0, 0);
        pls->scmap0n(std::max<PLINT>(16, 2 + 2 * static_cast<PLINT>(curves.size())));  // a band and a line colour per curve
        pls->scol0a(0, 255, 255, 255, 1.0);  // background
        pls->scol0a(1, 0, 0, 0, 1.0);        // axes and text
        pls->init();
        pls->col0(1);
        // Axes on the left, the legend to their right: margins wide enough for the tick and axis labels.
        pls->adv(0);
        pls->vpor(0.09, 0.6, 0.12, 0.9);
        pls->wind(x_min, x_max, y_min, y_max);
        pls->box(log_x ? "bcnstlg" : "bcnstg", 0.0, 0, log_y ? "bcnstvlg" : "bcnstvg", 0.0, 0);
        pls->lab(x_label.c_str(), y_label.c_str(), title.c_str());

        std::vector<PLINT> opts, colours, styles;
        std::vector<PLFLT> widths;
        std::vector<const char*> labels, symbols;
        for (std::size_t k = 0; k < curves.size(); ++k) {
            const auto& c = curves[k];
            const int band_colour = 2 + 2 * static_cast<int>(k);
            const int line_colour = band_colour + 1;
            // Very light skin colours would vanish on white: darken the line, keep the hue.
            const double luma = 0.2126 * c.colour[0] + 0.7152 * c.colour[1] + 0.0722 * c.colour[2];
            const double scale = luma > 0.7 ? 0.7 / luma : 1.0;
            const int r = channel(c.colour[0] * scale), g = channel(c.colour[1] * scale), b = channel(c.colour[2] * scale);
            pls->scol0a(band_colour, r, g, b, 0.25);
            pls->scol0a(line_colour, r, g, b, 1.0);
            std::vector<double> xs, ys, ss;
            for (std::size_t i = 0; i < c.value.size(); ++i) {
                if (log_x && !(c.x[i] > 0.0)) continue;
                xs.push_back(c.x[i]);
                ys.push_back(c.value[i]);
                ss.push_back(c.stderr.empty() ? 0.0 : c.stderr[i]);
            }
            for (const auto& [first, last] : visible_runs(ys, log_y, y_min)) {
                std::vector<PLFLT> bx, by, lx, ly;
                for (std::size_t i = first; i < last; ++i) {
                    bx.push_back(x_of(xs[i]));
                    by.push_back(y_of(ys[i] + 2.0 * ss[i]));
                    lx.push_back(x_of(xs[i]));
                    ly.push_back(y_of(ys[i]));
                }
                for (std::size_t i = last; i-- > first;) {
                    bx.push_back(x_of(xs[i]));
                    by.push_back(y_of(ys[i] - 2.0 * ss[i]));
                }
                pls->col0(band_colour);
                if (bx.size() >= 3) pls->fill(static_cast<PLINT>(bx.size()), bx.data(), by.data());
                pls->col0(line_colour);
                pls->lsty(c.dashed ? 2 : 1);
                pls->width(2.0);
                pls->line(static_cast<PLINT>(lx.size()), lx.data(), ly.data());
                if (c.marker > 0) {
                    pls->schr(0.0, 0.55);
                    pls->string(static_cast<PLINT>(lx.size()), lx.data(), ly.data(), marker_glyph(c.marker));
                    pls->schr(0.0, 1.0);
                }
            }
            opts.push_back(PL_LEGEND_LINE | (c.marker > 0 ? PL_LEGEND_SYMBOL : 0));
            symbols.push_back(marker_glyph(c.marker));
            colours.push_back(line_colour);
            styles.push_back(c.dashed ? 2 : 1);
            widths.push_back(2.0);
            labels.push_back(c.label.c_str());
        }
        pls->lsty(1);
        pls->col0(1);
        PLFLT legend_width = 0.0, legend_height = 0.0;
        const std::vector<PLINT> text_colours(curves.size(), 1);
        const std::vector<PLFLT> symbol_scales(curves.size(), 0.55);
        const std::vector<PLINT> symbol_numbers(curves.size(), 1);
        pls->legend(&legend_width, &legend_height, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, PL_POSITION_OUTSIDE | PL_POSITION_RIGHT,
                    0.05, 0.0, 0.06, 0, 1, 1, 0, 0, static_cast<PLINT>(curves.size()), opts.data(), 1.0,
                    curves.size() > 12 ? 0.55 : 0.7, 1.5, 0.0, text_colours.data(), labels.data(), nullptr, nullptr, nullptr, nullptr,
                    colours.data(), styles.data(), widths.data(), colours.data(), symbol_scales.data(), symbol_numbers.data(),
                    symbols.data());
        pls.reset();  // the destructor finishes and closes the file
        if (!std::filesystem::exists(temporary)) throw InputError(file.string() + ": the plot could not be written");
    });
}

}  // namespace skinspec
