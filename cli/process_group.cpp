#include "cli/process_group.hpp"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <limits>
#include <memory>
#include <thread>

#include "cli/progress.hpp"
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

// Passes a stop on to the whole job: a signal to any one process (a scheduler's SIGTERM to one rank, Ctrl-C
// forwarded to some) stops every other within ~50 ms, so each keeps what it finished, rank 0 gathers and writes it
// marked partial, and every process exits 128 + that signal. On its own communicator (the gathers are unaffected),
// from a thread of its own, which polls: the computation's threads never call MPI.
class StopRelay {
public:
    StopRelay() {
        check_mpi(MPI_Comm_dup(MPI_COMM_WORLD, &comm_), "MPI_Comm_dup");
        MPI_Comm_rank(comm_, &rank_);
        MPI_Comm_size(comm_, &size_);
        thread_ = std::thread([this] { run(); });
    }
    ~StopRelay() {
        done_.store(true);
        thread_.join();
        MPI_Comm_free(&comm_);
    }

private:
    static constexpr int tag = 1;
    void run() {
        bool passed_on = false;
        for (;;) {
            const bool last = done_.load();
            if (!passed_on && InterruptGuard::own_signal() != 0) {
                passed_on = true;
                int signal = InterruptGuard::own_signal();
                for (int r = 0; r < size_; ++r) {
                    if (r != rank_) MPI_Send(&signal, 1, MPI_INT, r, tag, comm_);
                }
            }
            int arrived = 0;
            MPI_Status status;
            while (MPI_Iprobe(MPI_ANY_SOURCE, tag, comm_, &arrived, &status) == MPI_SUCCESS && arrived) {
                int signal = 0;
                MPI_Recv(&signal, 1, MPI_INT, status.MPI_SOURCE, tag, comm_, MPI_STATUS_IGNORE);
                if (InterruptGuard::own_signal() == 0) InterruptGuard::stop_by_peer(signal, static_cast<std::size_t>(status.MPI_SOURCE));
                passed_on = true;  // the sender told every process
            }
            if (last) return;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    }
    MPI_Comm comm_ = MPI_COMM_NULL;
    int rank_ = 0, size_ = 1;
    std::atomic<bool> done_{false};
    std::thread thread_;
};

std::unique_ptr<StopRelay>& stop_relay() {
    static std::unique_ptr<StopRelay> relay;
    return relay;
}

}  // namespace

void join_process_group(int& argc, char**& argv) {
    if (!launched_by_mpi()) return;
    // The main thread calls MPI for the gathers, the stop relay's thread for stops; TBB's workers never do.
    int provided = 0;
    check_mpi(MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided), "MPI_Init_thread");
    if (provided < MPI_THREAD_MULTIPLE) throw std::runtime_error("MPI: the library does not support threads (MPI_THREAD_MULTIPLE), which passing a stop on needs");
    auto share = std::make_unique<MpiWorkShare>();
    if (share->size() > 1) {
        mpi_share() = std::move(share);
        InterruptGuard::install_for_process();
        stop_relay() = std::make_unique<StopRelay>();
    }
    // Registered after the holders exist, so it runs before they are destroyed. Every process waits for the others
    // (rank 0 writes before it exits): mpirun ends the job when one process exits non-zero, as a stopped one does,
    // and would otherwise signal rank 0 while it writes. Then the relay stops, then MPI.
    std::atexit([] {
        if (mpi_share()) MPI_Barrier(MPI_COMM_WORLD);
        stop_relay().reset();
        MPI_Finalize();
    });
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
