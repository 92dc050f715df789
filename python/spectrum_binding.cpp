// skinspec.spectrum, skinspec.profiles and skinspec.solvers (docs/PYTHON.md "Spectra"): the solver registry,
// its central refusals and replayed sweeps, exactly as `skinspec spectrum` / `skinspec profile` call them.
#include <algorithm>
#include <chrono>

#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "solvers/spectral_solver.hpp"
#include "spectral/input_error.hpp"
#include "transport/result_quantities.hpp"

namespace skinspec::python {
namespace {

py::object setting_value(const SettingValue& v) {
    return std::visit([](const auto& x) -> py::object { return py::cast(x); }, v);
}

py::dict settings_dict(const std::map<std::string, SettingValue>& settings) {
    py::dict out;
    for (const auto& [k, v] : settings) out[py::str(k)] = setting_value(v);
    return out;
}

py::list warnings_list(const std::vector<ResultWarning>& warnings) {
    py::list out;
    for (const auto& w : warnings) {
        out.append(py::dict(py::arg("kind") = w.kind, py::arg("subject") = w.subject, py::arg("at") = w.at, py::arg("value") = w.value));
    }
    return out;
}

py::object stated_error_object(const std::optional<StatedError>& e) {
    if (!e) return py::none();
    return py::dict(py::arg("R") = e->R, py::arg("meaning") = *e->meaning,
                    py::arg("delta_e2000") = e->delta_e2000 ? py::object(py::float_(*e->delta_e2000)) : py::none());
}

py::dict provenance_dict(const SpectralResult& r) {
    py::dict varied;
    for (std::size_t f = 0; f < r.provenance.varied.size(); ++f) varied[py::str(r.provenance.varied.field(f))] = r.provenance.varied.values[f];
    return py::dict(py::arg("solver") = r.provenance.solver, py::arg("material") = r.material, py::arg("model") = r.model,
                    py::arg("material_toml") = *r.provenance.material_toml, py::arg("overrides") = all_overrides(r.provenance),
                    py::arg("varied") = varied, py::arg("settings") = settings_dict(all_settings(r)), py::arg("warnings") = warnings_list(r.warnings),
                    py::arg("stated_error") = stated_error_object(r.stated_error),
                    py::arg("version") = r.provenance.version);
}

// The overrides of variant= and reflector=, in the order `spectrum --variant ... --reflector` applies them.
std::vector<MaterialOverride> option_overrides(const py::object& variant, const py::object& reflector) {
    std::vector<MaterialOverride> out;
    if (!variant.is_none()) out.push_back({"model.variant", variant.cast<std::string>(), "variant"});
    if (reflector.is_none()) return out;
    if (py::isinstance<py::bool_>(reflector)) {
        out.push_back(reflector_override(reflector.cast<bool>() ? "on" : "off", "reflector"));
        return out;
    }
    if (!py::isinstance<py::str>(reflector)) {
        throw InputError("reflector: must be True, False or one of " + reflector_choices() + " (got " + std::string(py::str(py::type::of(reflector).attr("__name__"))) + ")");
    }
    out.push_back(reflector_override(reflector.cast<std::string>(), "reflector"));
    return out;
}

// Results of a sweep laid out as numpy arrays of shape (sweep..., rows[, inner]); the first axis of `vary` is the
// first array axis (sweep_grid lists the first axis fastest).
class SweepLayout {
public:
    SweepLayout(std::vector<py::ssize_t> sweep_shape, std::size_t rows) : shape_(std::move(sweep_shape)), rows_(rows) {}

    template <class T, class Get>
    py::array_t<T> gather(const std::vector<SpectralResult>& results, std::size_t inner, const Get& get) const {
        auto shape = shape_;
        shape.push_back(static_cast<py::ssize_t>(rows_));
        if (inner > 0) shape.push_back(static_cast<py::ssize_t>(inner));
        py::array_t<T> out(shape);
        T* data = out.mutable_data();
        const std::size_t per_member = rows_ * std::max<std::size_t>(inner, 1);
        for (std::size_t f = 0; f < results.size(); ++f) {
            T* member = data + target(f) * per_member;
            for (std::size_t w = 0; w < rows_; ++w) {
                for (std::size_t k = 0; k < std::max<std::size_t>(inner, 1); ++k) {
                    member[w * std::max<std::size_t>(inner, 1) + k] = get(results[f].wavelengths[w], k);
                }
            }
        }
        return out;
    }

