#pragma once
// How the independent units of a long computation (the groups of a sweep, the chunks of a look-up texture) are
// shared among cooperating processes, e.g. MPI ranks (cli/process_group.cpp). Units go round-robin, so that a
// grid's neighbouring (similarly costly) units land on different processes. Results travel as bytes
// (solvers/result_wire.hpp); the process that gathers them gets exactly what it would have computed itself.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace skinspec {

class WorkShare {
public:
    virtual ~WorkShare() = default;
    virtual std::size_t rank() const = 0;  // 0: the process that gathers and writes
    virtual std::size_t size() const = 0;
    bool mine(std::size_t unit) const { return unit % size() == rank(); }
    // Collective (every process calls it once per computation): `mine` holds the (unit, bytes) this process
    // computed. Rank 0 gets `units` entries in unit order, empty where no process finished the unit (stopped);
    // the other ranks get nothing.
    virtual std::vector<std::string> gather(const std::vector<std::pair<std::size_t, std::string>>& mine, std::size_t units) const = 0;
};

}  // namespace skinspec
