#pragma once
// The native part of the Python module (docs/PYTHON.md): one bind_* per area, and the argument conversions and
// the interruptible call they share. Nothing here computes physics: every call goes to the library (solver
// registry, replay, fit, colorimetry) exactly as the command-line program's does.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <tbb/global_control.h>

#include "appearance/swatch_chart.hpp"
#include "materials/material_file.hpp"
#include "spectral/wavelength_grid.hpp"
#include "solvers/profile_shape_check.hpp"
#include "solvers/spectral_solver.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec::python {

namespace py = pybind11;

void bind_materials(py::module_& m);
void bind_spectra(py::module_& m);
void bind_color(py::module_& m);
void bind_fit(py::module_& m);
void bind_phase(py::module_& m);
void bind_bench(py::module_& m);
void bind_mcml(py::module_& m);
void bind_phase_study(py::module_& m);
void bind_profile_fit(py::module_& m);
void bind_swatch(py::module_& m);
void bind_exports(py::module_& m);
void bind_iad(py::module_& m);
void bind_image_fit(py::module_& m);

// A Python-side material: the resolved Material and the overrides set on it since it was loaded (recorded in
// the provenance of every result computed from it).
struct PyMaterial {
    Material material;
    std::vector<MaterialOverride> overrides;
};
// Whether `value` names a file (a str or an os.PathLike), and that file's path; InputError naming `what` otherwise.
bool is_path(const py::handle& value);
std::filesystem::path path_argument(const py::handle& value, std::string_view what);
// One path or a list of them (None: none), as the functions' output= takes them.
std::vector<std::filesystem::path> output_paths(const py::handle& value, std::string_view what);
// A Material object, or a preset name / .toml path (loaded).
PyMaterial material_argument(const py::handle& value, std::string_view what);

// A 1-D array-like of finite numbers (a scalar is one value). InputError naming `what`, the shape or the first
// bad entry and its index.
std::vector<double> finite_vector(const py::handle& value, std::string_view what);
// Any array-like of finite numbers, as float64 (C order).
py::array_t<double, py::array::c_style> finite_array(const py::handle& value, std::string_view what);
// Wavelengths in nm (an array-like; None: 400-700 nm every 10 nm, the CLI's default).
WavelengthGrid wavelength_argument(const py::object& wavelengths);
// Switch keywords (solvers/solver_switches.hpp: NAME with '_' for '-'), read by the same descriptors as the
// program's options; InputError for a keyword that is no switch.
SolverSwitches solver_switches(const py::kwargs& keywords);
// The Monte Carlo keywords of the functions that need radial profiles (as the commands' --rays, --stderr, --max-rays,
// --seed; None: the defaults, ProfileRequest's).
struct ProfileSamplingArguments {
    py::object rays, stderr_target, max_rays, seed;
};
// Sets them on `request` (InputError for rays and stderr both, or a value out of range); those given are named in its
// sampling_options, so that a deterministic solver refuses them.
void apply_profile_sampling(const ProfileSamplingArguments& sampling, ProfileRequest& request);
// A profile request as skinspec.profiles takes its keywords.
ProfileRequest profile_request_argument(const WavelengthGrid& wavelengths, const py::object& radii_mm, bool transmittance, const ProfileSamplingArguments& sampling,
                                        const py::kwargs& switches, std::vector<MaterialOverride> overrides);
// The solver of a function that needs radial profiles: mode= by name, or (None) default_profile_solver().
const SpectralSolver& profile_solver_argument(const py::object& mode);
// solve_profiles under run_interruptible (Ctrl-C stops it).
SpectralProfiles solve_profiles_interruptible(const SpectralSolver& solver, const Material& material, const ProfileRequest& request);
// Several materials' profiles together (solve_profiles), interruptible.
std::vector<SpectralProfiles> solve_profiles_interruptible(const SpectralSolver& solver, const std::vector<const Material*>& materials,
                                                           const ProfileRequest& request);
// `vary`: None (no axes) or a dict {field: values} (each a non-empty sequence of finite numbers), in order.
std::vector<SweepAxis> vary_axes(const py::object& vary);
// stated_profile_shape (solvers/profile_shape_check.hpp: a diffusion profile's shape against the volumetric walk) under
// run_interruptible; as a dict (profile_shape_json), None where nothing is checked (a walk's profile, band materials).
ProfileShapeCheck stated_profile_shape_interruptible(const SpectralSolver& solver, const Material& material, const WavelengthGrid& wavelengths,
                                                     const SolverSwitches& switches);
py::object profile_shape_object(const SpectralSolver& solver, const Material& material, const ProfileShapeCheck& shape);
// A string of comma-separated names or a sequence of strings ("R,T" or ["R", "T"]).
std::vector<std::string> name_list(const py::handle& value, std::string_view what);
// InputError "WHAT = V is outside [LO, HI]" unless lo <= v <= hi.
void check_range(double value, double lo, double hi, std::string_view what);
// A Python integer (or numpy integer; not a bool) in [lo, hi].
std::uint64_t whole_number(const py::handle& value, double lo, double hi, std::string_view what);
// One finite number.
double one_number(const py::handle& value, std::string_view what);

py::array_t<double> to_array(const std::vector<double>& values, const std::vector<py::ssize_t>& shape);
// A JSON report (the one a command prints with --json, declared once in the library) as Python: objects as dicts,
// arrays of numbers as float64 numpy arrays, other arrays as lists.
py::object json_object(const nlohmann::ordered_json& json);
// The result types of python/skinspec/results.py (Spectrum, Profiles, ...), built from keyword fields.
py::object result_object(const char* type_name, const py::dict& fields);

// Runs `work` on a worker thread with the GIL released. The calling thread wakes every 50 ms: it hands the
// latest progress to `on_progress` (a Python callable taking a dict, or None) and checks for signals. Ctrl-C (or an
// exception in the callback) sets the cancel flag, waits for the worker to stop at its next batch, discards what it
// computed and raises. Exceptions of `work` are re-raised in the caller (InputError as skinspec.InputError).
using Work = std::function<void(const CancelFlag& cancel, const std::function<void(const Progress&)>& report)>;
void run_interruptible(const Work& work, const py::object& on_progress);

// A swatch request from skinspec.swatch's keywords (set: a dict of overrides; seed, max_rays: None for the defaults;
// the solver's switches as keywords).
SwatchRequest swatch_request_argument(const std::string& material, const py::object& set, double delta_e, const std::string& illuminant,
                                      const std::string& observer, const std::string& solver, const py::object& seed, const py::object& max_rays,
                                      const std::string& geometry, const py::kwargs& switches);
// compute_swatch under run_interruptible, with `threads` and `progress` as the functions take them.
SwatchChart compute_swatch_interruptible(const SwatchRequest& request, const py::object& threads, const py::object& progress);
// The chart as skinspec.swatch returns it: (rows, columns, ...) numpy arrays; colours in the linear `space`.
py::dict swatch_dict(const SwatchChart& chart, const SwatchRequest& request, const std::string& space);

// Scoped `threads` (None: all cores): TBB's global parallelism limit while a call runs.
class ThreadLimit {
public:
    explicit ThreadLimit(const py::object& threads);
    ThreadLimit(const ThreadLimit&) = delete;
    ThreadLimit& operator=(const ThreadLimit&) = delete;

private:
    std::optional<tbb::global_control> control_;
};

}  // namespace skinspec::python
