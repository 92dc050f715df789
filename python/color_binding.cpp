// skinspec.color, skinspec.delta_e2000 and skinspec.color_spaces (docs/PYTHON.md "Colour"): CIE colorimetry of
// numpy spectra and OpenColorIO spaces of the shipped config, as `skinspec color` computes them (docs/COLOR.md).
#include <cmath>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "spectral/ciede2000.hpp"
#include "spectral/color_management.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/colorimetry.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "spectral/wavelength_grid.hpp"

namespace skinspec::python {
namespace {

// The span `skinspec color` requires of a spectrum file (formats/spectrum_csv.hpp): the visible range.
constexpr double color_span_from_nm = 400.0;
constexpr double color_span_to_nm = 700.0;

ObserverKind observer_argument(const py::object& observer) {
    const auto text = py::isinstance<py::str>(observer) ? observer.cast<std::string>() : py::str(observer).cast<std::string>();
    return parse_observer(text, "observer");
}

std::vector<py::ssize_t> leading_shape(const py::array& a) {
    return std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim() - 1);
}

py::array_t<double> triples(const std::vector<double>& values, std::vector<py::ssize_t> shape, py::ssize_t width) {
    shape.push_back(width);
    return to_array(values, shape);
}

py::object color(const py::object& wavelengths, const py::object& spectra, const std::string& illuminant_name, const py::object& observer_name,
                 const py::object& spaces, bool allow_over_one, const py::object& standard_errors, double stated_error) {
    const auto grid = WavelengthGrid::list(finite_vector(wavelengths, "wavelengths"), "wavelengths");
    if (grid.front() > color_span_from_nm || grid.back() < color_span_to_nm) {
        throw InputError(fmt::format("wavelengths: the samples must span {:g}-{:g} nm (got {:g}-{:g} nm)", color_span_from_nm, color_span_to_nm,
                                     grid.front(), grid.back()));
    }
    const auto values = finite_array(spectra, "spectra");
    if (values.ndim() == 0 || values.shape(values.ndim() - 1) != static_cast<py::ssize_t>(grid.size())) {
        throw InputError(fmt::format("spectra: the last axis must have one value per wavelength ({}), got shape with last axis {}", grid.size(),
                                     values.ndim() == 0 ? 0 : values.shape(values.ndim() - 1)));
    }
    const double hi = allow_over_one ? std::numeric_limits<double>::infinity() : 1.0;
    for (py::ssize_t i = 0; i < values.size(); ++i) {
        const double v = values.data()[i];
        if (v < 0.0 || v > hi) {
            throw InputError(fmt::format("spectra: value {} (entry {} in C order) is outside [0, {}]{}", format_number(v), i, allow_over_one ? "inf)" : "1",
                                         allow_over_one ? "" : " (use allow_over_one=True for values above 1)"));
        }
    }
    std::optional<py::array_t<double, py::array::c_style>> errors;
    if (!standard_errors.is_none()) {
        errors = finite_array(standard_errors, "standard_errors");
        if (errors->ndim() != values.ndim() || !std::equal(values.shape(), values.shape() + values.ndim(), errors->shape())) {
            throw InputError("standard_errors: must have the shape of spectra");
        }
        for (py::ssize_t i = 0; i < errors->size(); ++i) {
            if (errors->data()[i] < 0.0) throw InputError(fmt::format("standard_errors: value {} (entry {}) is outside [0, inf)", format_number(errors->data()[i]), i));
        }
    }
    if (!std::isfinite(stated_error) || stated_error < 0.0) {
        throw InputError("stated_error = " + format_number(stated_error) + " is outside [0, inf)");
    }
    const bool uncertain = errors.has_value() || stated_error > 0.0;
    const auto illuminant = parse_illuminant(illuminant_name, "illuminant");
    const auto observer = observer_argument(observer_name);
    const auto& cm = ColorManagement::builtin();
    std::vector<std::string> space_names{"sRGB", "Linear Rec.709", "ACEScg"};
    if (!spaces.is_none()) {
        space_names.clear();
        for (const auto& name : name_list(spaces, "spaces")) space_names.push_back(cm.canonical_space(name, "spaces"));
    }
    const TristimulusWeights weights(grid.nm(), illuminant, observer, OutOfRangePolicy::hold);
    const std::size_t n = grid.size();
    const std::size_t count = static_cast<std::size_t>(values.size()) / n;
    std::vector<double> xyz, xy, lab, lab_spread, delta_e_spread;
    std::vector<std::vector<double>> rgb(space_names.size()), rgb_spread(space_names.size());
    const std::vector<double> no_errors(n, 0.0);
    for (std::size_t s = 0; s < count; ++s) {
        const std::span<const double> samples(values.data() + s * n, n);
        const XYZ c = weights.integrate(samples);
        if (uncertain) {
            const auto u = color_uncertainty(weights, samples, errors ? std::span<const double>(errors->data() + s * n, n) : std::span<const double>(no_errors),
                                             stated_error);
            lab_spread.insert(lab_spread.end(), {u.lab.L, u.lab.a, u.lab.b});
            delta_e_spread.push_back(u.delta_e2000);
            for (std::size_t k = 0; k < space_names.size(); ++k) {
                const auto v = rgb_uncertainty(c, weights.white(), u.xyz_covariance, space_names[k]);
                rgb_spread[k].insert(rgb_spread[k].end(), v.begin(), v.end());
            }
        }
        const auto ch = chromaticity(c);
        const auto l = xyz_to_lab(c, weights.white());
        xyz.insert(xyz.end(), {c.X, c.Y, c.Z});
        xy.insert(xy.end(), {ch.x, ch.y});
        lab.insert(lab.end(), {l.L, l.a, l.b});
        for (std::size_t k = 0; k < space_names.size(); ++k) {
            const auto v = cm.from_xyz(c, weights.white(), space_names[k]);
            rgb[k].insert(rgb[k].end(), v.begin(), v.end());
        }
    }
    const auto shape = leading_shape(values);
    py::dict d, spaces_out;
    d["XYZ"] = triples(xyz, shape, 3);
    d["xy"] = triples(xy, shape, 2);
    d["Lab"] = triples(lab, shape, 3);
    d["white_XYZ"] = to_array({weights.white().X, weights.white().Y, weights.white().Z}, {3});
    for (std::size_t k = 0; k < space_names.size(); ++k) spaces_out[py::str(space_names[k])] = triples(rgb[k], shape, 3);
    d["rgb"] = spaces_out;
    if (uncertain) {
        py::dict spread;
        for (std::size_t k = 0; k < space_names.size(); ++k) spread[py::str(space_names[k])] = triples(rgb_spread[k], shape, 3);
        d["Lab_uncertainty"] = triples(lab_spread, shape, 3);
        d["delta_e2000_uncertainty"] = to_array(delta_e_spread, shape);
        d["rgb_uncertainty"] = spread;
    } else {
        d["Lab_uncertainty"] = py::none();
        d["delta_e2000_uncertainty"] = py::none();
        d["rgb_uncertainty"] = py::none();
    }
    d["illuminant"] = std::string(short_name(illuminant));
    d["observer"] = std::string(display_name(observer));
    return result_object("Color", d);
}

py::array_t<double> delta_e2000(const py::object& reference, const py::object& sample) {
    const auto numpy = py::module_::import("numpy");
    const py::tuple pair = numpy.attr("broadcast_arrays")(finite_array(reference, "reference"), finite_array(sample, "sample"));
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(numpy.attr("ascontiguousarray")(pair[0]));
    const auto b = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(numpy.attr("ascontiguousarray")(pair[1]));
    if (a.ndim() == 0 || a.shape(a.ndim() - 1) != 3) throw InputError("delta_e2000: Lab values need a last axis of 3 (L, a, b)");
    std::vector<double> out;
    for (py::ssize_t i = 0; i < a.size(); i += 3) {
        out.push_back(ciede2000(Lab{a.data()[i], a.data()[i + 1], a.data()[i + 2]}, Lab{b.data()[i], b.data()[i + 1], b.data()[i + 2]}));
    }
    return to_array(out, leading_shape(a));
}

}  // namespace

