#include "spectral/memory_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <sys/resource.h>

#include <fmt/format.h>

#include "spectral/input_error.hpp"

namespace skinspec {
namespace {

// A "Key:   N kB" line of a /proc file, in bytes; +inf when absent.
double proc_kb(const char* file, std::string_view key) {
    std::ifstream in(file);
    const std::string prefix = std::string(key) + ":";
    std::string line;
    while (std::getline(in, line)) {
        if (!line.starts_with(prefix)) continue;
        char* end = nullptr;
        const double kb = std::strtod(line.c_str() + prefix.size(), &end);
        return end == line.c_str() + prefix.size() ? std::numeric_limits<double>::infinity() : kb * 1024.0;
    }
    return std::numeric_limits<double>::infinity();
}

}  // namespace

double available_memory_bytes() {
    double available = proc_kb("/proc/meminfo", "MemAvailable");
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
        const double used = proc_kb("/proc/self/status", "VmSize");
        available = std::min(available, static_cast<double>(limit.rlim_cur) - (std::isfinite(used) ? used : 0.0));
    }
    return std::max(available, 0.0);
}

void check_memory(double bytes, std::string_view what, std::string_view hint) {
    const double available = available_memory_bytes();
    if (bytes > available) {
        throw InputError(fmt::format("{} needs about {:.2g} GB of memory, more than the {:.2g} GB available ({})", what, bytes / 1e9, available / 1e9, hint));
    }
}

}  // namespace skinspec