    py::object objects(const std::vector<py::object>& items) const {
        if (shape_.empty()) return items.front();
        py::array out(py::dtype("O"), shape_);
        auto* data = static_cast<PyObject**>(out.mutable_data());
        for (std::size_t f = 0; f < items.size(); ++f) {
            Py_XDECREF(data[target(f)]);
            data[target(f)] = items[f].inc_ref().ptr();
        }
        return out;
    }

private:
    // Flat member index (first axis fastest) -> C-order offset over shape_.
    std::size_t target(std::size_t f) const {
        std::size_t offset = 0, stride = 1;
        std::vector<std::size_t> index(shape_.size());
        for (std::size_t a = 0; a < shape_.size(); ++a) {
            index[a] = f % static_cast<std::size_t>(shape_[a]);
            f /= static_cast<std::size_t>(shape_[a]);
        }
        for (std::size_t a = shape_.size(); a-- > 0;) {
            offset += index[a] * stride;
            stride *= static_cast<std::size_t>(shape_[a]);
        }
        return offset;
    }

    std::vector<py::ssize_t> shape_;
    std::size_t rows_;
};

py::object spectrum_result(const std::vector<SpectralResult>& results, const std::vector<SweepAxis>& axes, double seconds) {
    std::vector<py::ssize_t> sweep_shape;
    for (const auto& a : axes) sweep_shape.push_back(static_cast<py::ssize_t>(a.values.size()));
    const auto& first = results.front();
    const SweepLayout layout(sweep_shape, first.wavelengths.size());
    const bool stderrs = first.has_uncertainty;
    py::dict d;
    if (first.bands.empty()) {
        std::vector<double> nm;
        for (const auto& w : first.wavelengths) nm.push_back(w.wavelength_nm);
        d["wavelength_nm"] = to_array(nm, {static_cast<py::ssize_t>(nm.size())});
    } else {
        d["wavelength_nm"] = py::none();
    }
    d["bands"] = first.bands;
    // Every quantity of the table (transport/result_quantities.hpp) by its Python name; None where not requested.
    for (const auto& q : result_quantities()) {
        const std::string name(q.python_name);
        const bool asked = q.requested(first.quantities);
        const std::size_t inner = q.shape == QuantityShape::scalar ? 0 : q.count(first);
        const auto gather = [&](bool error) {
            return layout.gather<double>(results, inner, [&](const WavelengthResult& w, std::size_t k) {
                const auto& e = q.values(w)[k];
                return error ? e.stderr : e.value;
            });
        };
        d[name.c_str()] = asked ? py::object(gather(false)) : py::none();
        d[(name + "_stderr").c_str()] = asked && stderrs ? py::object(gather(true)) : py::none();
    }
    d["angular_bin_edges_deg"] = first.angular_bin_edges_deg;
    if (stderrs) {
        d["rays"] = layout.gather<std::uint64_t>(results, 0, [](const WavelengthResult& w, std::size_t) { return w.rays; });
        d["truncated_rays"] = layout.gather<std::uint64_t>(results, 0, [](const WavelengthResult& w, std::size_t) { return w.truncated_rays; });
        d["converged"] = layout.gather<bool>(results, 0, [](const WavelengthResult& w, std::size_t) { return w.converged; });
    } else {
        for (const char* name : {"rays", "truncated_rays", "converged"}) d[name] = py::none();
    }
    d["has_uncertainty"] = stderrs;
    d["layer_names"] = first.layer_names;
    d["solver"] = first.provenance.solver;
    d["model"] = first.model;
    d["material"] = first.material;
    d["settings"] = settings_dict(all_settings(first));
    py::dict vary;
    for (const auto& a : axes) vary[py::str(a.field)] = to_array(a.values, {static_cast<py::ssize_t>(a.values.size())});
    d["vary"] = vary;
    std::vector<py::object> provenance;
    std::vector<ResultWarning> warnings;
    for (const auto& r : results) {
        provenance.push_back(provenance_dict(r));
        warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
    }
    d["provenance"] = layout.objects(provenance);
    d["warnings"] = summarise_warnings(warnings);
    d["seconds"] = seconds;
    return result_object("Spectrum", d);
}

py::object spectrum(const py::object& material, const py::object& wavelengths, const std::string& mode, const py::object& quantities,
                    const py::object& stderr_target, const py::object& rays, const py::object& max_rays, const std::string& geometry,
                    const py::object& incidence_deg, const py::object& seed, const py::object& threads, const py::object& reflector,
                    const py::object& variant, const py::object& layers, const py::object& vary, const py::object& progress,
                    const py::kwargs& switches) {
    const auto& solver = find_solver(mode, "mode");
    const auto base = material_argument(material, "material");
    SolverRequest request;
    const auto extra = option_overrides(variant, reflector);
    request.overrides = base.overrides;
    request.overrides.insert(request.overrides.end(), extra.begin(), extra.end());
    request.switches = solver_switches(switches);
    auto& spectral = request.spectral;
    spectral.wavelengths = wavelength_argument(wavelengths);
    std::string quantity_text;
    for (const auto& q : name_list(quantities, "quantities")) quantity_text += (quantity_text.empty() ? "" : ",") + q;
    spectral.quantities = parse_quantities(quantity_text, "quantities");
    spectral.incidence_deg = one_number(incidence_deg, "incidence_deg");
    spectral.geometry = parse_measurement_geometry(geometry, "geometry");
    // Given (not None) to a deterministic solver, these are refused by check_request, as --seed and --max-rays are.
    if (!seed.is_none()) {
        spectral.seed = whole_number(seed, 0, 9.223372036854775808e18, "seed");
        request.sampling_options.push_back("seed");
    }
    spectral.max_rays_per_wavelength = 10'000'000;  // as the CLI's --max-rays
    if (!max_rays.is_none()) {
        spectral.max_rays_per_wavelength = whole_number(max_rays, static_cast<double>(minimum_rays_per_wavelength), static_cast<double>(maximum_rays_per_wavelength), "max_rays");
        request.sampling_options.push_back("max_rays");
    }
    if (!rays.is_none() && !stderr_target.is_none()) throw InputError("rays and stderr: give one (a fixed ray count or a target), not both");
    if (!rays.is_none()) {
        request.fixed_rays_per_wavelength = whole_number(rays, static_cast<double>(minimum_rays_per_wavelength), static_cast<double>(maximum_rays_per_wavelength), "rays");
    } else if (!stderr_target.is_none()) {
        const double target = one_number(stderr_target, "stderr");
        if (!(target > 0.0)) throw InputError("stderr = " + py::str(stderr_target).cast<std::string>() + " is outside (0, inf)");
        spectral.stderr_target = target;
    } else if (solver.capabilities().uncertainty) {
        spectral.stderr_target = 0.002;
    }
    const auto axes = vary_axes(vary);
    const auto layer_list = layers.is_none() ? std::vector<std::string>{} : name_list(layers, "layers");
    const auto with_options = with_overrides(base.material, extra);
    const auto members = sweep_members(solver, request, axes, layer_list, with_options);

    const ThreadLimit limit(threads);
    std::vector<SpectralResult> results;
    const auto start = std::chrono::steady_clock::now();
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
            auto r = request;
            r.spectral.cancel = &cancel;
            r.spectral.on_progress = report;
            results = solve_sweep(solver, members, r);
        },
        progress);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return spectrum_result(results, axes, seconds);
}

