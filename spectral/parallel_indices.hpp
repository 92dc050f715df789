#pragma once
// f(i) for every i in [0, n), in parallel (oneTBB), with the failure a serial loop would report: when several calls
// throw, the exception of the lowest index is rethrown after all have run, so a refusal names the same member for
// any thread count.
#include <cstddef>
#include <exception>
#include <vector>

#include <tbb/parallel_for.h>

namespace skinspec {

template <typename F>
void parallel_indices(std::size_t n, F&& f) {
    std::vector<std::exception_ptr> failures(n);
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
        try {
            f(i);
        } catch (...) {
            failures[i] = std::current_exception();
        }
    });
    for (const auto& failure : failures) {
        if (failure) std::rethrow_exception(failure);
    }
}

}  // namespace skinspec
