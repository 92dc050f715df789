#include "cli/process_group.hpp"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <limits>
#include <memory>

#include "spectral/input_error.hpp"

#ifdef SKINSPEC_MPI
#include <mpi.h>
#endif

namespace skinspec::cli {

#ifdef SKINSPEC_MPI
namespace {

// Started by an MPI launcher: OpenMPI's mpirun sets OMPI_COMM_WORLD_SIZE, PMIx launchers PMIX_RANK.
bool launched_by_mpi() { return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr; }

void check_mpi(int code, const char* call) {
    if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed (code " + std::to_string(code) + ")");
}

class MpiWorkShare final : public WorkShare {
public:
    MpiWorkShare() {
        int rank = 0, size = 1;
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        rank_ = static_cast<std::size_t>(rank);
        size_ = static_cast<std::size_t>(size);
    }
    std::size_t rank() const override { return rank_; }
    std::size_t size() const override { return size_; }
    // One message per rank: [unit count][unit, length]... then the bytes, gathered with MPI_Gatherv.
    std::vector<std::string> gather(const std::vector<std::pair<std::size_t, std::string>>& mine, std::size_t units) const override {
        std::vector<std::uint64_t> header{mine.size()};
        std::string body;
        for (const auto& [unit, bytes] : mine) {
            header.push_back(unit);
            header.push_back(bytes.size());
            body += bytes;
        }
        std::string message(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
        message += body;
        if (message.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
            throw InputError("MPI: rank " + std::to_string(rank_) + "'s results are over 2 GiB; use more ranks or a smaller grid");
        }
        const int length = static_cast<int>(message.size());
        std::vector<int> lengths(rank_ == 0 ? size_ : 0), offsets(rank_ == 0 ? size_ : 0);
        check_mpi(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
        std::string all;
        if (rank_ == 0) {
            std::size_t total = 0;
            for (std::size_t r = 0; r < size_; ++r) {
                offsets[r] = static_cast<int>(total);
                total += static_cast<std::size_t>(lengths[r]);
            }
            if (total > static_cast<std::size_t>(std::numeric_limits<int>::max())) throw InputError("MPI: the gathered results are over 2 GiB; use a smaller grid");
            all.resize(total);
        }
        check_mpi(MPI_Gatherv(message.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD),
                  "MPI_Gatherv");
        if (rank_ != 0) return {};
        std::vector<std::string> out(units);
        for (std::size_t r = 0; r < size_; ++r) {
            const char* at = all.data() + offsets[r];
            const auto word = [&](std::size_t i) {
                std::uint64_t w = 0;
                std::memcpy(&w, at + i * sizeof(std::uint64_t), sizeof w);
                return w;
            };
            const auto count = word(0);
            std::size_t position = (1 + 2 * count) * sizeof(std::uint64_t);
            for (std::uint64_t k = 0; k < count; ++k) {
                const auto unit = word(1 + 2 * k), size = word(2 + 2 * k);
                out.at(unit).assign(at + position, size);
                position += size;
            }
        }
        return out;
    }

private:
    std::size_t rank_ = 0;
    std::size_t size_ = 1;
};

std::unique_ptr<MpiWorkShare>& mpi_share() {
    static std::unique_ptr<MpiWorkShare> share;
    return share;
}

}  // namespace

void join_process_group(int& argc, char**& argv) {
    if (!launched_by_mpi()) return;
    // Only the main thread calls MPI (the gathers); TBB's workers never do.
    int provided = 0;
    check_mpi(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    auto share = std::make_unique<MpiWorkShare>();
    if (share->size() > 1) mpi_share() = std::move(share);
    // Registered after the share's holder exists, so it runs before the holder is destroyed.
    std::atexit([] { MPI_Finalize(); });
}

int error_exit(int code) {
    if (mpi_share()) MPI_Abort(MPI_COMM_WORLD, code);
    return code;
}

const WorkShare* process_work_share() { return mpi_share().get(); }
#else
void join_process_group(int&, char**&) {}
int error_exit(int code) { return code; }
const WorkShare* process_work_share() { return nullptr; }
#endif

bool is_root_process() { return process_work_share() == nullptr || process_work_share()->rank() == 0; }
std::size_t process_count() { return process_work_share() == nullptr ? 1 : process_work_share()->size(); }

}  // namespace skinspec::cli
