#pragma once
// A WorkShare of N "processes" that are threads of the test: what an MPI run does (each rank solves its share,
// rank 0 gathers), without MPI, so the library's sharing is tested in every build.
#include <barrier>
#include <functional>
#include <mutex>
#include <thread>

#include "solvers/work_share.hpp"

namespace skinspec::testing {

class ThreadWorkShare final : public WorkShare {
public:
    struct Pool {
        explicit Pool(std::size_t n) : size(n), sync(static_cast<std::ptrdiff_t>(n)) {}
        std::size_t size;
        std::barrier<> sync;
        std::mutex lock;
        std::vector<std::pair<std::size_t, std::string>> all;
    };
    ThreadWorkShare(Pool& pool, std::size_t rank) : pool_(pool), rank_(rank) {}
    std::size_t rank() const override { return rank_; }
    std::size_t size() const override { return pool_.size; }
    std::vector<std::string> gather(const std::vector<std::pair<std::size_t, std::string>>& mine, std::size_t units) const override {
        {
            const std::lock_guard guard(pool_.lock);
            pool_.all.insert(pool_.all.end(), mine.begin(), mine.end());
        }
        pool_.sync.arrive_and_wait();
        std::vector<std::string> out;
        if (rank_ == 0) {
            out.resize(units);
            for (const auto& [unit, bytes] : pool_.all) out.at(unit) = bytes;
        }
        pool_.sync.arrive_and_wait();
        return out;
    }

private:
    Pool& pool_;
    std::size_t rank_;
};

// Runs `run(share)` on `n` threads, one per rank; returns rank 0's result.
template <class Result>
Result run_shared(std::size_t n, const std::function<Result(const WorkShare&)>& run) {
    ThreadWorkShare::Pool pool(n);
    Result root;
    std::vector<std::thread> ranks;
    for (std::size_t r = 1; r < n; ++r) ranks.emplace_back([&, r] { run(ThreadWorkShare(pool, r)); });
    root = run(ThreadWorkShare(pool, 0));
    for (auto& t : ranks) t.join();
    return root;
}

}  // namespace skinspec::testing
