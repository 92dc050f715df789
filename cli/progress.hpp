#pragma once
// Terminal progress and Ctrl-C handling for long runs: a one-line bar on standard error when it is a
// terminal, and a SIGINT handler that asks the solver to stop (a second Ctrl-C exits at once).
#include <chrono>
#include <string>

#include "layers/spectral_request.hpp"

namespace skinspec::cli {

class ProgressBar {
public:
    explicit ProgressBar(std::string label);
    ~ProgressBar();
    void operator()(const Progress& progress);

private:
    std::string label_;
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point last_;
};

// Installs the SIGINT handler for the lifetime of the object; cancel_flag() is what solvers watch.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    static const CancelFlag& cancel_flag();
    static bool interrupted();
};

}  // namespace skinspec::cli
