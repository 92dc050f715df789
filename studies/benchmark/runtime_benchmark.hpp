#pragma once
// Run time against error for every solver (skinspec bench, docs/PERFORMANCE.md). Fixed cases, each with an
// independent reference:
//   - three adding-doubling slabs (data/reference, Prahl, ~1e-3 relative): Rd by the volumetric walk, the
//     multipole (the finite slab) and the dipole (semi-infinite);
//   - the lightly/moderately/heavily pigmented presets at 550 nm: R by the BioSpec walk against a long BioSpec
//     run with a different seed (its standard error is stated), and by both diffusion modes;
//   - Jensen's skin1 (G band) as `spectrum --mode rte` walks it (rte_band_slab): R by the volumetric walk against a
//     long walk, and diffusion;
//   - one skin in every mode: each pigmentation preset's 31-wavelength spectrum (400-700 nm) by every solver on one
//     thread against the exact solution of its description (biospec-adding-doubling for the BioSpec walk,
//     adding-doubling for the mu_a, mu_s, phase solvers), the two descriptions against each other, and the
//     volumetric walk against adding-doubling in standard errors at 550 nm (1e7 photons);
//   - the diffusion solvers' R(r) against the volumetric walk's (1e7 photons) at 450, 550 and 650 nm.
// The walks sweep their ray budget (several seeds per budget, RMS relative error); diffusion has no budget
// for totals (closed form), so it gives one point whose error is the model's. The multipole profile's pair
// tolerance is swept separately against the fully converged image series. Also: thread scaling 1 -> 2 and
// the time per colour (one swatch patch at Delta E <= 0.3).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "transport/spectral_request.hpp"

