#pragma once
// What a finished benchmark says beyond its points (skinspec bench, skinspec.bench; docs/PERFORMANCE.md): each
// case's points in order, its Pareto front, the walks' error slopes, the fastest solver within a tolerance; and the
// whole report as the JSON the command writes and the Python function returns, declared once here.
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "studies/benchmark/error_fits.hpp"
#include "studies/benchmark/runtime_benchmark.hpp"

namespace skinspec {

bool is_walk(BenchSolver s);

// The points of one case (indices into report.points).
std::vector<std::size_t> points_of(const BenchReport& report, std::size_t case_index);

struct CaseSummary {
    std::vector<bool> pareto;  // per point of the case
    struct WalkSlopes {
        BenchSolver solver;
        std::optional<PowerLawFit> against_time, against_rays;
    };
    std::vector<WalkSlopes> slopes;
    std::optional<std::size_t> fastest;  // point index meeting the tolerance
};

// Walk slopes use the points whose error is resolved (above twice the reference's floor).
CaseSummary summarise(const BenchReport& report, std::size_t case_index, double tolerance);

// The run's settings the report records.
struct BenchReportSettings {
    bool quick = false;
    std::uint64_t seed = 1;
    double tolerance_percent = 1.0;
};

nlohmann::ordered_json bench_report_json(const BenchReport& report, const BenchReportSettings& settings);

}  // namespace skinspec
