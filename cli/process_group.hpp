#pragma once
// The processes one run is shared among. Built with MPI (SKINSPEC_MPI, OpenMPI from Debian) and started by
// mpirun/mpiexec, every rank runs the same command: `spectrum --vary` and `export lut` give each rank its share
// of the grid (solvers/work_share.hpp) and rank 0 gathers, prints and writes. Otherwise (a plain start, or a
// build without MPI) the run is one process.
#include "solvers/work_share.hpp"

namespace skinspec::cli {

// Joins the MPI job when started by an MPI launcher (MPI_Init; MPI_Finalize at exit, std::exit included);
// nothing otherwise.
void join_process_group(int& argc, char**& argv);
// The exit code for an error: with several processes, the whole job is stopped (MPI_Abort), since the other
// ranks may be waiting for this one's results; otherwise `code` is returned.
int error_exit(int code);

// The share of this run among its processes; nullptr for one process.
const WorkShare* process_work_share();
// Rank 0 (or the only process): the one that prints and writes.
bool is_root_process();
std::size_t process_count();

}  // namespace skinspec::cli
