// skinspec.phase_study (docs/PYTHON.md "Thin-layer phase functions"): the experiments of Baranoski et al. 2005 as
// `skinspec phase-study --json` reports them (studies/phase_study/phase_study.hpp declares the report once).
#include "python/bindings.hpp"
#include "studies/phase_study/phase_study.hpp"

namespace skinspec::python {
namespace {

py::object phase_study(const py::object& seed, const py::object& threads) {
    PhaseStudySettings settings;
    settings.seed = whole_number(seed, 0, 9.223372036854775808e18, "seed");
    const ThreadLimit limit(threads);
    PhaseStudy study;
    run_interruptible([&](const CancelFlag&, const std::function<void(const Progress&)>&) { study = run_phase_study(settings); }, py::none());
    return json_object(phase_study_json(study));
}

}  // namespace

void bind_phase_study(py::module_& m) {
    m.def("phase_study", &phase_study, R"doc(Baranoski et al. 2005's experiments, as `skinspec phase-study --json` reports them (6-9 s; Ctrl-C stops it at the end).

    Returns a dict: bin_edges_deg; cases (stratum corneum and epidermis at 436 and 546 nm), each with the measured
    bin fractions, the HG g fitted by RMS (Table 2) and van Gemert's, and per approach (table_lookup, hg_rms,
    hg_van_gemert) the sampled fractions, their relative errors (Table 3) and the virtual goniometer's BTDF (1/sr);
    and the cost of HG warping against table look-up per sample. Arrays are numpy.)doc",
          py::kw_only(), py::arg("seed") = 1, py::arg("threads") = py::none());
}

}  // namespace skinspec::python
