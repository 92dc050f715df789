#include "spectral/line_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>
#include <plplot/plstream.h>

#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

constexpr int page_width_px = 1400;
constexpr int single_panel_px = 560;  // a panel's height alone; 400 among two or three, 300 among more
constexpr double title_px = 110, x_label_px = 110, panel_gap_px = 60, edge_px = 8;

int channel(double c) { return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); }

// Unicode glyphs (DejaVu has them) for PlotCurve::marker 1-8.
const char* marker_glyph(int marker) {
    static const char* glyphs[] = {"", "\u25CF", "\u25A0", "\u25B2", "\u25C6", "\u25CB", "\u25A1", "\u25B3", "\u25C7"};
    return glyphs[std::clamp(marker, 0, 8)];
}

// A curve of one point has no line to show it: it gets a dot.
int drawn_marker(const PlotCurve& c) { return c.marker > 0 ? c.marker : c.value.size() == 1 ? 1 : 0; }

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

// The world window of a panel: x and y ranges in plotted units (log10 on a log axis).
struct Window {
    double x_min, x_max, y_min, y_max;
};

Window panel_window(const std::filesystem::path& file, const PlotPanel& panel) {
    const bool log_x = panel.style.log_x, log_y = panel.style.log_y;
    const auto band = [](const PlotCurve& c, std::size_t i) { return c.stderr.empty() ? 0.0 : 2.0 * c.stderr[i]; };
    double x_min = 1e300, x_max = -1e300, y_max = 0.0, y_low = 0.0;
    for (const auto& c : panel.curves) {
        for (std::size_t i = 0; i < c.value.size(); ++i) {
            if (log_x && !(c.x[i] > 0.0)) continue;
            x_min = std::min(x_min, log_x ? std::log10(c.x[i]) : c.x[i]);
            x_max = std::max(x_max, log_x ? std::log10(c.x[i]) : c.x[i]);
            y_max = std::max(y_max, c.value[i] + band(c, i));
            y_low = std::min(y_low, c.value[i] - band(c, i));
        }
    }
    if (x_min > x_max) throw InputError(file.string() + ": no point with a positive x on the logarithmic x axis");
    if (log_x) {
        x_min = std::floor(x_min);
        x_max = std::ceil(x_max);
    }
    if (x_max <= x_min) {
        // One x (a single wavelength): a window around it, so the points stand inside the axes.
        const double half = std::max(1.0, 0.05 * std::abs(x_min));
        x_min -= half;
        x_max += half;
    }
    double y_min = 0.0;
    if (log_y) {
        // Plot log10 of the values on a log axis; the floor is eight decades below the top.
        y_max = std::ceil(std::log10(std::max(y_max, 1e-300)));
        double smallest = y_max;
        for (const auto& c : panel.curves) {
            for (const double v : c.value) {
                if (v > 0.0) smallest = std::min(smallest, std::floor(std::log10(0.8 * v)));  // a value off the floor
            }
        }
        y_min = std::max(smallest, y_max - 8.0);
        if (y_min >= y_max) y_min = y_max - 1.0;
    } else if (y_low < 0.0) {
        // Values of both signs (residuals): a symmetric axis, in steps of 0.01 below 0.1.
        const double m = std::max(y_max, -y_low) * 1.05;
        y_max = m < 0.1 ? std::ceil(m * 100.0) / 100.0 : m <= 1.0 ? std::ceil(m * 10.0) / 10.0 : m;
        if (y_max <= 0.0) y_max = 0.01;
        y_min = -y_max;
    } else {
        y_max = y_max <= 1.0 ? std::max(0.05, std::ceil(y_max * 10.0 * 1.05) / 10.0) : y_max * 1.05;
    }
    return {x_min, x_max, y_min, y_max};
}

// A legend's arrangement: the axes' right edge (fraction of the page), columns, type size, every k-th entry.
struct LegendChoice {
    double axes_right;
    int columns;
    double text_scale;
};

constexpr std::array<LegendChoice, 10> legend_choices{{{0.62, 1, 0.7},
                                                       {0.62, 1, 0.6},
                                                       {0.58, 1, 0.5},
                                                       {0.5, 2, 0.6},
                                                       {0.5, 2, 0.5},
                                                       {0.42, 3, 0.5},
                                                       {0.42, 3, 0.45},
                                                       {0.36, 4, 0.45},
                                                       {0.36, 4, 0.4},
                                                       {0.3, 5, 0.4}}};

