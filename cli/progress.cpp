#include "cli/progress.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <unistd.h>

#include <fmt/format.h>

#include "spectral/atomic_file.hpp"

namespace skinspec::cli {
namespace {

CancelFlag cancel_requested{false};
std::atomic<int> received_signal{0};  // lock-free: safe in a handler
static_assert(std::atomic<int>::is_always_lock_free);
// A stop passed on from another process of the job (cli/process_group.cpp): its signal and rank.
std::atomic<int> peer_signal{0};
std::atomic<std::size_t> peer_rank{0};
bool installed_for_process = false;  // InterruptGuard::install_for_process

extern "C" void on_stop_signal(int signal) {
    // A second signal to this process exits at once (a stop passed on from a peer does not count: mpirun's own
    // SIGTERM after it must still let this process write what finished).
    if (received_signal.load() != 0) {
        remove_temporaries_in_progress();  // nothing half-written stays (a second Ctrl-C left lut.partial-PID.exr)
        _exit(128 + signal);
    }
    received_signal.store(signal);
    cancel_requested.store(true);
}

std::string signal_name(int signal) {
    switch (signal) {
        case SIGTERM: return "SIGTERM";
        case SIGHUP: return "SIGHUP";
        default: return "SIGINT";
    }
}

// Runs longer than this are announced once, with their estimated duration.
constexpr double long_run_seconds = 60.0;

}  // namespace

std::string duration_text(double seconds) {
    constexpr double day = 86400.0, year = 365.25 * day;
    if (seconds >= 2.0 * year) return fmt::format("{:.3g} years", seconds / year);  // a budget no run will spend: say so plainly
    if (seconds >= 2.0 * day) return fmt::format("{:.0f} days", seconds / day);
    if (seconds >= 3600.0) return fmt::format("{} h {} min", static_cast<long>(seconds / 3600.0), static_cast<long>(seconds / 60.0) % 60);
    if (seconds >= 60.0) return fmt::format("{} min {} s", static_cast<long>(seconds / 60.0), static_cast<long>(seconds) % 60);
    return fmt::format("{:.0f} s", seconds);
}

ProgressBar::ProgressBar(std::string label, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), enabled_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { clear(); }

void ProgressBar::clear() {
    if (drawn_) std::fputs("\r\033[K", stderr);
    drawn_ = false;
}

void ProgressBar::operator()(const Progress& p) {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double share = work_share(p);
    const auto estimate = time_left_.update(elapsed, share);
    const bool estimable = estimate.has_value();
    const double left = estimate.value_or(0.0);
    if (estimable && !noted_ && elapsed + left > long_run_seconds) {
        noted_ = true;
        clear();
        std::fputs(fmt::format("skinspec: note: {}: estimated {} in all ({} left); Ctrl-C or SIGTERM stops and keeps what "
                               "finished\n", label_, duration_text(elapsed + left), duration_text(left)).c_str(), stderr);
    }
    if (!enabled_) return;
    if (drawn_ && now - last_ < std::chrono::milliseconds(100) && p.wavelengths_done < p.wavelengths_total) return;
    last_ = now;
    drawn_ = true;
    const std::size_t width = 30;
    const auto filled = static_cast<std::size_t>(static_cast<double>(width) * std::clamp(share, 0.0, 1.0));
    const auto rays = p.rays_done ? fmt::format(", {:.3g} rays", static_cast<double>(p.rays_done)) : std::string();
    std::fputs(fmt::format("\r\033[K{} [{}{}] {}/{} {}{}{}{}", label_, std::string(filled, '#'), std::string(width - filled, '.'),
                           p.wavelengths_done, p.wavelengths_total, unit_, rays,
                           estimable ? ", " + duration_text(left) + " left" : std::string(share < 1.0 ? ", time left: measuring" : ""),
                           cancel_requested ? " (stopping)" : "")
                   .c_str(),
               stderr);
}

InterruptGuard::InterruptGuard() {
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, on_stop_signal);
}
InterruptGuard::~InterruptGuard() {
    if (installed_for_process) return;
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, SIG_DFL);
}
void InterruptGuard::install_for_process() {
    installed_for_process = true;
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, on_stop_signal);
}
const CancelFlag& InterruptGuard::cancel_flag() { return cancel_requested; }
bool InterruptGuard::interrupted() { return cancel_requested.load(); }

std::string InterruptGuard::reason() {
    const int own = received_signal.load();
    if (own == 0 && peer_signal.load() != 0) return fmt::format("stopped ({} to process {} of the job)", signal_name(peer_signal.load()), peer_rank.load());
    return own == 0 || own == SIGINT ? std::string("interrupted") : "stopped (" + signal_name(own) + ")";
}

int InterruptGuard::exit_code() {
    const int signal = received_signal.load() != 0 ? received_signal.load() : peer_signal.load();
    return 128 + (signal != 0 ? signal : SIGINT);
}

int InterruptGuard::own_signal() { return received_signal.load(); }

void InterruptGuard::stop_by_peer(int signal, std::size_t rank) {
    peer_rank.store(rank);
    peer_signal.store(signal);
    cancel_requested.store(true);
}

}  // namespace skinspec::cli
