// Argument conversions, result objects and the interruptible call shared by every binding (bindings.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "appearance/profile_shape_report.hpp"
#include "python/bindings.hpp"
#include "solvers/matched_multipole_solver.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec::python {

bool is_path(const py::handle& value) { return py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"); }

std::filesystem::path path_argument(const py::handle& value, std::string_view what) {
    if (!is_path(value)) {
        throw InputError(std::string(what) + ": expected a file path (str or os.PathLike), got " +
                         py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
    }
    return py::str(py::module_::import("os").attr("fspath")(value)).cast<std::string>();
}

std::vector<std::filesystem::path> output_paths(const py::handle& value, std::string_view what) {
    std::vector<std::filesystem::path> out;
    if (value.is_none()) return out;
    if (is_path(value) || !py::isinstance<py::iterable>(value)) return {path_argument(value, what)};
    for (const auto& f : py::iter(value)) out.push_back(path_argument(f, what));
    return out;
}

const SpectralSolver& profile_solver_argument(const py::object& mode) {
    if (mode.is_none()) return default_profile_solver();
    if (!py::isinstance<py::str>(mode)) throw InputError("mode: expected a solver name or None, got " + std::string(py::str(py::type::of(mode).attr("__name__"))));
    return find_solver(mode.cast<std::string>(), "mode");
}

PyMaterial material_argument(const py::handle& value, std::string_view what) {
    if (py::isinstance<PyMaterial>(value)) return value.cast<PyMaterial>();
    if (is_path(value)) return {load_material(path_argument(value, what).string()), {}};
    throw InputError(std::string(what) + ": expected a skinspec.Material, a preset name or a .toml path, got " +
                     py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

// Switch keywords (solvers/solver_switches.hpp: NAME with '_' for '-'), read by the same descriptors as the program's options.
SolverSwitches solver_switches(const py::kwargs& keywords) {
    SolverSwitches s;
    for (const auto& [key, value] : keywords) {
        const auto name = py::str(key).cast<std::string>();
        const auto* d = find_switch(name);
        if (!d) {
            std::string allowed;
            for (const auto& sd : switch_descriptors()) {
                std::string keyword(sd.name);
                std::replace(keyword.begin(), keyword.end(), '-', '_');
                if (sd.parse) allowed += (allowed.empty() ? "" : ", ") + keyword;
            }
            throw InputError("'" + name + "' is not a keyword (solver switches: " + allowed + ")");
        }
        if (value.is_none()) continue;
        if (py::isinstance<py::bool_>(value)) throw InputError(name + " = " + py::str(value).cast<std::string>() + " is not allowed (" + std::string(d->values) + ")");
        d->parse(s, py::str(value).cast<std::string>(), name);
    }
    return s;
}

ProfileRequest profile_request_argument(const WavelengthGrid& wavelengths, const py::object& radii_mm, bool transmittance, const ProfileSamplingArguments& sampling,
                                        const py::kwargs& switches, std::vector<MaterialOverride> overrides) {
    ProfileRequest request;
    request.overrides = std::move(overrides);
    request.wavelengths = wavelengths;
    request.radii_mm = finite_vector(radii_mm, "radii_mm");
    request.transmittance = transmittance;
    request.switches = solver_switches(switches);
    apply_profile_sampling(sampling, request);
    return request;
}

void apply_profile_sampling(const ProfileSamplingArguments& sampling, ProfileRequest& request) {
    if (!sampling.rays.is_none() && !(sampling.stderr_target.is_none() && sampling.max_rays.is_none())) {
        throw InputError("rays and stderr / max_rays: give an exact photon count or a precision target (and its budget), not both");
    }
    if (!sampling.rays.is_none()) request.rays_per_wavelength = whole_number(sampling.rays, 1.0, 1e15, "rays");
    if (!sampling.stderr_target.is_none()) {
        request.stderr_target = one_number(sampling.stderr_target, "stderr");
        check_range(request.stderr_target, 1e-6, 0.5, "stderr");
        request.sampling_options.push_back("stderr");
    }
    if (!sampling.max_rays.is_none()) {
        request.max_rays_per_wavelength = whole_number(sampling.max_rays, static_cast<double>(minimum_rays_per_wavelength), 1e15, "max_rays");
        request.sampling_options.push_back("max_rays");
    }
    if (!sampling.seed.is_none()) {
        request.seed = whole_number(sampling.seed, 0.0, 9.2e18, "seed");
        request.sampling_options.push_back("seed");
    }
}

SpectralProfiles solve_profiles_interruptible(const SpectralSolver& solver, const Material& material, const ProfileRequest& request) {
    return solve_profiles_interruptible(solver, std::vector<const Material*>{&material}, request).front();
}

std::vector<SpectralProfiles> solve_profiles_interruptible(const SpectralSolver& solver, const std::vector<const Material*>& materials,
                                                           const ProfileRequest& request) {
    std::vector<SpectralProfiles> p;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>&) {
            auto r = request;
            r.cancel = &cancel;
            p = solve_profiles(solver, materials, r);
        },
        py::none());
    return p;
}

std::vector<SweepAxis> vary_axes(const py::object& vary) {
    std::vector<SweepAxis> axes;
    if (vary.is_none()) return axes;
    if (!py::isinstance<py::dict>(vary)) throw InputError("vary: expected a dict {field: values}");
    for (const auto& [field, values] : vary.cast<py::dict>()) {
        const auto key = py::str(field).cast<std::string>();
        auto v = finite_vector(values, "vary['" + key + "']");
        if (v.empty()) throw InputError("vary['" + key + "']: no values");
        axes.push_back({key, std::move(v)});
    }
    return axes;
}

ProfileShapeCheck stated_profile_shape_interruptible(const SpectralSolver& solver, const Material& material, const WavelengthGrid& wavelengths,
                                                     const SolverSwitches& switches) {
    ProfileShapeCheck shape;
    run_interruptible([&](const CancelFlag& cancel, const std::function<void(const Progress&)>&) { shape = stated_profile_shape(solver, material, wavelengths, switches, &cancel); },
                      py::none());
    return shape;
}

py::object profile_shape_object(const SpectralSolver& solver, const Material& material, const ProfileShapeCheck& shape) {
    return profile_shape_checked(solver, material) ? json_object(profile_shape_json(shape)) : py::object(py::none());
}

WavelengthGrid wavelength_argument(const py::object& wavelengths) {
    if (wavelengths.is_none()) return WavelengthGrid::range(400.0, 700.0, 10.0);
    return WavelengthGrid::list(finite_vector(wavelengths, "wavelengths"), "wavelengths");
}

namespace {

std::string shape_text(const py::array& a) {
    std::string out = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) out += (d ? ", " : "") + std::to_string(a.shape(d));
    return out + (a.ndim() == 1 ? ",)" : ")");
}

py::array_t<double, py::array::c_style> as_doubles(const py::handle& value, std::string_view what) {
    if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || value.is_none()) {
        throw InputError(std::string(what) + ": expected numbers, got " + py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
    }
    py::array raw;
    try {
        raw = py::array(py::module_::import("numpy").attr("asarray")(value));
    } catch (const py::error_already_set&) {
        throw InputError(std::string(what) + ": expected an array of numbers");
    }
    const char kind = raw.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
        throw InputError(std::string(what) + ": expected numbers, got an array of dtype " + py::str(raw.dtype()).cast<std::string>());
    }
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
}

void check_finite(const py::array_t<double, py::array::c_style>& a, std::string_view what) {
    const double* data = a.data();
    for (py::ssize_t i = 0; i < a.size(); ++i) {
        if (std::isfinite(data[i])) continue;
        std::string index;
        py::ssize_t rest = i;
        for (py::ssize_t d = a.ndim() - 1; d >= 0; --d) {
            index = std::to_string(rest % a.shape(d)) + (index.empty() ? "" : ", ") + index;
            rest /= a.shape(d);
        }
        throw InputError(fmt::format("{}[{}] = {} is not a finite number", what, index, format_number(data[i])));
    }
}

}  // namespace

