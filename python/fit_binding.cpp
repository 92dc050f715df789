// skinspec.fit_spectrum (docs/PYTHON.md "Fitting"): biophysical parameters of measured reflectance spectra by the
// BioSpec walk on replayed paths, as `skinspec fit-spectrum` fits them (docs/SPECTRUM_FIT.md).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "formats/measured_spectra.hpp"
#include "inverse/spectrum_fit/spectrum_fit.hpp"
#include "python/bindings.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::python {
namespace {

std::vector<FitParameter> free_parameters(const py::object& free, const py::object& bounds) {
    std::vector<FitParameter> out;
    if (free.is_none()) out = default_free_parameters();
    else {
        for (const auto& key : name_list(free, "free")) out.push_back({key, {}, {}});
    }
    if (bounds.is_none()) return out;
    if (!py::isinstance<py::dict>(bounds)) throw InputError("bounds: expected a dict {field: (lo, hi)}");
    for (const auto& [field, range] : bounds.cast<py::dict>()) {
        const auto key = py::str(field).cast<std::string>();
        const auto lo_hi = finite_vector(range, "bounds['" + key + "']");
        if (lo_hi.size() != 2 || !(lo_hi[0] < lo_hi[1])) throw InputError("bounds['" + key + "']: expected (lo, hi) with lo < hi");
        const auto it = std::find_if(out.begin(), out.end(), [&](const FitParameter& p) { return p.key == key; });
        if (it == out.end()) {
            std::string keys;
            for (const auto& p : out) keys += (keys.empty() ? "" : ", ") + p.key;
            throw InputError("bounds['" + key + "']: not a free parameter (free: " + keys + ")");
        }
        it->lo = lo_hi[0];
        it->hi = lo_hi[1];
    }
    return out;
}

py::object fit_object(const SpectrumFit& f) {
    py::dict parameters, stderrs;
    std::vector<std::string> on_bound;
    for (std::size_t i = 0; i < f.parameter_keys.size(); ++i) {
        parameters[py::str(f.parameter_keys[i])] = f.parameters[i];
        stderrs[py::str(f.parameter_keys[i])] = f.parameter_stderr[i];
        if (f.on_bound[i]) on_bound.push_back(f.parameter_keys[i]);
    }
    const auto n = static_cast<py::ssize_t>(f.wavelength_nm.size());
    std::vector<double> residual;
    for (std::size_t w = 0; w < f.measured.size(); ++w) residual.push_back(f.fitted[w] - f.measured[w]);
    py::dict d;
    d["name"] = f.name;
    d["parameters"] = parameters;
    d["parameter_stderr"] = stderrs;
    d["on_bound"] = on_bound;
    d["rms"] = f.rms;
    d["model_accuracy"] = f.model_accuracy ? py::object(py::float_(*f.model_accuracy)) : py::object(py::none());
    d["wavelength_nm"] = to_array(f.wavelength_nm, {n});
    d["measured"] = to_array(f.measured, {n});
    d["fitted"] = to_array(f.fitted, {n});
    d["fitted_stderr"] = to_array(f.fitted_stderr, {n});
    d["residual"] = to_array(residual, {n});
    d["measured_lab"] = to_array({f.measured_lab.L, f.measured_lab.a, f.measured_lab.b}, {3});
    d["fitted_lab"] = to_array({f.fitted_lab.L, f.fitted_lab.a, f.fitted_lab.b}, {3});
    d["delta_e2000"] = f.delta_e2000;
    d["evaluations"] = f.evaluations;
    d["seconds"] = f.seconds;
    return result_object("Fit", d);
}

py::object fit_spectrum(const py::object& wavelengths, const py::object& measured, const py::object& material, const py::object& free,
                        const py::object& bounds, const py::object& window, const py::object& weights, const py::object& rays,
                        const py::object& seed, const std::string& geometry, const py::object& incidence_deg, const py::object& starts, const py::object& names,
                        const std::string& mode, const py::object& channels, const py::object& threads, const py::object& progress) {
    // How the model is evaluated (as the command's --mode), checked before any input is read.
    const FitEngine engine = parse_fit_engine(mode, "mode");
    if (!traces_rays(engine) && (!rays.is_none() || !seed.is_none())) {
        throw InputError(std::string(rays.is_none() ? "seed" : "rays") + ": mode '" + mode +
                         "' solves the model exactly at every evaluation and traces no rays (rays and seed are for mode 'biospec', the replayed walk)");
    }
    if (!channels.is_none() && traces_rays(engine)) {
        throw InputError("channels: the quadrature of the exact modes (mode 'biospec' replays traced paths and has none)");
    }
    const auto nm = finite_vector(wavelengths, "wavelengths");
    WavelengthGrid::list(nm, "wavelengths");
    if (nm.size() < min_measured_points) {
        throw InputError(fmt::format("wavelengths: {} given, a fit needs at least {}", nm.size(), min_measured_points));
    }
    const auto values = finite_array(measured, "measured");
    if ((values.ndim() != 1 && values.ndim() != 2) || values.shape(values.ndim() - 1) != static_cast<py::ssize_t>(nm.size())) {
        throw InputError(fmt::format("measured: expected shape ({},) or (spectra, {}), one value per wavelength", nm.size(), nm.size()));
    }
    for (py::ssize_t i = 0; i < values.size(); ++i) {
        const double v = values.data()[i];
        if (v < 0.0 || v > max_measured_reflectance) {
            throw InputError(fmt::format("measured: value {} (entry {} in C order) is outside [0, {}]", format_number(v), i,
                                         format_number(max_measured_reflectance)));
        }
    }
    const std::size_t count = values.ndim() == 1 ? 1 : static_cast<std::size_t>(values.shape(0));
    std::vector<std::vector<double>> spectra;
    for (std::size_t s = 0; s < count; ++s) spectra.emplace_back(values.data() + s * nm.size(), values.data() + (s + 1) * nm.size());
    std::vector<std::string> spectrum_names;
    if (names.is_none()) {
        for (std::size_t s = 0; s < count; ++s) spectrum_names.push_back(count == 1 ? "measured" : "spectrum " + std::to_string(s));
    } else {
        spectrum_names = names.cast<std::vector<std::string>>();
        if (spectrum_names.size() != count) throw InputError(fmt::format("names: {} given for {} spectra", spectrum_names.size(), count));
    }
    const auto base = material_argument(material.is_none() ? py::str("biospec-moderately") : material, "material");
    const auto* stack = std::get_if<LayerStack>(&base.material);
    if (!stack) throw InputError("material '" + material_name(base.material) + "' is homogeneous: the fit needs a layered skin for the BioSpec walk");

    SpectrumFitSettings settings;
    settings.engine = engine;
    if (!channels.is_none()) {
        py::kwargs quadrature;  // read as every switch keyword is (call_support's solver_switches)
        quadrature["channels"] = channels;
        settings.channels = *solver_switches(quadrature).quadrature_channels;
    }
    settings.free = free_parameters(free, bounds);
    if (!window.is_none()) {
        const auto w = finite_vector(window, "window");
        if (w.size() != 2) throw InputError("window: expected (from_nm, to_nm)");
        settings.window_from_nm = w[0];
        settings.window_to_nm = w[1];
    }
    if (!weights.is_none()) {
        for (const auto& item : weights) {
            const auto w = finite_vector(item, "weights");
            if (w.size() != 3 || !(w[0] <= w[1]) || w[2] < 0.0) throw InputError("weights: each entry must be (from_nm, to_nm, weight) with from <= to, weight >= 0");
            settings.weights.push_back({w[0], w[1], w[2]});
        }
    }
    if (!rays.is_none()) settings.rays_per_wavelength = whole_number(rays, 1, 1e12, "rays");
    if (!seed.is_none()) settings.seed = whole_number(seed, 0, 9.223372036854775808e18, "seed");
    settings.geometry = parse_measurement_geometry(geometry, "geometry");
    settings.incidence_deg = one_number(incidence_deg, "incidence_deg");
    settings.starts = whole_number(starts, 1, static_cast<double>(SpectrumFitSettings::scan_points), "starts");
    for (std::size_t w = 0; w < nm.size(); ++w) settings.wavelength_sources.push_back("wavelengths[" + std::to_string(w) + "]");

    const ThreadLimit limit(threads);
    std::vector<std::optional<SpectrumFit>> fits;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            auto s = settings;
            s.cancel = &cancel;
            const SpectrumFitter fitter(*stack, nm, s);
            if (fitter.cancelled()) return;
            fits = fitter.fit_all(spectrum_names, spectra, [&](std::size_t done, std::size_t total) { report(Progress{0, 0, done, total}); });
        },
        progress);
    py::list out;
    for (const auto& f : fits) out.append(fit_object(*f));
    return values.ndim() == 1 ? out[0] : py::object(out);
}

}  // namespace

