#pragma once
// MCML's file formats (Wang, Jacques & Zheng, MCML manual 1995, Sec. 9-10): `.mci` input (several runs per
// file, grid, layers in cm, ambient indices) and `.mco` ASCII output in MCML 1.2's layout (InParm, RAT,
// A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, A_rz, Rd_ra, Tt_ra), so MCML readers and its convolution program work.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "transport/rte/rte_model.hpp"

namespace skinspec {

struct McmlRun {
    std::string output_file;  // as written in the .mci
    char output_format = 'A';
    std::uint64_t photons = 0;
    RteGrid grid;
    RteStack stack;
};

// InputError naming file, line, field, value and range for any malformed entry.
std::vector<McmlRun> read_mci(const std::filesystem::path& file);

// One run's input parameters in MCML's layout (output file, photons, grid, layers, ambient indices): a run of a `.mci`
// file, and the InParm block of its `.mco`.
std::string run_parameters_text(const McmlRun& run);
// A `.mci` file of `runs` (MCML 1.2 reads it, as does read_mci), `comments` as its opening comment lines. Phase
// functions are written as their g (MCML's HG): a run's stack must hold HG layers only, and no bottom reflector.
std::string mci_text(const std::vector<McmlRun>& runs, const std::vector<std::string>& comments);

// The .mco text of one run (MCML 1.2 layout; `time_report` becomes the "# ..." line after the header).
// With `grids` false (a deterministic solver's totals) the file ends after A_l with a note.
std::string mco_text(const McmlRun& run, const RteResult& result, const std::string& time_report, bool grids = true);

// The walk's request for one run: its stack, photons, grid; `seed` and `boundaries` from the caller.
RteRequest mcml_request(const McmlRun& run, std::uint64_t seed, BoundaryMode boundaries);

// One run's result as `skinspec mcml --json` writes it and skinspec.mcml returns it: totals with standard errors
// and MCML's arrays (grids [r][z] and [r][a] row-major), each with its _stderr, in MCML's units (named).
nlohmann::ordered_json mcml_run_json(const McmlRun& run, const RteResult& result, double seconds);

}  // namespace skinspec
