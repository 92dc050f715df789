#include "transport/time_left.hpp"

#include <algorithm>
#include <cmath>

namespace skinspec {

double work_share(const Progress& p) {
    if (p.wavelengths_total == 0) return 1.0;
    const double total = static_cast<double>(p.wavelengths_total);
    const double finished = static_cast<double>(p.wavelengths_done) / total;
    if (p.rays_expected == 0 || p.rays_done == 0) return finished;
    const double by_rays = static_cast<double>(p.rays_done) / static_cast<double>(p.rays_expected);
    const double in_progress = static_cast<double>(std::max<std::size_t>(1, p.wavelengths_in_progress)) / total;
    return std::clamp(by_rays, finished, std::min(1.0, finished + in_progress));
}

std::optional<double> TimeLeft::update(double elapsed_s, double share) {
    share_ = std::max(share_, std::clamp(share, 0.0, 1.0));
    if (!rate_from_ && share_ > 0.0 && elapsed_s > startup_s) rate_from_ = std::pair{elapsed_s, share_};
    const bool measured = rate_from_ && share_ > rate_from_->second &&
                          ((elapsed_s - rate_from_->first >= min_window_s && share_ - rate_from_->second >= min_share_step) ||
                           elapsed_s - rate_from_->first >= long_window_s);
    if (!measured) {
        if (!last_) return std::nullopt;
        return std::max(0.0, last_->second - (elapsed_s - last_->first));  // the last estimate, counted down
    }
    const double fresh = (1.0 - share_) * (elapsed_s - rate_from_->first) / (share_ - rate_from_->second);
    double blended = fresh;
    if (last_) {
        // Blended as logarithms: a wild early estimate (a share that had barely moved) fades within seconds.
        const double since = elapsed_s - last_->first, weight = 1.0 - std::exp(-since / smoothing_s);
        const double counted_down = std::max(1e-3, last_->second - since);
        blended = std::exp(weight * std::log(std::max(1e-3, fresh)) + (1.0 - weight) * std::log(counted_down));
    }
    const double left = share_ >= 1.0 ? 0.0 : blended;
    last_ = std::pair{elapsed_s, left};
    return left;
}

}  // namespace skinspec
