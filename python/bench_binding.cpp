// skinspec.bench (docs/PYTHON.md "Benchmark"): run time against error for every solver, the report `skinspec bench
// --json` prints (studies/benchmark/bench_report.hpp declares it once), as Python dicts, lists and numpy arrays.
#include "python/bindings.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "studies/benchmark/bench_report.hpp"

namespace skinspec::python {
namespace {

py::object bench(bool quick, const py::object& seed, const py::object& tolerance_percent, const py::object& threads) {
    BenchReportSettings settings{quick, whole_number(seed, 0, 9.223372036854775808e18, "seed"), one_number(tolerance_percent, "tolerance_percent")};
    if (!(settings.tolerance_percent > 0.0 && settings.tolerance_percent < 100.0)) {
        throw InputError("tolerance_percent = " + format_number(settings.tolerance_percent) + " % is outside (0, 100)");
    }
    const ThreadLimit limit(threads);
    BenchReport report;
    run_interruptible(
        [&](const CancelFlag& cancel, const std::function<void(const Progress&)>&) {
            BenchOptions options;
            options.quick = settings.quick;
            options.seed = settings.seed;
            options.cancel = &cancel;
            report = run_benchmark(options);
        },
        py::none());
    return json_object(bench_report_json(report, settings));
}

}  // namespace

void bind_bench(py::module_& m) {
    m.def("bench", &bench, R"doc(Run time against error for every solver, as `skinspec bench --json` reports it (docs/PERFORMANCE.md).

    quick: the short form (fewer budgets and seeds, shorter references); seed: of the swept runs (the references use
    another); tolerance_percent: the relative error for "fastest within". Returns a dict: cases (each with its
    reference, points: solver, rays, runs, seconds, value, relative_error, pareto; walk slopes; the fastest solver),
    multipole_pair_sweep, thread_scaling, time_per_colour, skin_in_every_mode, walk_against_adding_doubling.)doc",
          py::arg("quick") = false, py::kw_only(), py::arg("seed") = 1, py::arg("tolerance_percent") = 1.0, py::arg("threads") = py::none());
}

}  // namespace skinspec::python