py::object profiles(const py::object& material, const py::object& radii_mm, const py::object& wavelengths, const py::object& mode,
                    bool transmittance, const py::object& rays, const py::object& stderr_target, const py::object& max_rays, const py::object& seed,
                    const py::kwargs& switches) {
    const auto base = material_argument(material, "material");
    const auto& solver = profile_solver_argument(mode);
    const auto request = profile_request_argument(wavelengths.is_none() ? WavelengthGrid::list({450.0, 550.0, 650.0}) : wavelength_argument(wavelengths),
                                                  radii_mm, transmittance, {rays, stderr_target, max_rays, seed}, switches, base.overrides);
    const auto p = solve_profiles_interruptible(solver, base.material, request);
    const auto rows = static_cast<py::ssize_t>(p.channels.size());
    const auto radii = static_cast<py::ssize_t>(p.radii_mm.size());
    std::vector<double> nm, r, t, r_se, t_se, total_r, total_t, specular;
    std::vector<std::string> labels;
    for (const auto& c : p.channels) {
        labels.push_back(c.label);
        nm.push_back(c.wavelength_nm);
        r.insert(r.end(), c.reflectance_per_mm2.begin(), c.reflectance_per_mm2.end());
        t.insert(t.end(), c.transmittance_per_mm2.begin(), c.transmittance_per_mm2.end());
        r_se.insert(r_se.end(), c.reflectance_stderr_per_mm2.begin(), c.reflectance_stderr_per_mm2.end());
        t_se.insert(t_se.end(), c.transmittance_stderr_per_mm2.begin(), c.transmittance_stderr_per_mm2.end());
        total_r.push_back(c.total_reflectance);
        total_t.push_back(c.total_transmittance);
        specular.push_back(c.specular_reflectance);
    }
    const bool bands = std::holds_alternative<HomogeneousMaterial>(base.material);
    py::dict d;
    d["radii_mm"] = to_array(p.radii_mm, {radii});
    d["wavelength_nm"] = bands ? py::object(py::none()) : py::object(to_array(nm, {rows}));
    d["labels"] = labels;
    d["R_per_mm2"] = to_array(r, {rows, radii});
    d["T_per_mm2"] = transmittance ? py::object(to_array(t, {rows, radii})) : py::object(py::none());
    const bool errors = solver.capabilities().uncertainty;  // Monte Carlo profiles carry standard errors
    d["R_stderr_per_mm2"] = errors ? py::object(to_array(r_se, {rows, radii})) : py::object(py::none());
    d["T_stderr_per_mm2"] = errors && transmittance ? py::object(to_array(t_se, {rows, radii})) : py::object(py::none());
    d["total_R"] = to_array(total_r, {rows});
    d["total_T"] = transmittance ? py::object(to_array(total_t, {rows})) : py::object(py::none());
    d["R_specular"] = to_array(specular, {rows});
    d["solver"] = std::string(solver.name());
    d["model"] = p.model;
    d["material"] = p.material;
    d["warnings"] = summarise_warnings(p.warnings);
    d["shape"] = profile_shape_object(solver, base.material, stated_profile_shape_interruptible(solver, base.material, request.wavelengths, request.switches));
    return result_object("Profiles", d);
}