// One legend entry: the first curve of each label (panels share their labels), or a line of text.
struct LegendEntry {
    const PlotCurve* curve;  // null: a note without a sample
    std::string text;
};

std::vector<LegendEntry> legend_entries(const std::vector<PlotPanel>& panels, std::size_t every) {
    std::vector<LegendEntry> all;
    std::unordered_set<std::string> listed;
    for (const auto& panel : panels) {
        for (const auto& c : panel.curves) {
            if (!c.label.empty() && listed.insert(c.label).second) all.push_back({&c, c.label});
        }
    }
    if (every <= 1) return all;
    std::vector<LegendEntry> some;
    for (std::size_t i = 0; i < all.size(); i += every) some.push_back(all[i]);
    if (!all.empty() && (all.size() - 1) % every != 0) some.push_back(all.back());
    some.push_back({nullptr, fmt::format("(1 in {} of {} listed)", every, all.size())});
    return some;
}

// A drawn figure and its legend's measures: the size of the space beside the axes and how much of it the legend took.
struct Rendering {
    PlotLayout layout;
    bool legend_fits;
    double region_width_px, region_height_px;
    double legend_width_fraction, legend_height_fraction;
};

// How the legend is drawn: an arrangement, every k-th entry, labels cut to at most `label_chars` (0: whole).
struct LegendPlan {
    LegendChoice choice;
    std::size_t every = 1;
    std::size_t label_chars = 0;
};

std::size_t utf8_length(const std::string& text) {
    return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// `text` cut to `chars` characters with an ellipsis (UTF-8 aware), or whole when it is short enough or chars is 0.
std::string shortened(const std::string& text, std::size_t chars) {
    if (chars == 0) return text;
    std::size_t count = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if ((static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) continue;
        if (++count == chars) {
            std::size_t end = i + 1;
            while (end < text.size() && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) ++end;
            return end >= text.size() ? text : text.substr(0, i) + "\u2026";
        }
    }
    return text;
}

// The drawn length of `text` in mm at the current type size, estimated: PLplot 5.15 does not export its text
// measure (plstrl). DejaVu Sans averages 0.62 of the type's height per character (measured on drawn labels).
double text_length_mm(plstream& pls, const std::string& text) {
    PLFLT default_height, height;
    pls.gchr(default_height, height);
    return 0.62 * height * static_cast<double>(utf8_length(text));
}

// Draws `text` centred on one side of the current viewport, wrapped to the side's length, in type made smaller
// (down to 0.6) while a line is still too long, and a line that is too long even then shortened with an ellipsis.
// `nearest_disp` places the line nearest the axes, in the full type's heights. Returns the lines drawn.
std::vector<std::string> draw_side_text(plstream& pls, const char* side, double nearest_disp, const std::string& text,
                                        double side_mm, double type) {
    if (text.empty()) return {};
    pls.schr(0.0, type);
    const double length_mm = text_length_mm(pls, text);
    auto lines = length_mm <= side_mm ? std::vector<std::string>{text}
                                      : wrap_plot_text(text, static_cast<std::size_t>(utf8_length(text) * side_mm / length_mm));
    double fit = 1.0;
    for (const auto& line : lines) fit = std::min(fit, side_mm / std::max(1e-9, text_length_mm(pls, line)));
    fit = std::max(0.6, fit);
    pls.schr(0.0, type * fit);
    for (auto& line : lines) {
        const double over = text_length_mm(pls, line) / side_mm;
        if (over > 1.0) line = shortened(line, static_cast<std::size_t>(utf8_length(line) / over));
    }
    // Below the axes the first line is the nearest; above and to the left of them, the farthest.
    const bool below = side[0] == 'b';
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const double disp = nearest_disp / fit + 1.5 * static_cast<double>(below ? i : lines.size() - 1 - i);
        pls.mtex(side, disp, 0.5, 0.5, lines[i].c_str());
    }
    pls.schr(0.0, type);
    return lines;
}