std::vector<double> finite_vector(const py::handle& value, std::string_view what) {
    const auto a = as_doubles(value, what);
    if (a.ndim() > 1) throw InputError(std::string(what) + ": expected a 1-D array, got shape " + shape_text(a));
    check_finite(a, what);
    return std::vector<double>(a.data(), a.data() + a.size());
}

py::array_t<double, py::array::c_style> finite_array(const py::handle& value, std::string_view what) {
    auto a = as_doubles(value, what);
    check_finite(a, what);
    return a;
}

std::vector<std::string> name_list(const py::handle& value, std::string_view what) {
    std::vector<std::string> out;
    // A dict iterates its keys: its values would be dropped without a word (swatch(vary={field: values})).
    if (py::isinstance<py::dict>(value)) throw InputError(std::string(what) + ": expected a string or a list of strings, not a dict");
    if (py::isinstance<py::str>(value)) {
        const auto text = value.cast<std::string>();
        for (std::size_t start = 0; start <= text.size();) {
            const auto comma = std::min(text.find(',', start), text.size());
            out.push_back(std::string(trim(std::string_view(text).substr(start, comma - start))));
            start = comma + 1;
        }
        return out;
    }
    try {
        for (const auto& item : value) out.push_back(item.cast<std::string>());
    } catch (const py::cast_error&) {
        throw InputError(std::string(what) + ": expected a string or a list of strings");
    }
    return out;
}

