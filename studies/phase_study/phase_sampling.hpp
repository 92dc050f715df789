#pragma once
// The sampling experiments of Baranoski et al. 2005 Sec. 4-5: polar angles drawn by HG warping (Eq. 5) or by the
// randomized table look-up, binned into the 13 goniometer bins (samples beyond 62.5 deg discarded and the
// rest renormalised, as the measurements stop there), relative errors against the measured fractions
// (Table 3), and the BTDF of the virtual goniometer (Eq. 10).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "materials/measured_profile.hpp"
#include "transport/random_stream.hpp"

namespace skinspec {

// Draws one polar angle in degrees.
using AngleSampler = std::function<double(RandomStream&)>;

AngleSampler hg_angle_sampler(double g);
// Keeps a copy of the table.
AngleSampler table_angle_sampler(InverseCdfTable table);

struct BinnedSamples {
    std::vector<double> fractions;  // per bin, renormalised over the kept samples
    std::uint64_t kept = 0;         // samples within the last bin edge
    std::uint64_t drawn = 0;
};
BinnedSamples bin_samples(const AngleSampler& sampler, std::span<const double> bin_edges_deg, std::uint64_t n,
                          std::uint64_t seed, double stream_key);

struct RelativeErrors {
    double max_percent = 0.0;
    double average_percent = 0.0;
};
// |F_sim(i) - F_meas(i)| / F_meas(i) over the bins, in percent (Table 3).
RelativeErrors relative_errors(std::span<const double> simulated, std::span<const double> measured);

// Eq. 10: f_i = F_i / (delta omega_i cos theta_i), delta omega_i = 2 pi (cos lo - cos hi), theta_i the bin centre.
std::vector<double> goniometer_btdf_per_sr(std::span<const double> fractions, std::span<const double> bin_edges_deg);

// Seconds per sample, timed over n draws of each sampler in turn in one call.
std::vector<double> seconds_per_sample(const std::vector<AngleSampler>& samplers, std::uint64_t n);

}  // namespace skinspec
