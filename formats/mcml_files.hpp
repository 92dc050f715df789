#pragma once
// MCML's file formats (Wang, Jacques & Zheng, MCML manual 1995, Sec. 9-10): `.mci` input (several runs per
// file, grid, layers in cm, ambient indices) and `.mco` ASCII output in MCML 1.2's layout (InParm, RAT,
// A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, A_rz, Rd_ra, Tt_ra), so MCML readers and its convolution program work.
#include <filesystem>
#include <string>
#include <vector>

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

}  // namespace skinspec
