#include "cli/stress_command.hpp"

#include <iostream>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "cli/common_options.hpp"
#include "cli/progress.hpp"
#include "studies/benchmark/stress_grid.hpp"

namespace skinspec::cli {
namespace {

struct StressCommandOptions {
    bool full = false;
    bool verbose = false;
    std::uint64_t seed = 1;
    double max_seconds = 60.0;
};

int run_stress(const StressCommandOptions& o) {
    const InterruptGuard interrupt;
    StressOptions options;
    options.full = o.full;
    options.seed = o.seed;
    options.max_seconds_per_case = o.max_seconds;
    options.cancel = &InterruptGuard::cancel_flag();
    std::size_t done = 0;
    options.on_case = [&](const StressOutcome& c) {
        ++done;
        if (!c.passed) std::cout << fmt::format("FAIL  {:<21} {}: {}\n", c.solver, c.name, c.failure);
        else if (o.verbose || !c.limit.empty()) std::cout << fmt::format("{}  {:<21} {} ({:.3f} s){}\n", c.limit.empty() ? "ok   " : "limit", c.solver, c.name, c.seconds, c.limit.empty() ? "" : ": " + c.limit);
        if (done % 50 == 0) std::cerr << "stress: " << done << " cases\n";
    };
    const auto report = run_stress_grid(options);
    std::map<std::string, std::array<std::size_t, 3>> per_solver;  // cases, failures, limits
    double slowest = 0.0;
    for (const auto& c : report.outcomes) {
        auto& s = per_solver[c.solver];
        ++s[0];
        s[1] += c.passed ? 0 : 1;
        s[2] += c.limit.empty() ? 0 : 1;
        slowest = std::max(slowest, c.seconds);
    }
    std::cout << fmt::format("\nstress grid ({}), seed {}:\n", o.full ? "full" : "short", o.seed);
    for (const auto& [solver, s] : per_solver) std::cout << fmt::format("  {:<21} {:>4} cases, {} failed, {} met a documented limit\n", solver, s[0], s[1], s[2]);
    std::cout << fmt::format("  {} cases, {} failed; slowest case {:.2f} s (bound {:g} s){}\n", report.outcomes.size(), report.failures(), slowest, o.max_seconds,
                             report.partial ? "; stopped early" : "");
    // A stop is no pass: the cases not run were not checked (the shell's code for the signal, as every command).
    if (report.partial) {
        std::cerr << "skinspec: " << InterruptGuard::reason() << ": " << report.outcomes.size() << " cases checked before the stop\n";
        return InterruptGuard::exit_code();
    }
    return report.failures() == 0 ? 0 : 1;
}

}  // namespace

void add_stress_command(CLI::App& app) {
    auto o = std::make_shared<StressCommandOptions>();
    auto* cmd = app.add_subcommand("stress", "The stability suite: every solver over a grid of extremes (finite, in [0, 1], energy, order, time)");
    cmd->add_flag("--full", o->full, "The full grid (minutes); default the short one ctest runs");
    cmd->add_flag("--verbose", o->verbose, "A line for every case, not only failures and limits");
    add_seed_option(*cmd, o->seed, "Seed of the walks");
    cmd->add_option("--max-seconds", o->max_seconds, "Run-time bound per case")->capture_default_str()->check(CLI::Range(1e-3, 86400.0));
    cmd->callback([o] {
        const int status = run_stress(*o);
        if (status != 0) throw CLI::RuntimeError(status);
    });
}

}  // namespace skinspec::cli