Rendering render(const std::filesystem::path& target, const std::string& device, const std::string& title, const std::string& x_label,
                 const std::vector<PlotPanel>& panels, const std::vector<Window>& windows, const LegendPlan& plan) {
    const auto& choice = plan.choice;
    auto entries = legend_entries(panels, plan.every);
    for (auto& e : entries) e.text = shortened(e.text, plan.label_chars);
    std::size_t n_curves = 0;
    for (const auto& p : panels) n_curves += p.curves.size();
    // Panels with titles of their own get room above each for it.
    const bool titled = std::any_of(panels.begin(), panels.end(), [](const PlotPanel& p) { return !p.title.empty(); });
    const double head_px = title_px + (titled ? 30.0 : 0.0), gap_px = panel_gap_px + (titled ? 30.0 : 0.0);
    const double panel_px = panels.size() == 1 ? single_panel_px : panels.size() <= 3 ? 400.0 : 300.0;
    const int height_px = static_cast<int>(head_px + x_label_px + panel_px * panels.size() + gap_px * (panels.size() - 1));
    const double H = height_px, W = page_width_px;
    Rendering out{};
    out.layout.width_px = page_width_px;
    out.layout.height_px = height_px;
    out.layout.legend_columns = choice.columns;
    out.layout.legend_text_scale = choice.text_scale;
    out.layout.legend_entries = entries.size();

    auto pls = std::make_unique<plstream>();
    pls->sdev(device.c_str());
    pls->sfnam(target.string().c_str());
    pls->spage(0.0, 0.0, page_width_px, height_px, 0, 0);
    pls->scmap0n(std::max<PLINT>(16, 2 + 2 * static_cast<PLINT>(n_curves)));  // a band and a line colour per curve
    pls->scol0a(0, 255, 255, 255, 1.0);  // background
    pls->scol0a(1, 0, 0, 0, 1.0);        // axes and text
    pls->init();
    pls->adv(0);
    // PLplot's type grows with the page's height: the same type on a taller figure of several panels.
    const double type = (title_px + x_label_px + single_panel_px) / H;
    pls->schr(0.0, type);
    PLFLT page_x0, page_x1, page_y0, page_y1;
    pls->gspa(page_x0, page_x1, page_y0, page_y1);
    const double mm_per_px = (page_x1 - page_x0) / W;
    constexpr double axes_left = 0.11;  // room for the tick labels and two lines of a y label

    std::unordered_map<const PlotCurve*, PLINT> line_colours;  // each curve's line colour, for its legend entry
    int colour_index = 2;
    for (std::size_t p = 0; p < panels.size(); ++p) {
        const auto& panel = panels[p];
        const auto& w = windows[p];
        const bool log_x = panel.style.log_x, log_y = panel.style.log_y;
        const double top_px = head_px + static_cast<double>(p) * (panel_px + gap_px);
        const double bottom_px = top_px + panel_px;
        pls->col0(1);
        pls->lsty(1);
        pls->width(1.0);
        pls->vpor(axes_left, choice.axes_right, 1.0 - bottom_px / H, 1.0 - top_px / H);
        pls->wind(w.x_min, w.x_max, w.y_min, w.y_max);
        const bool last = p + 1 == panels.size();
        pls->box(log_x ? (last ? "bcnstlg" : "bcstlg") : (last ? "bcnstg" : "bcstg"), 0.0, 0, log_y ? "bcnstvlg" : "bcfnstvg", 0.0, 0);
        const double axes_width_mm = (choice.axes_right - axes_left) * W * mm_per_px;
        if (!panel.title.empty()) draw_side_text(*pls, "t", 1.0, panel.title, axes_width_mm, 0.8 * type);
        if (p == 0) out.layout.title_lines = draw_side_text(*pls, "t", panel.title.empty() ? 1.6 : 2.6, title, axes_width_mm, type);
        if (last) out.layout.x_label_lines = draw_side_text(*pls, "b", 3.2, x_label, axes_width_mm, type);
        const auto y_lines = draw_side_text(*pls, "l", 4.6, panel.y_label, panel_px * mm_per_px, type);
        if (p == 0) out.layout.y_label_lines = y_lines;

        const auto x_of = [&](double x) { return log_x ? std::log10(x) : x; };
        const auto y_of = [&](double v) {
            return log_y ? std::clamp(v > 0.0 ? std::log10(v) : w.y_min, w.y_min, w.y_max) : std::clamp(v, w.y_min, w.y_max);
        };
        for (const auto& c : panel.curves) {
            const int band_colour = colour_index++;
            const int line_colour = colour_index++;
            // Very light skin colours would vanish on white: darken the line, keep the hue.
            const double luma = 0.2126 * c.colour[0] + 0.7152 * c.colour[1] + 0.0722 * c.colour[2];
            const double scale = luma > 0.7 ? 0.7 / luma : 1.0;
            const int r = channel(c.colour[0] * scale), g = channel(c.colour[1] * scale), b = channel(c.colour[2] * scale);
            pls->scol0a(band_colour, r, g, b, 0.25);
            pls->scol0a(line_colour, r, g, b, 1.0);
            line_colours[&c] = line_colour;
            std::vector<double> xs, ys, ss;
            for (std::size_t i = 0; i < c.value.size(); ++i) {
                if (log_x && !(c.x[i] > 0.0)) continue;
                xs.push_back(c.x[i]);
                ys.push_back(c.value[i]);
                ss.push_back(c.stderr.empty() ? 0.0 : c.stderr[i]);
            }
            for (const auto& [first, end] : visible_runs(ys, log_y, w.y_min)) {
                std::vector<PLFLT> bx, by, lx, ly, low, high;
                for (std::size_t i = first; i < end; ++i) {
                    bx.push_back(x_of(xs[i]));
                    by.push_back(y_of(ys[i] + 2.0 * ss[i]));
                    lx.push_back(x_of(xs[i]));
                    ly.push_back(y_of(ys[i]));
                    low.push_back(y_of(ys[i] - 2.0 * ss[i]));
                    high.push_back(y_of(ys[i] + 2.0 * ss[i]));
                }
                for (std::size_t i = end; i-- > first;) {
                    bx.push_back(x_of(xs[i]));
                    by.push_back(y_of(ys[i] - 2.0 * ss[i]));
                }
                const auto n = static_cast<PLINT>(lx.size());
                pls->col0(band_colour);
                if (bx.size() >= 3 && lx.size() >= 2) pls->fill(static_cast<PLINT>(bx.size()), bx.data(), by.data());
                pls->col0(line_colour);
                pls->lsty(c.dashed ? 2 : 1);
                pls->width(2.0);
                if (n >= 2) pls->line(n, lx.data(), ly.data());
                const bool lone = c.value.size() == 1;  // a curve of one point: a larger dot and its +-2 s.e. bar
                if (lone && ss[first] > 0.0) pls->erry(n, lx.data(), low.data(), high.data());
                if (const int marker = drawn_marker(c); marker > 0) {
                    // About 20 markers along a dense curve, so that they mark it without hiding it.
                    const auto stride = std::max<std::size_t>(1, xs.size() / 20);
                    std::vector<PLFLT> mx, my;
                    for (std::size_t i = first; i < end; ++i) {
                        if (i % stride == 0) {
                            mx.push_back(lx[i - first]);
                            my.push_back(ly[i - first]);
                        }
                    }
                    pls->schr(0.0, type * (lone ? 0.9 : 0.55));
                    pls->string(static_cast<PLINT>(mx.size()), mx.data(), my.data(), marker_glyph(marker));
                    pls->schr(0.0, type);
                }
            }
        }
    }
    pls->lsty(1);
    pls->col0(1);

    // The legend beside the axes, from the top of the first panel down to the foot of the page.
    const double region_left = choice.axes_right + 0.03, region_right = 1.0 - edge_px / W;
    const double region_top = 1.0 - head_px / H, region_bottom = edge_px / H;
    pls->vpor(region_left, region_right, region_bottom, region_top);
    pls->wind(0.0, 1.0, 0.0, 1.0);
    const double region_w_px = (region_right - region_left) * W, region_h_px = (region_top - region_bottom) * H;
    std::vector<PLINT> opts, colours, styles, text_colours(entries.size(), 1), symbol_numbers(entries.size(), 1);
    std::vector<PLFLT> widths, symbol_scales;
    std::vector<const char*> labels, symbols;
    for (const auto& e : entries) {
        labels.push_back(e.text.c_str());
        if (e.curve == nullptr) {
            opts.push_back(PL_LEGEND_NONE);
            colours.push_back(1);
            styles.push_back(1);
            widths.push_back(1.0);
            symbols.push_back("");
            symbol_scales.push_back(0.0);
            continue;
        }
        const auto& c = *e.curve;
        colours.push_back(line_colours.at(e.curve));
        const int marker = drawn_marker(c);
        opts.push_back((c.value.size() > 1 ? PL_LEGEND_LINE : 0) | (marker > 0 ? PL_LEGEND_SYMBOL : 0));
        styles.push_back(c.dashed ? 2 : 1);
        widths.push_back(2.0);
        symbols.push_back(marker_glyph(marker));
        symbol_scales.push_back(type * 0.55);
    }
    const auto rows = static_cast<PLINT>((entries.size() + choice.columns - 1) / choice.columns);
    PLFLT legend_width = 0.0, legend_height = 0.0;
    if (!entries.empty()) pls->legend(&legend_width, &legend_height, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX | PL_LEGEND_ROW_MAJOR,
                PL_POSITION_INSIDE | PL_POSITION_TOP | PL_POSITION_LEFT, 0.0, 0.0, 44.0 / region_w_px, 0, 1, 1, rows,
                choice.columns, static_cast<PLINT>(entries.size()), opts.data(), 1.0, type * choice.text_scale, 1.5, 0.0, text_colours.data(),
                labels.data(), nullptr, nullptr, nullptr, nullptr, colours.data(), styles.data(), widths.data(), colours.data(),
                symbol_scales.data(), symbol_numbers.data(), symbols.data());
    out.layout.legend_left_px = region_left * W;
    out.layout.legend_right_px = out.layout.legend_left_px + legend_width * region_w_px;
    out.layout.legend_top_px = head_px;
    out.layout.legend_bottom_px = head_px + legend_height * region_h_px;
    out.legend_fits = legend_width <= 1.0 && legend_height <= 1.0;
    out.legend_height_fraction = legend_height;
    out.legend_width_fraction = legend_width;
    out.region_width_px = region_w_px;
    out.region_height_px = region_h_px;
    pls.reset();  // the destructor finishes and closes the file
    return out;
}

}  // namespace

