// skinspec.mcml (docs/PYTHON.md "MCML files"): the runs of an MCML .mci file by the volumetric walk (or
// adding-doubling's totals), as `skinspec mcml --json` reports them (formats/mcml_files.hpp), with numpy arrays.
#include <chrono>

#include "formats/mcml_files.hpp"
#include "python/bindings.hpp"
#include "spectral/input_error.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"

namespace skinspec::python {
namespace {

// The run's JSON as Python (numpy arrays), MCML's grids shaped [r][z] and [r][a].
py::dict run_object(const McmlRun& run, const RteResult& result, double seconds) {
    const py::dict d = json_object(mcml_run_json(run, result, seconds));
    const py::ssize_t nr = run.grid.nr, nz = run.grid.nz, na = run.grid.na;
    for (const auto& [key, value] : d) {
        const auto name = py::str(key).cast<std::string>();
        if (!py::isinstance<py::array>(value)) continue;
        if (name.starts_with("A_rz")) d[key] = value.attr("reshape")(nr, nz);
        if (name.starts_with("R_ra") || name.starts_with("T_ra")) d[key] = value.attr("reshape")(nr, na);
    }
    return d;
}

py::list mcml(const std::string& file, const py::object& photons, const py::object& seed, const std::string& boundaries, const std::string& solver,
              const py::object& threads, const py::object& progress) {
    auto runs = read_mci(file);
    const bool deterministic = solver == "adding-doubling";
    if (!deterministic && solver != "rte") throw InputError("solver: '" + solver + "' is not allowed (allowed: rte, adding-doubling)");
    if (deterministic && (!photons.is_none() || !seed.is_none())) {
        throw InputError(std::string("solver adding-doubling is deterministic: it takes no ") + (!photons.is_none() ? "photons" : "seed") +
                         " (the volumetric walk does)");
    }
    const auto mode = parse_boundary_mode(boundaries, "boundaries");
    const auto chosen_seed = seed.is_none() ? std::uint64_t{1} : whole_number(seed, 0, 9.223372036854775808e18, "seed");
    if (!photons.is_none()) {
        const auto n = whole_number(photons, 1, 1e12, "photons");
        for (auto& run : runs) run.photons = n;
    }
    const ThreadLimit limit(threads);
    py::list out;
    for (auto& run : runs) {
        RteResult result;
        double seconds = 0.0;
        run_interruptible(
            [&](const CancelFlag& cancel, const std::function<void(const Progress&)>& report) {
                const auto start = std::chrono::steady_clock::now();
                if (deterministic) {
                    AdOptions options;
                    options.cancel = &cancel;
                    result = rte_totals(solve_adding_doubling(run.stack, {}, options));
                } else {
                    auto request = mcml_request(run, chosen_seed, mode);
                    request.cancel = &cancel;
                    request.on_progress = report;
                    result = solve_rte(request);
                }
                seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            },
            progress);
        run.photons = result.photons;
        auto d = run_object(run, result, seconds);
        if (deterministic) d["model"] = "adding-doubling";
        out.append(d);
    }
    return out;
}

}  // namespace

void bind_mcml(py::module_& m) {
    m.def("mcml", &mcml, R"doc(The runs of an MCML .mci file, as `skinspec mcml --json` reports them (no .mco is written).

    photons: overrides each run's count; boundaries: "random" (MCML's) or "split"; solver: "rte" (the volumetric
    walk, with standard errors and MCML's grids) or "adding-doubling" (deterministic totals). Returns one dict per
    run: R, R_specular, R_diffuse, T, A (each with _stderr), A_layers and MCML's arrays in its units as numpy arrays
    (A_z_per_cm, R_r_per_cm2, T_r_per_cm2, R_a_per_sr, T_a_per_sr; A_rz_per_cm3 shaped (nr, nz), R_ra/T_ra_per_cm2_sr
    shaped (nr, na)), the input's grid and the photons traced.)doc",
          py::arg("file"), py::kw_only(), py::arg("photons") = py::none(), py::arg("seed") = py::none(), py::arg("boundaries") = "random",
          py::arg("solver") = "rte", py::arg("threads") = py::none(), py::arg("progress") = py::none());
}

}  // namespace skinspec::python
