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

// The .mco text of one run (MCML 1.2 layout; `time_report` becomes the "# ..." line after the header).
// With `grids` false (a deterministic solver's totals) the file ends after A_l with a note.
std::string mco_text(const McmlRun& run, const RteResult& result, const std::string& time_report, bool grids = true);

// The walk's request for one run: its stack, photons, grid; `seed` and `boundaries` from the caller.
RteRequest mcml_request(const McmlRun& run, std::uint64_t seed, BoundaryMode boundaries);

// One run's result as `skinspec mcml --json` writes it and skinspec.mcml returns it: totals with standard errors
// and MCML's arrays (grids [r][z] and [r][a] row-major), each with its _stderr, in MCML's units (named).
nlohmann::ordered_json mcml_run_json(const McmlRun& run, const RteResult& result, double seconds);

}  // namespace skinspec
