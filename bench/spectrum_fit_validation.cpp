// The synthetic round trip of skinspec fit-spectrum (docs/SPECTRUM_FIT.md). A long run, not a test.
// 50 skins drawn at random (melanosome fraction log-uniform in 0.005-0.2, papillary and reticular blood
// fraction log-uniform in 0.003-0.03, oxygen saturation uniform in 0.4-0.95); their spectra at 400-700 nm / 10 nm
// come from the BioSpec walk itself (its own paths, absorption replay, another seed, 100,000 rays per wavelength),
// plus Gaussian noise of standard deviation 0.005; then each is fitted (default settings: 20,000 traced rays per
// wavelength, seed 1). Reports, per parameter, how often the truth lies within 2 standard errors of the fit, how
// often all four do, the RMS and the fit time per spectrum.
// With "starts": the local minima study instead. Skins over wider ranges (melanosome fraction 0.002-0.3, blood
// 0.002-0.05 each, saturation 0.3-0.99; 50,000 rays per wavelength, seed 99), each fitted with 4, 8 and 16 local
// searches; counts the fits more than 5 % above the 16-start fit's RMS.
// Usage: skinspec_validate_spectrum_fit [cases] [noise] [starts]
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "bench/bench_timing.hpp"
#include "inverse/spectrum_fit/spectrum_fit.hpp"
#include "materials/material_file.hpp"
#include "transport/biospec/biospec_solver.hpp"
#include "transport/random_stream.hpp"

using namespace skinspec;

namespace {

struct Ranges {
    double melanin_lo, melanin_hi, blood_lo, blood_hi, saturation_lo, saturation_hi;
};

// `cases` skins drawn from `random` over `ranges` (log-uniform fractions, uniform saturation) and their measured
// spectra: the BioSpec walk's (replayed, its own seed) plus Gaussian noise.
std::vector<std::vector<double>> synthetic_spectra(const LayerStack& base, const std::vector<double>& nm, std::size_t cases, const Ranges& ranges,
                                                   std::uint64_t rays, std::uint64_t seed, double noise, RandomStream& random,
                                                   std::vector<std::vector<double>>& truths) {
    const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, random.uniform()); };
    std::vector<LayerStack> stacks;
    for (std::size_t c = 0; c < cases; ++c) {
        const std::vector<double> t{log_uniform(ranges.melanin_lo, ranges.melanin_hi), log_uniform(ranges.blood_lo, ranges.blood_hi),
                                    log_uniform(ranges.blood_lo, ranges.blood_hi),
                                    ranges.saturation_lo + (ranges.saturation_hi - ranges.saturation_lo) * random.uniform()};
        auto s = base;
        s.name = fmt::format("case{}", c);
        s.layers[1].melanosome_fraction = t[0];
        s.layers[2].blood_fraction = t[1];
        s.layers[3].blood_fraction = t[2];
        s.layers[2].oxygen_saturation = s.layers[3].oxygen_saturation = t[3];
        truths.push_back(t);
        stacks.push_back(std::move(s));
    }
    const auto forward_start = std::chrono::steady_clock::now();
    SpectralRequest request;
    request.wavelengths = WavelengthGrid::list(nm);
    request.max_rays_per_wavelength = rays;
    request.seed = seed;
    std::vector<const LayerStack*> sets;
    for (const auto& s : stacks) sets.push_back(&s);
    const auto forward = solve_biospec_sets(sets, request);
    fmt::print("forward spectra: {} skins x {} wavelengths by the BioSpec walk (replayed) in {:.1f} s\n", cases, nm.size(),
               bench::seconds_since(forward_start));
    std::vector<std::vector<double>> measured(cases);
    for (std::size_t c = 0; c < cases; ++c) {
        for (const auto& w : forward[c].wavelengths) {
            const double g = std::sqrt(-2.0 * std::log(1.0 - random.uniform())) * std::cos(2.0 * std::numbers::pi * random.uniform());
            measured[c].push_back(w.reflectance.value + noise * g);
        }
    }
    return measured;
}

