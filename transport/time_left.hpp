#pragma once
// The time a run has left, from the share of its work done as it goes: what a progress display shows. The rate is
// measured from the first report after start-up (tables, paths and each wavelength's first batches made early
// estimates swing from 46 h to 1 min for one 12.5 s run); the share never goes back (a planner's re-estimate of a
// wavelength's rays moved it both ways); and each new estimate is blended with the previous one counted down, with
// a time constant of `smoothing_s`, so that the figure moves smoothly ("14 s left" and "1 min 50 s left"
// alternated between wavelengths).
#include <optional>
#include <utility>

#include "transport/spectral_request.hpp"

namespace skinspec {

// The share of a request's work done: its finished units (wavelengths, patches), and within the units in progress
// the rays against the planner's estimate, kept between the units finished and those plus the ones in progress (an
// estimate from a unit's first batch, applied to the units to come, put the share near 1 at the second of 31; the
// walks trace every wavelength of a round at once, and a cap of one unit held their share at 1/11 to the end, the
// estimate rising to 8 min for a 6 s run).
double work_share(const Progress& progress);

class TimeLeft {
public:
    // `elapsed_s` since the start, `share` of the work done in [0, 1]; the seconds left once they can be
    // estimated (a share grown by at least `min_share_step` over at least `min_window_s` after start-up, or by any
    // amount over `long_window_s`: a budget so large that a second moves its share by 1e-9 is still estimated),
    // else nothing; afterwards the last estimate counted down while the share stands still.
    std::optional<double> update(double elapsed_s, double share);

    static constexpr double startup_s = 0.5, min_window_s = 1.0, min_share_step = 1e-3, long_window_s = 5.0;
    static constexpr double smoothing_s = 3.0;

private:
    double share_ = 0.0;
    std::optional<std::pair<double, double>> rate_from_;  // (seconds, share done) where the rate is measured from
    std::optional<std::pair<double, double>> last_;       // (seconds, estimate) shown last
};

}  // namespace skinspec
