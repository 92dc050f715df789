#pragma once
// Wall-clock timing shared by the benchmark programs in bench/.
#include <chrono>
#include <functional>

namespace skinspec::bench {

inline double seconds_of(const std::function<void()>& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace skinspec::bench