std::uint64_t whole_number(const py::handle& value, double lo, double hi, std::string_view what) {
    if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) throw InputError(std::string(what) + ": expected a whole number");
    const auto index = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
    if (!index) throw py::error_already_set();
    check_range(index.cast<double>(), lo, hi, what);
    return index.cast<std::uint64_t>();
}

double one_number(const py::handle& value, std::string_view what) {
    const auto a = as_doubles(value, what);
    if (a.ndim() != 0) throw InputError(std::string(what) + ": expected one number");
    check_finite(a, what);
    return *a.data();
}

void check_range(double value, double lo, double hi, std::string_view what) {
    if (!(value >= lo && value <= hi)) {
        throw InputError(fmt::format("{} = {} is outside [{}, {}]", what, format_number(value), format_number(lo), format_number(hi)));
    }
}

py::array_t<double> to_array(const std::vector<double>& values, const std::vector<py::ssize_t>& shape) {
    py::array_t<double> out(shape);
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

py::object json_object(const nlohmann::ordered_json& json) {
    if (json.is_object()) {
        py::dict d;
        for (const auto& [key, value] : json.items()) d[py::str(key)] = json_object(value);
        return d;
    }
    if (json.is_array()) {
        const bool numbers = !json.empty() && std::all_of(json.begin(), json.end(), [](const auto& v) { return v.is_number(); });
        if (numbers) return to_array(json.get<std::vector<double>>(), {static_cast<py::ssize_t>(json.size())});
        py::list l;
        for (const auto& v : json) l.append(json_object(v));
        return l;
    }
    if (json.is_boolean()) return py::bool_(json.get<bool>());
    if (json.is_number_integer()) return py::int_(json.get<std::int64_t>());
    if (json.is_number_unsigned()) return py::int_(json.get<std::uint64_t>());
    if (json.is_number()) return py::float_(json.get<double>());
    if (json.is_string()) return py::str(json.get<std::string>());
    return py::none();
}

py::object result_object(const char* type_name, const py::dict& fields) {
    return py::module_::import("skinspec.results").attr(type_name)(**fields);
}

void run_interruptible(const Work& work, const py::object& on_progress) {
    CancelFlag cancel{false};
    std::mutex lock;
    std::condition_variable finished_signal;
    bool finished = false;
    std::optional<Progress> latest;
    std::exception_ptr failure;
    const auto report = [&](const Progress& p) {
        const std::lock_guard guard(lock);
        latest = p;
    };
    std::thread worker;
    {
        const py::gil_scoped_release release;
        worker = std::thread([&] {
            try {
                work(cancel, report);
            } catch (...) {
                failure = std::current_exception();
            }
            const std::lock_guard guard(lock);
            finished = true;
            finished_signal.notify_all();
        });
    }
    const auto stop = [&] {
        cancel = true;
        const py::gil_scoped_release release;
        worker.join();
    };
    while (true) {
        bool done = false;
        std::optional<Progress> progress;
        {
            const py::gil_scoped_release release;
            std::unique_lock guard(lock);
            finished_signal.wait_for(guard, std::chrono::milliseconds(50), [&] { return finished; });
            done = finished;
            progress.swap(latest);
        }
        try {
            if (progress && !on_progress.is_none()) {
                py::dict p;
                p["rays_done"] = progress->rays_done;
                p["rays_expected"] = progress->rays_expected;
                p["done"] = progress->wavelengths_done;
                p["total"] = progress->wavelengths_total;
                on_progress(p);
            }
            if (!done && PyErr_CheckSignals() != 0) throw py::error_already_set();
        } catch (...) {
            stop();
            throw;
        }
        if (done) break;
    }
    {
        const py::gil_scoped_release release;
        worker.join();
    }
    if (failure) std::rethrow_exception(failure);
}

ThreadLimit::ThreadLimit(const py::object& threads) {
    if (threads.is_none()) return;
    control_.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(whole_number(threads, 1, 1024, "threads")));
}

}  // namespace skinspec::python