py::list solvers() {
    py::list out;
    for (const auto* s : solver_registry()) {
        const auto& c = s->capabilities();
        std::vector<std::string> quantities, switches, geometries;
        if (c.quantities.reflectance) quantities.push_back("R");
        if (c.quantities.transmittance) quantities.push_back("T");
        if (c.quantities.absorptance) quantities.push_back("A");
        if (c.quantities.angular) quantities.push_back("brdf");
        for (const auto sw : c.switches) switches.emplace_back(to_string(sw));
        for (const auto g : c.geometries) geometries.emplace_back(to_string(g));
        out.append(py::dict(py::arg("name") = std::string(s->name()), py::arg("description") = std::string(s->description()),
                            py::arg("quantities") = quantities, py::arg("layered_materials") = c.layered_materials,
                            py::arg("band_materials") = c.band_materials, py::arg("uncertainty") = c.uncertainty,
                            py::arg("radial_profiles") = c.radial_profiles, py::arg("switches") = switches,
                            py::arg("replay_fields") = c.replay_fields, py::arg("geometries") = geometries,
                            py::arg("material_needs") = c.material_needs, py::arg("bottom") = c.bottom));
    }
    return out;
}

// The result quantity table: what skinspec.Spectrum holds, in order.
py::list quantities() {
    py::list out;
    for (const auto& q : result_quantities()) {
        out.append(py::dict(py::arg("python_name") = std::string(q.python_name), py::arg("key") = std::string(q.key), py::arg("unit") = std::string(q.unit),
                            py::arg("doc") = std::string(q.doc)));
    }
    return out;
}

