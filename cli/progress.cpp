#include "cli/progress.hpp"

#include <csignal>
#include <cstdio>
#include <unistd.h>

#include <fmt/format.h>

namespace skinspec::cli {
namespace {

CancelFlag cancel_requested{false};

extern "C" void on_interrupt(int) {
    if (cancel_requested.load()) _exit(130);
    cancel_requested.store(true);
}

}  // namespace

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
    if (drawn_) std::fputs("\r\033[K", stderr);
}

void ProgressBar::operator()(const Progress& p) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - last_ < std::chrono::milliseconds(100) && p.wavelengths_done < p.wavelengths_total) return;
    last_ = now;
    drawn_ = true;
    const std::size_t width = 30;
    const auto filled = p.wavelengths_total ? width * p.wavelengths_done / p.wavelengths_total : width;
    std::fputs(fmt::format("\r\033[K{} [{}{}] {}/{} wavelengths, {:.3g} rays{}", label_, std::string(filled, '#'),
                           std::string(width - filled, '.'), p.wavelengths_done, p.wavelengths_total,
                           static_cast<double>(p.rays_done), cancel_requested ? " (stopping)" : "")
                   .c_str(),
               stderr);
}

InterruptGuard::InterruptGuard() { std::signal(SIGINT, on_interrupt); }
InterruptGuard::~InterruptGuard() { std::signal(SIGINT, SIG_DFL); }
const CancelFlag& InterruptGuard::cancel_flag() { return cancel_requested; }
bool InterruptGuard::interrupted() { return cancel_requested.load(); }

}  // namespace skinspec::cli