SeriesStyle distinct_series_style(std::size_t k) {
    // Matplotlib's "tab10" colours (Tableau 10), sRGB.
    static constexpr std::array<std::array<int, 3>, 10> tab10{{{31, 119, 180},
                                                               {255, 127, 14},
                                                               {44, 160, 44},
                                                               {214, 39, 40},
                                                               {148, 103, 189},
                                                               {140, 86, 75},
                                                               {227, 119, 194},
                                                               {127, 127, 127},
                                                               {188, 189, 34},
                                                               {23, 190, 207}}};
    const auto& c = tab10[k % 10];
    return {{c[0] / 255.0, c[1] / 255.0, c[2] / 255.0}, static_cast<int>((k / 10) % 8) + 1};
}

std::vector<std::string> wrap_plot_text(const std::string& text, std::size_t max_chars) {
    if (text.size() <= max_chars) return {text};
    const auto semicolon = text.find("; ");
    if (semicolon != std::string::npos) return {text.substr(0, semicolon + 1), text.substr(semicolon + 2)};
    const auto middle = text.size() / 2;
    std::size_t best = std::string::npos;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == ' ' && (best == std::string::npos || (i > middle ? i - middle : middle - i) < (best > middle ? best - middle : middle - best))) best = i;
    }
    if (best == std::string::npos) return {text};
    return {text.substr(0, best), text.substr(best + 1)};
}