// Each spectrum fitted with 4, 8 and 16 local searches: how often fewer starts stop in a poorer minimum.
void starts_study(const LayerStack& base, const std::vector<double>& nm, const std::vector<std::vector<double>>& measured) {
    const std::vector<std::size_t> starts{4, 8, 16};
    std::vector<std::vector<double>> rms(starts.size(), std::vector<double>(measured.size()));
    std::vector<double> seconds(starts.size());
    for (std::size_t s = 0; s < starts.size(); ++s) {
        SpectrumFitSettings settings;
        settings.free = default_free_parameters();
        settings.starts = starts[s];
        const SpectrumFitter fitter(base, nm, settings);
        const auto start = std::chrono::steady_clock::now();
        tbb::parallel_for(std::size_t{0}, measured.size(), [&](std::size_t c) { rms[s][c] = fitter.fit(fmt::format("case{}", c), measured[c]).rms; });
        seconds[s] = bench::seconds_since(start);
    }
    for (std::size_t s = 0; s < starts.size(); ++s) {
        std::size_t poorer = 0;
        double worst = 1.0;
        for (std::size_t c = 0; c < measured.size(); ++c) {
            const double ratio = rms[s][c] / rms.back()[c];
            poorer += ratio > 1.05 ? 1 : 0;
            worst = std::max(worst, ratio);
        }
        fmt::print("starts {:2}: {} fits in {:.2f} s (2 threads); RMS more than 5 % above the 16-start fit's: {} (worst {:.3f}x)\n", starts[s],
                   measured.size(), seconds[s], poorer, worst);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const std::size_t cases = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 50;
    const double noise = argc > 2 ? std::strtod(argv[2], nullptr) : 0.005;
    const bool study_starts = argc > 3 && std::string_view(argv[3]) == "starts";
    const auto base = std::get<LayerStack>(load_material("biospec-moderately"));
    std::vector<double> nm;
    for (double w = 400.0; w <= 700.0; w += 10.0) nm.push_back(w);
    std::vector<std::vector<double>> truths;
    if (study_starts) {
        auto random = RandomStream::for_batch(4242, 0.0, 17);
        starts_study(base, nm, synthetic_spectra(base, nm, cases, {0.002, 0.3, 0.002, 0.05, 0.3, 0.99}, 50'000, 99, noise, random, truths));
        return 0;
    }
    auto random = RandomStream::for_batch(2026, 0.0, 17);
    const auto measured = synthetic_spectra(base, nm, cases, {0.005, 0.2, 0.003, 0.03, 0.4, 0.95}, 100'000, 777, noise, random, truths);

    const auto fit_start = std::chrono::steady_clock::now();
    SpectrumFitSettings settings;
    settings.free = default_free_parameters();
    const SpectrumFitter fitter(base, nm, settings);
    const double trace_seconds = bench::seconds_since(fit_start);
    std::vector<SpectrumFit> fits(cases);
    tbb::parallel_for(std::size_t{0}, cases, [&](std::size_t c) { fits[c] = fitter.fit(fmt::format("case{}", c), measured[c]); });
    const double fit_seconds = bench::seconds_since(fit_start) - trace_seconds;

    const auto& keys = fitter.keys();
    std::vector<std::size_t> inside(keys.size(), 0);
    std::size_t all_inside = 0;
    double rms_sum = 0.0, seconds_sum = 0.0;
    for (std::size_t c = 0; c < cases; ++c) {
        bool all = true;
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const bool ok = std::abs(fits[c].parameters[i] - truths[c][i]) <= 2.0 * fits[c].parameter_stderr[i];
            inside[i] += ok;
            all = all && ok;
        }
        all_inside += all;
        rms_sum += fits[c].rms;
        seconds_sum += fits[c].seconds;
    }
    fmt::print("fits: paths traced in {:.2f} s, {} spectra fitted in {:.2f} s (2 threads); {:.2f} s per spectrum on one core\n", trace_seconds,
               cases, fit_seconds, seconds_sum / static_cast<double>(cases));
    fmt::print("noise {:g}: mean RMS {:.4f} (noise alone: {:.4f})\n", noise, rms_sum / static_cast<double>(cases), noise);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        fmt::print("  {:<34} truth within 2 standard errors in {:2} of {} cases ({:.0f} %)\n", keys[i], inside[i], cases,
                   100.0 * static_cast<double>(inside[i]) / static_cast<double>(cases));
    }
    fmt::print("  all four within 2 standard errors in {} of {} cases ({:.0f} %)\n", all_inside, cases,
               100.0 * static_cast<double>(all_inside) / static_cast<double>(cases));
    return 0;
}