void bind_fit(py::module_& m) {
    m.def("fit_spectrum", &fit_spectrum, R"doc(Fits biophysical parameters to measured reflectance, as `skinspec fit-spectrum` does.

    wavelengths: 1-D, nm (at least 5); measured: one spectrum (1-D) or several (spectra x wavelengths), values in
    [0, 1.5]. material: the base (default biospec-moderately) the free fields start from; free: the fields (default
    melanosome fraction, papillary and reticular blood fraction, oxygen saturation); bounds={field: (lo, hi)};
    window=(from_nm, to_nm); weights=[(from_nm, to_nm, weight), ...]. mode: 'biospec' (default: paths traced once,
    rays per wavelength (default 20000) and seed (default 1), re-weighted), 'biospec-adding-doubling' (the model
    solved exactly at every evaluation) or 'adding-doubling' (the volumetric description solved exactly, e.g. the layers'
    own measured scattering with model.volumetric_matched_to_biospec = false); channels: the exact modes' quadrature,
    default 24. Returns a skinspec.Fit (a list of them
    for 2-D input) with parameters and standard errors, RMS, the fitted spectrum, CIEDE2000 to the measured colour and,
    for the exact model, model_accuracy: the quadrature's stated accuracy of the fitted R.)doc",
          py::arg("wavelengths"), py::arg("measured"), py::arg("material") = py::none(), py::kw_only(), py::arg("free") = py::none(),
          py::arg("bounds") = py::none(), py::arg("window") = py::none(), py::arg("weights") = py::none(), py::arg("rays") = py::none(),
          py::arg("seed") = py::none(), py::arg("geometry") = "sci", py::arg("incidence_deg") = 0.0, py::arg("starts") = SpectrumFitSettings{}.starts,
          py::arg("names") = py::none(), py::arg("mode") = "biospec", py::arg("channels") = py::none(), py::arg("threads") = py::none(),
          py::arg("progress") = py::none());
}

}  // namespace skinspec::python