PlotLayout write_figure(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                        const std::vector<PlotPanel>& panels) {
    const auto ext = file.extension().string();
    if (ext != ".png" && ext != ".svg") throw InputError(file.string() + ": plot extension '" + ext + "' is not supported (allowed: .png, .svg)");
    const bool empty = std::all_of(panels.begin(), panels.end(), [](const PlotPanel& p) {
        return std::all_of(p.curves.begin(), p.curves.end(), [](const PlotCurve& c) { return c.value.empty(); });
    });
    if (panels.empty() || empty) throw InputError(file.string() + ": nothing to plot");
    std::vector<Window> windows;
    for (const auto& p : panels) windows.push_back(panel_window(file, p));
    const auto device = ext == ".png" ? std::string("pngcairo") : std::string("svgcairo");
    PlotLayout layout;
    write_atomically(file, [&](const std::filesystem::path& temporary) {
        const auto draw = [&](const LegendPlan& plan) { return render(temporary, device, title, x_label, panels, windows, plan); };
        const auto all_entries = legend_entries(panels, 1);
        std::size_t longest_label_chars = 1;
        for (const auto& e : all_entries) longest_label_chars = std::max(longest_label_chars, utf8_length(e.text));
        auto drawn = draw({legend_choices.front()});
        if (!drawn.legend_fits) {
            // The first drawing measures a column's width and a row's height; they scale with the type. Each other
            // arrangement predicted to fit is drawn, in order, until one does.
            const auto& first = legend_choices.front();
            const double entries = static_cast<double>(drawn.layout.legend_entries);
            const double column_px = drawn.legend_width_fraction * drawn.region_width_px / first.text_scale;
            const double row_px = drawn.legend_height_fraction * drawn.region_height_px / entries / first.text_scale;
            const auto width_of = [&](const LegendChoice& c) { return (1.0 - edge_px / page_width_px - c.axes_right - 0.03) * page_width_px; };
            const auto rows_fit = [&](const LegendChoice& c) { return std::floor(0.95 * drawn.region_height_px / (row_px * c.text_scale)); };
            const auto wide_enough = [&](const LegendChoice& c) { return c.columns * column_px * c.text_scale <= 0.97 * width_of(c); };
            for (std::size_t i = 1; i < legend_choices.size() && !drawn.legend_fits; ++i) {
                const auto& c = legend_choices[i];
                if (wide_enough(c) && std::ceil(entries / c.columns) <= rows_fit(c)) drawn = draw({c});
            }
            if (!drawn.legend_fits) {
                // Too many to list: every k-th entry in the arrangement that holds the most, its columns as wide as
                // the longer of the labels and the note; labels too long for any arrangement are shortened. A drawing
                // still too wide loses a column or label characters, one still too tall lists fewer entries.
                const double note_chars = 24.0, sample_chars = 8.0;  // "(1 in 12 of 120 listed)"; a line sample and gaps
                const double listed_column_px = column_px * (std::max<double>(static_cast<double>(longest_label_chars), note_chars) + sample_chars) /
                                                (static_cast<double>(longest_label_chars) + sample_chars);
                const auto holds = [&](const LegendChoice& c) { return c.columns * listed_column_px * c.text_scale <= 0.97 * width_of(c); };
                const auto every_for = [&](const LegendChoice& c) {
                    const double capacity = std::max(3.0, c.columns * rows_fit(c));
                    return std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(entries / (capacity - 2.0))));
                };
                std::optional<LegendChoice> roomiest;
                for (const auto& c : legend_choices) {
                    if (holds(c) && (!roomiest || c.columns * rows_fit(c) > roomiest->columns * rows_fit(*roomiest))) roomiest = c;
                }
                LegendPlan plan{roomiest.value_or(legend_choices[2])};
                plan.every = every_for(plan.choice);
                if (!roomiest) {
                    const double room_px = 0.9 * width_of(plan.choice) / plan.choice.text_scale;
                    plan.label_chars = std::max<std::size_t>(8, static_cast<std::size_t>((longest_label_chars + sample_chars) * room_px / column_px - sample_chars));
                }
                for (int attempt = 0; attempt < 16; ++attempt) {
                    drawn = draw(plan);
                    if (drawn.legend_fits) break;
                    if (drawn.legend_width_fraction > 1.0) {
                        const auto fewer = std::find_if(legend_choices.begin(), legend_choices.end(),
                                                        [&](const LegendChoice& c) { return c.columns == plan.choice.columns - 1; });
                        if (fewer != legend_choices.end()) {
                            plan.choice = *fewer;
                        } else {
                            const auto chars = plan.label_chars > 0 ? plan.label_chars : longest_label_chars;
                            plan.label_chars = std::max<std::size_t>(8, static_cast<std::size_t>(0.9 * chars / drawn.legend_width_fraction));
                        }
                        plan.every = every_for(plan.choice);
                    } else {
                        plan.every = std::max(plan.every + 1, static_cast<std::size_t>(std::ceil(plan.every * drawn.legend_height_fraction * 1.05)));
                    }
                }
            }
        }
        if (!std::filesystem::exists(temporary)) throw InputError(file.string() + ": the plot could not be written");
        layout = drawn.layout;
    });
    return layout;
}

PlotLayout write_line_plot(const std::filesystem::path& file, const std::string& title, const std::string& x_label,
                           const std::string& y_label, const std::vector<PlotCurve>& curves, PlotStyle style) {
    return write_figure(file, title, x_label, {PlotPanel{y_label, curves, style, {}}});
}

}  // namespace skinspec