void bind_color(py::module_& m) {
    m.def("color", &color, R"doc(CIE XYZ, xy, CIELAB and colour-space RGB of reflectance spectra, as `skinspec color` computes them.

    wavelengths: 1-D, nm, spanning 400-700 nm; spectra: any shape whose last axis has one value per wavelength,
    each in [0, 1] (allow_over_one=True: any value >= 0). XYZ has the perfect reflector at Y = 1; Lab is relative
    to the illuminant's white; rgb holds each of `spaces` (any colour space of the shipped OpenColorIO config,
    skinspec.color_spaces(); default sRGB (encoded), Linear Rec.709 and ACEScg), Bradford-adapted to D65 first.
    standard_errors (the spectra's shape; e.g. a Spectrum's R_stderr) and stated_error (a solver's stated error of R,
    common to every wavelength) give standard uncertainties, propagated linearly through the CIE integrals:
    Lab_uncertainty, delta_e2000_uncertainty (RMS CIEDE2000) and rgb_uncertainty per space (None without either).
    Returns a skinspec.Color whose arrays have the spectra's leading shape plus one axis (3, or 2 for xy).)doc",
          py::arg("wavelengths"), py::arg("spectra"), py::kw_only(), py::arg("illuminant") = "D65", py::arg("observer") = 2,
          py::arg("spaces") = py::none(), py::arg("allow_over_one") = false, py::arg("standard_errors") = py::none(), py::arg("stated_error") = 0.0);
    m.def("delta_e2000", &delta_e2000, "CIEDE2000 colour difference of Lab arrays (last axis L, a, b; broadcast).", py::arg("reference"),
          py::arg("sample"));
    m.def("color_spaces", [] { return ColorManagement::builtin().color_spaces(); }, "The colour spaces of the shipped OpenColorIO config.");
}

}  // namespace skinspec::python