// The solver switches a call can give as keywords, from their descriptors.
py::list switches() {
    py::list out;
    for (const auto& d : switch_descriptors()) {
        if (!d.parse) continue;
        std::string keyword(d.name);
        std::replace(keyword.begin(), keyword.end(), '-', '_');
        out.append(py::dict(py::arg("keyword") = keyword, py::arg("option") = "--" + std::string(d.name), py::arg("values") = std::string(d.values)));
    }
    return out;
}

}  // namespace

void bind_spectra(py::module_& m) {
    m.def("spectrum", &spectrum, R"doc(Spectral reflectance (and T, A per layer, BRDF) of a material by any registered solver.

    The same computation as `skinspec spectrum`: same defaults (400-700 nm every 10 nm; Monte Carlo solvers stop
    each wavelength at a standard error of 0.002 unless rays= or stderr= is given), same seed -> same numbers (seed
    default 1, max_rays default 1e7; both refused by deterministic modes, as rays= is).
    mode: a solver of skinspec.solvers(). quantities: "R", "R,T,A,brdf" or a list. vary={field: values} sweeps
    one or more fields (a grid): every array then has the sweep's shape in front, R[i, j, w] at the i-th value of
    the first field and the j-th of the second; fields that only absorb are replayed from one set of traced paths.
    progress: a callable taking {rays_done, rays_expected, done, total}, called on this thread. Ctrl-C raises
    KeyboardInterrupt within about a batch of rays and keeps nothing. Solver switches as keywords, one per switch
    the registry knows (skinspec.switches(): estimator, fold_into_skin, boundaries, roughness, channels); one the
    solver does not take is refused. Returns a skinspec.Spectrum.)doc",
          py::arg("material"), py::arg("wavelengths") = py::none(), py::kw_only(), py::arg("mode") = "biospec", py::arg("quantities") = "R",
          py::arg("stderr") = py::none(), py::arg("rays") = py::none(), py::arg("max_rays") = py::none(), py::arg("geometry") = "sci",
          py::arg("incidence_deg") = 0.0, py::arg("seed") = py::none(), py::arg("threads") = py::none(), py::arg("reflector") = py::none(),
          py::arg("variant") = py::none(), py::arg("layers") = py::none(), py::arg("vary") = py::none(), py::arg("progress") = py::none());
    m.def("profiles", &profiles, R"doc(Radial diffuse reflectance R(r) (and T(r)) in 1/mm^2, as `skinspec profile` computes it.

    radii_mm: 1-D array; wavelengths (layered materials; default 450, 550, 650 nm); mode: a solver with radial
    profiles (default None: rte, the exact transport by the volumetric walk, radii from 0 in equal steps, each
    wavelength run until the reflectance leaving within every radius of a 1-2-5 series has a standard error of at most
    stderr (default 0.002) within max_rays photons (default 1e6), or exactly rays photons; seed; its R_stderr_per_mm2;
    or a diffusion mode: matched-multipole, multipole, dipole). Solver switches as keywords (roughness=, boundaries=, ...); a switch the
    solver does not take is refused.
    Returns a skinspec.Profiles.)doc",
          py::arg("material"), py::arg("radii_mm"), py::arg("wavelengths") = py::none(), py::kw_only(), py::arg("mode") = py::none(),
          py::arg("transmittance") = false, py::arg("rays") = py::none(), py::arg("stderr") = py::none(), py::arg("max_rays") = py::none(),
          py::arg("seed") = py::none());
    m.def("solvers", &solvers, "The registered solvers and what each declares it supports.");
    m.def("result_quantities", &quantities, "The result quantities (the rows of skinspec.Spectrum's arrays), with units.");
    m.def("switches", &switches, "The solver switches (keywords of spectrum and profiles), with the values each takes.");
}

}  // namespace skinspec::python