namespace skinspec {

enum class BenchSolver { biospec_walk, volumetric_walk, dipole, multipole, adding_doubling };
std::string_view to_string(BenchSolver solver);

struct BenchCase {
    std::string name;
    std::string quantity;           // "Rd" (specular excluded) or "R" (total)
    Estimate reference;             // stderr 0 for a tabulated reference
    double resolvable_error = 0.0;  // relative errors below this are not resolved by the reference
    std::string reference_source;
    double reference_seconds = 0.0;  // time of the long reference run (0 for tables)
};

struct BenchPoint {
    std::size_t case_index = 0;
    BenchSolver solver = BenchSolver::biospec_walk;
    std::uint64_t rays = 0;      // the walks' budget per run (0: deterministic)
    int repetitions = 1;         // runs with different seeds
    double seconds = 0.0;        // mean wall time per run, all threads
    Estimate value;              // the first run's value (stderr 0 for diffusion)
    double relative_error = 0.0; // RMS over the runs of (value - reference) / reference
    std::string note;            // e.g. the diffusion trust warnings
};

struct PairSweepPoint {
    double tolerance = 0.0;
    std::size_t pairs = 0;       // most pairs any radius needed
    double seconds = 0.0;        // one profile of `radii` radii
    double max_relative_error = 0.0;
};

struct ThreadScaling {
    BenchSolver solver = BenchSolver::biospec_walk;
    std::string workload;
    std::uint64_t rays = 0;
    double seconds_one_thread = 0.0;
    double seconds_two_threads = 0.0;
};

struct ColourTiming {
    std::string material;
    double seconds = 0.0;
    std::uint64_t rays = 0;
    double delta_e_uncertainty = 0.0;
    bool converged = true;
};

// One preset's spectrum (400-700 nm / 10 nm, SCI) by one solver, against the exact solution of its description.
// The row of adding-doubling on a preset's own volumetric description (its layers' fields, not the one derived from
// the BioSpec description): the gap between the two descriptions, which the derived one closes.
inline constexpr std::string_view own_description_row = "adding-doubling, own description";

struct SkinModeRow {
    std::string material;
    std::string solver;                 // registry name, or own_description_row
    std::string reference;              // biospec-adding-doubling (the BioSpec description; for adding-doubling: the
                                        // derived description's miss, for own_description_row the gap between the
                                        // descriptions) or adding-doubling (the volumetric one); itself: none
    double seconds_one_thread = 0.0;    // the whole spectrum
    std::uint64_t rays = 0;             // walks: over all wavelengths
    double uncertainty = 0.0;           // walks: largest standard error of R; adding-doubling: its stated accuracy
    double max_abs_error = 0.0;         // largest |R - R_reference|
    double min_relative_diffuse_error = 0.0;  // range of (Rd - Rd_ref) / Rd_ref, Rd = R - R_specular
    double max_relative_diffuse_error = 0.0;
    double delta_e_ab = 0.0;            // CIELAB (D65, CIE 1931 2 deg) against the reference
    double delta_e2000 = 0.0;           // CIEDE2000, the same colours
    std::optional<double> stated_delta_e2000;  // the solver's own statement of its colour error (diffusion)
};

// The volumetric walk against adding-doubling on a preset at one wavelength.
struct WalkAgreement {
    std::string material;
    double wavelength_nm = 0.0;
    std::uint64_t photons = 0;
    Estimate walk;                      // R (SCI)
    double adding_doubling = 0.0;       // default channels
    double adding_doubling_accuracy = 0.0;  // its stated accuracy
    std::size_t fine_channels = 0;
    double adding_doubling_fine = 0.0;  // with fine_channels
    double seconds = 0.0;               // the walk, all threads
};

// A deterministic solver's radial profile R(r) against the volumetric walk's (rings, 0-5 mm) on a preset at one
// wavelength, over 0.05-5 mm where the walk's standard error is below 5 % (issue 31's target: within 15 %).
struct ProfileAgreement {
    std::string material;
    double wavelength_nm = 0.0;
    std::string solver;
    std::uint64_t photons = 0;
    std::size_t radii = 0;              // compared
    double share_within_15_percent = 0.0;
    double worst_relative_error = 0.0;  // signed, largest in size
    double relative_error_at_0_1_mm = 0.0;
    double median_relative_error_1_to_5_mm = 0.0;
    double walk_seconds = 0.0;
};

// A lit swatch (spot of 2 mm radius, 20 mm field, 256 x 256 px, 400-700 nm / 10 nm) by the exact transport at its
// default precision and by matched-multipole, run side by side (docs/PROFILES.md).
struct LitSwatchTiming {
    std::string material;
    double exact_seconds = 0.0;       // rte, default precision (all threads)
    double diffusion_seconds = 0.0;   // matched-multipole
    std::uint64_t photons = 0;        // the walk's, all wavelengths
    double within_radius_stderr = 0.0;  // the walk's largest standard error of R within a radius
    bool converged = true;
};

struct ProfileGridTiming {
    std::string material;
    std::size_t members = 0;
    double one_member_seconds = 0.0;  // profiles (default precision, 380-780 nm / 10 nm, 0-10 mm) and the Gaussian fit
    double grid_seconds = 0.0;        // every member's, one set of variances
    std::uint64_t photons = 0;        // the grid's walk, most per wavelength
    double within_radius_stderr = 0.0;  // the largest over members and wavelengths
    double worst_profile_error = 0.0;   // the fit's relative L2 error, worst member and channel
};

struct BenchOptions {
    bool quick = false;                        // under a minute: fewer budgets, seeds and a shorter reference
    std::uint64_t seed = 1;                    // runs use seed, seed + 1, ...
    std::uint64_t reference_seed = 1'000'003;  // the long reference runs: a different stream
    std::function<void(const std::string& stage)> on_stage;
    const CancelFlag* cancel = nullptr;
};

struct BenchReport {
    std::vector<BenchCase> cases;
    std::vector<BenchPoint> points;
    std::size_t pair_sweep_radii = 0;
    std::vector<PairSweepPoint> pair_sweep;
    std::vector<ThreadScaling> scaling;
    std::vector<ColourTiming> colours;
    std::vector<SkinModeRow> skin_modes;
    std::vector<WalkAgreement> walk_agreement;
    std::vector<ProfileAgreement> profile_agreement;
    std::vector<LitSwatchTiming> lit_swatches;
    std::vector<ProfileGridTiming> profile_grids;
    bool partial = false;  // stopped by the cancel flag: what was finished is kept
};

BenchReport run_benchmark(const BenchOptions& options);

}  // namespace skinspec
