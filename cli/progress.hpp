#pragma once
// Terminal progress and stopping for long runs: a one-line bar on standard error when it is a terminal, with
// the time left once it can be estimated, a one-time note (terminal or not) when a run is estimated to take
// minutes, and handlers for SIGINT, SIGTERM and SIGHUP (what Ctrl-C, batch schedulers, `timeout` and
// container stops send) that ask the solver to stop, so what finished is kept; a second signal exits at once.
#include <chrono>
#include <string>

#include "transport/spectral_request.hpp"
#include "transport/time_left.hpp"

namespace skinspec::cli {

class ProgressBar {
public:
    // `unit`: what Progress's done/total count, e.g. "wavelengths" or "patches".
    explicit ProgressBar(std::string label, std::string unit = "wavelengths");
    ~ProgressBar();
    void operator()(const Progress& progress);
    // Removes the bar from the terminal (before anything else is printed).
    void clear();

private:
    std::string label_;
    std::string unit_;
    bool enabled_;
    bool drawn_ = false;
    bool noted_ = false;
    TimeLeft time_left_;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_;
};

// "2 h 13 min", "4 min 5 s", "12 s".
std::string duration_text(double seconds);

// Installs the handlers for the lifetime of the object; cancel_flag() is what solvers watch.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    static const CancelFlag& cancel_flag();
    static bool interrupted();
    static std::string reason();  // "interrupted", "stopped (SIGTERM)", "stopped (SIGTERM to process 1 of the job)"
    static int exit_code();       // 128 + the signal number, as a shell reports it
    // The signal this process received (0: none), and a stop passed on from another process of the job, which
    // stops this one as that signal would (cli/process_group.cpp).
    static int own_signal();
    static void stop_by_peer(int signal, std::size_t rank);
    // The handlers from now until the process exits (a process of an MPI job: one that finished its share and
    // waits for the others must still pass a stop on, not die of it).
    static void install_for_process();
};

}  // namespace skinspec::cli
