// skinspec.iad (docs/PYTHON.md "Fitting", docs/IAD.md): optical properties of a slab from integrating-sphere
// measurements, as `skinspec iad` inverts them (inverse/iad; the document is declared there once: iad_json).
#include <map>

#include <pybind11/stl.h>

#include "formats/rxt_file.hpp"
#include "inverse/iad/inverse_adding_doubling.hpp"
#include "python/bindings.hpp"
#include "spectral/input_error.hpp"

namespace skinspec::python {
namespace {

// None: not given; a number or a 1-D array-like: one value per measurement.
std::vector<double> optional_values(const py::object& value, std::string_view what) {
    if (value.is_none()) return {};
    return finite_vector(value, what);
}

py::object iad(const py::object& input, const py::object& r, const py::object& t, const py::object& u, const py::object& wavelengths, double r_uncertainty, double t_uncertainty,
               double u_uncertainty, std::size_t channels, double tolerance, bool skip_unreachable, const py::object& threads,
               const py::object& progress, const py::kwargs& setup_keywords) {
    // The setup keywords are the setup table's keys (inverse/iad/slab_measurement.hpp), as `skinspec iad --KEY` takes them.
    std::map<std::string, double> setup;
    for (const auto& [key, value] : setup_keywords) setup[py::str(key).cast<std::string>()] = one_number(value, py::str(key).cast<std::string>());
    const auto in = iad_input(input.is_none() ? std::nullopt : std::optional(path_argument(input, "input")),
                              {optional_values(r, "r"), optional_values(t, "t"), optional_values(u, "u"), optional_values(wavelengths, "wavelengths")}, setup);
    check_range(r_uncertainty, 0.0, 1.0, "r_uncertainty");
    check_range(t_uncertainty, 0.0, 1.0, "t_uncertainty");
    check_range(u_uncertainty, 0.0, 1.0, "u_uncertainty");
    check_range(static_cast<double>(channels), 4.0, 256.0, "channels");
    check_range(tolerance, 1e-12, 0.1, "tolerance");
    IadSettings settings;
    settings.channels = channels;
    settings.tolerance = tolerance;
    const MeasurementUncertainty uncertainty{r_uncertainty, t_uncertainty, u_uncertainty};
    const ThreadLimit limit(threads);
    IadRun run;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            auto s = settings;
            s.cancel = &cancel;
            run = invert_rows(in.rows, uncertainty, s, [&](std::size_t done, std::size_t total) { report(Progress{0, 0, done, total}); });
        },
        progress);
    if (!run.unreachable.empty() && !skip_unreachable) {
        throw InputError(std::to_string(run.unreachable.size()) + " of " + std::to_string(in.rows.size()) +
                         " measurements are unreachable (skip_unreachable=True returns the others); the first: " + run.unreachable.front());
    }
    return json_object(iad_json(run, in.setup, in.name, settings, uncertainty, false, 0.0));
}

}  // namespace

void bind_iad(py::module_& m) {
    m.def("iad", &iad, R"doc(Optical properties of a slab from integrating-sphere measurements, as `skinspec iad` inverts them.

    input: an iad measurement file (.rxt); or r (M_R), t (M_T), u (M_U: then g is fitted too): numbers for one
    measurement or 1-D arrays for a spectrum (wavelengths in nm optional, recorded with the rows).
    Any setup field as a keyword (sample_index, slide_index, sample_thickness_mm, spheres, r_wall, ...; the keys of
    `skinspec iad --help`), applied to every row. r_uncertainty, t_uncertainty, u_uncertainty: standard uncertainties
    of the measurements, propagated to the results. Returns the document `skinspec iad --json` prints: "setup",
    "rows" (per row mu_a_per_mm, mu_s_reduced_per_mm, g, their uncertainties, the fitted M_R, M_T; None where unset)
    and "unreachable". Raises skinspec.InputError for a measurement no slab produces unless skip_unreachable.)doc",
          py::arg("input") = py::none(), py::kw_only(), py::arg("r") = py::none(), py::arg("t") = py::none(), py::arg("u") = py::none(),
          py::arg("wavelengths") = py::none(), py::arg("r_uncertainty") = 0.0, py::arg("t_uncertainty") = 0.0, py::arg("u_uncertainty") = 0.0, py::arg("channels") = IadSettings{}.channels,
          py::arg("tolerance") = IadSettings{}.tolerance, py::arg("skip_unreachable") = false, py::arg("threads") = py::none(),
          py::arg("progress") = py::none());
}

}  // namespace skinspec::python
