#include "studies/benchmark/stress_grid.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <variant>

#include <fmt/format.h>

#include "solvers/spectral_solver.hpp"
#include "transport/diffusion/diffusion_model.hpp"
#include "transport/diffusion/dipole.hpp"
#include "transport/diffusion/multipole.hpp"
#include "transport/adding_doubling/adding_doubling.hpp"
#include "materials/measured_profile.hpp"
#include "transport/rte/rte_model.hpp"
#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

std::size_t StressReport::failures() const {
    std::size_t n = 0;
    for (const auto& o : outcomes) n += o.passed ? 0 : 1;
    return n;
}

std::size_t StressReport::limits() const {
    std::size_t n = 0;
    for (const auto& o : outcomes) n += o.limit.empty() ? 0 : 1;
    return n;
}

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double energy_tolerance = 1e-9;

struct Stopped {};

// The assertions of one case; every problem is kept, the first is reported.
class Checks {
public:
    void unit(const std::string& what, double v) {
        if (!std::isfinite(v)) fail(fmt::format("{} = {} is not finite", what, v));
        else if (v < -1e-12 || v > 1.0 + 1e-12) fail(fmt::format("{} = {:.17g} is outside [0, 1]", what, v));
    }
    // A Monte Carlo estimate of a fraction: finite, and within 4.5 standard errors of [0, 1]. An unbiased estimator that
    // conserves each ray's energy exactly (roulette survivors repay their boost from the layer they are in) can fall
    // below 0 by its noise where the true value is ~0; such a case is reported as a limit, not hidden.
    void statistical_unit(const std::string& what, const Estimate& e) {
        if (!std::isfinite(e.value) || !std::isfinite(e.stderr)) return fail(fmt::format("{} = {} +- {} is not finite", what, e.value, e.stderr));
        const double slack = 4.5 * e.stderr + 1e-12;
        if (e.value < -slack || e.value > 1.0 + slack) fail(fmt::format("{} = {:.17g} +- {:.3g} is outside [0, 1] by more than 4.5 sigma", what, e.value, e.stderr));
        else if (e.value < 0.0 || e.value > 1.0) limit = fmt::format("{} = {:.3g} +- {:.3g}: outside [0, 1] within its noise", what, e.value, e.stderr);
    }
    void estimate(const std::string& what, const Estimate& e) {
        unit(what, e.value);
        if (!std::isfinite(e.stderr) || e.stderr < 0.0) fail(fmt::format("{} standard error = {} is not finite and >= 0", what, e.stderr));
    }
    void finite(const std::string& what, double v) {
        if (!std::isfinite(v)) fail(fmt::format("{} = {} is not finite", what, v));
    }
    void non_negative(const std::string& what, double v) {
        if (!std::isfinite(v) || v < 0.0) fail(fmt::format("{} = {} is not finite and >= 0", what, v));
    }
    void energy(double sum, double tolerance = energy_tolerance) {
        if (!(std::abs(sum - 1.0) <= tolerance)) fail(fmt::format("energy: R + T + A = {:.17g} (allowed 1 +- {:g})", sum, tolerance));
    }
    void expect(bool condition, const std::string& what) {
        if (!condition) fail(what);
    }
    void fail(std::string what) {
        if (failure_.empty()) failure_ = std::move(what);
    }
    const std::string& failure() const { return failure_; }
    std::string limit;

private:
    std::string failure_;
};

class Grid {
public:
    explicit Grid(const StressOptions& options) : options_(options) {}

    // Runs one case: an InputError is a documented limit, any other exception a failure.
    void run(const std::string& solver, const std::string& name, const std::function<void(Checks&)>& body) {
        if (options_.cancel && options_.cancel->load()) throw Stopped{};
        Checks checks;
        const auto start = std::chrono::steady_clock::now();
        try {
            body(checks);
        } catch (const InputError& e) {
            checks.limit = e.what();
        } catch (const std::exception& e) {
            checks.fail(std::string("unexpected exception: ") + e.what());
        }
        StressOutcome o{solver, name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), true, checks.failure(), checks.limit};
        if (o.failure.empty() && o.seconds > options_.max_seconds_per_case) {
            o.failure = fmt::format("took {:.1f} s (bound {:g} s)", o.seconds, options_.max_seconds_per_case);
        }
        o.passed = o.failure.empty();
        if (options_.on_case) options_.on_case(o);
        report_.outcomes.push_back(std::move(o));
    }

    // An ordering physics requires, between two finished cases, within `slack`.
    void order(const std::string& solver, const std::string& name, double smaller, double larger, double slack) {
        run(solver, name, [&](Checks& c) {
            c.expect(smaller <= larger + slack, fmt::format("expected {:.9g} <= {:.9g} (slack {:.3g})", smaller, larger, slack));
        });
    }

    const StressOptions& options() const { return options_; }
    StressReport& report() { return report_; }

private:
    StressOptions options_;
    StressReport report_;
};

// The volumetric walk: one slab, HG phase function.
void rte_cases(Grid& grid) {
    const bool full = grid.options().full;
    const std::vector<double> gs = full ? std::vector<double>{-0.99, 0.0, 0.9, 0.999} : std::vector<double>{0.0, 0.999};
    const std::vector<double> albedos = full ? std::vector<double>{0.0, 0.5, 0.99, 1.0} : std::vector<double>{0.0, 0.99, 1.0};
    const std::vector<double> depths = full ? std::vector<double>{1e-6, 1.0, 30.0} : std::vector<double>{1e-6, 30.0};
    const std::vector<double> indices = full ? std::vector<double>{1.0, 1.4, 4.0} : std::vector<double>{1.0, 4.0};
    const std::vector<double> incidences = full ? std::vector<double>{0.0, 60.0, 89.9} : std::vector<double>{0.0, 89.9};
    const std::uint64_t photons = full ? 4000 : 1000;
    for (const double g : gs) {
        for (const double b : depths) {
            for (const double n : indices) {
                for (const double incidence : incidences) {
                    Estimate previous{-1.0, 0.0};
                    for (const double a : albedos) {
                        const auto name = fmt::format("g {:g}, albedo {:g}, optical thickness {:g}, n {:g}, incidence {:g} deg", g, a, b, n, incidence);
                        Estimate reflected{};
                        grid.run("rte", name, [&](Checks& c) {
                            RteRequest request;
                            const double d = 0.1, mu_t = b / d;
                            request.stack.layers.push_back({n, mu_t * (1.0 - a), mu_t * a, d, PhaseFunction::henyey_greenstein(g)});
                            request.photons = photons;
                            request.seed = grid.options().seed;
                            request.incidence_deg = incidence;
                            request.max_steps_per_photon = 1'000'000;
                            request.cancel = grid.options().cancel;
                            const auto r = solve_rte(request);
                            c.estimate("R_specular", r.specular_reflectance);
                            c.estimate("R_diffuse", r.diffuse_reflectance);
                            c.estimate("T", r.transmittance);
                            c.estimate("A", r.absorbed);
                            c.energy(r.specular_reflectance.value + r.diffuse_reflectance.value + r.transmittance.value + r.absorbed.value);
                            if (a == 1.0) c.expect(r.absorbed.value == 0.0 || r.truncated_photons > 0, "albedo 1 but A > 0");
                            if (a == 0.0 && n == 1.0) {
                                // Beer-Lambert along the slanted path (no refraction at n = 1).
                                // 4 standard errors of the binomial count at the expected fraction.
                                const double expected = std::exp(-b / std::cos(incidence * std::acos(-1.0) / 180.0));
                                const double spread = std::sqrt(expected * (1.0 - expected) / static_cast<double>(photons));
                                c.expect(std::abs(r.transmittance.value - expected) <= 4.0 * spread + 1e-12,
                                         fmt::format("T = {:.6g} +- {:.2g}, Beer-Lambert {:.6g}", r.transmittance.value, r.transmittance.stderr, expected));
                            }
                            if (r.truncated_photons > 0) c.limit = fmt::format("{} photon(s) stopped at the step limit (weight counted as absorbed)", r.truncated_photons);
                            reflected = {r.specular_reflectance.value + r.diffuse_reflectance.value, r.diffuse_reflectance.stderr};
                        });
                        if (previous.value >= 0.0 && reflected.value > 0.0) {
                            grid.order("rte", name + ": R does not fall as albedo rises", previous.value, reflected.value,
                                       4.0 * std::hypot(previous.stderr, reflected.stderr) + 1e-12);
                        }
                        previous = reflected;
                    }
                }
            }
        }
    }
}

// Adding-doubling: one slab, HG phase functions up to g 0.999 and the measured stratum-corneum forward peak.
// Deterministic: energy to 5e-8 (roundoff of ~30 doublings of a conservative 1000-mfp layer from a grazing beam's
// thin start, where 1 - R R is nearly singular; 1e-9 elsewhere in practice), Beer-Lambert to 1e-5 relative.
void adding_doubling_cases(Grid& grid) {
    const bool full = grid.options().full;
    const auto peak = std::make_shared<const InverseCdfTable>(MeasuredProfile::stratum_corneum().inverse_table(302.0));
    std::vector<std::pair<std::string, PhaseFunction>> phases{{"g 0", PhaseFunction::henyey_greenstein(0.0)},
                                                              {"g 0.999", PhaseFunction::henyey_greenstein(0.999)},
                                                              {"stratum corneum profile", {PhaseFunction::Kind::tabulated, peak->mean_cos(), 0.0, 1.0, peak}}};
    if (full) {
        phases.insert(phases.begin(), {"g -0.99", PhaseFunction::henyey_greenstein(-0.99)});
        phases.insert(phases.begin() + 2, {"g 0.9", PhaseFunction::henyey_greenstein(0.9)});
    }
    const std::vector<double> albedos = full ? std::vector<double>{0.0, 0.5, 0.99, 1.0} : std::vector<double>{0.0, 0.99, 1.0};
    const std::vector<double> depths = full ? std::vector<double>{1e-6, 1e-2, 1.0, 30.0, 1e3} : std::vector<double>{1e-6, 30.0, 1e3};
    const std::vector<double> indices = full ? std::vector<double>{1.0, 1.4, 2.0, 4.0} : std::vector<double>{1.0, 2.0};
    const std::vector<double> incidences = full ? std::vector<double>{0.0, 60.0, 89.9} : std::vector<double>{0.0, 89.9};
    for (const auto& entry : phases) {
        const auto& phase_name = entry.first;
        const auto& phase = entry.second;  // a named variable: lambdas below capture it (clang 14: not a structured binding)
        for (const double b : depths) {
            for (const double n : indices) {
                for (const double incidence : incidences) {
                    double previous = -1.0;
                    for (const double a : albedos) {
                        const auto name = fmt::format("{}, albedo {:g}, optical thickness {:g}, n {:g}, incidence {:g} deg", phase_name, a, b, n, incidence);
                        double reflected = -1.0;
                        grid.run("adding-doubling", name, [&](Checks& c) {
                            RteStack stack;
                            const double d = 0.1, mu_t = b / d;
                            stack.layers.push_back({n, mu_t * (1.0 - a), mu_t * a, d, phase});
                            const auto r = solve_adding_doubling(stack, {false, incidence});
                            c.unit("R_specular", r.specular_reflectance);
                            c.unit("R_diffuse", r.diffuse_reflectance);
                            c.unit("T", r.transmittance);
                            c.unit("A", r.absorbed_layers.front());
                            c.non_negative("accuracy", r.accuracy);
                            c.energy(r.specular_reflectance + r.diffuse_reflectance + r.transmittance + r.absorbed_layers.front(), 5e-8);
                            if (a == 1.0) c.expect(std::abs(r.absorbed_layers.front()) <= 1e-8, fmt::format("albedo 1 but A = {:.3g}", r.absorbed_layers.front()));
                            if (a == 0.0 && n == 1.0) {
                                // Beer-Lambert along the slanted path (no refraction at n = 1); the diamond start's error
                                // in the exponent is b h^2 / (12 mu^3) (h <= 2^-8), 1e-5 relative allowed.
                                const double expected = std::exp(-b / std::cos(incidence * std::acos(-1.0) / 180.0));
                                c.expect(std::abs(r.transmittance - expected) <= 1e-5 * expected + 1e-12,
                                         fmt::format("T = {:.9g}, Beer-Lambert {:.9g}", r.transmittance, expected));
                            }
                            reflected = r.specular_reflectance + r.diffuse_reflectance;
                        });
                        if (previous >= 0.0 && reflected >= 0.0) grid.order("adding-doubling", name + ": R does not fall as albedo rises", previous, reflected, 1e-9);
                        previous = reflected;
                    }
                }
            }
        }
    }
}

// The BioSpec walk on the moderately pigmented preset with one field pushed to an extreme.
void biospec_cases(Grid& grid) {
    const bool full = grid.options().full;
    struct Variant {
        std::string name;
        std::vector<std::string> overrides;
        std::vector<double> wavelengths_nm;
        double incidence_deg;
        std::uint64_t rays;
    };
    const std::uint64_t rays = full ? 20'000 : 4'000;
    std::vector<Variant> variants{
        {"preset", {}, {250.0, 550.0, 1450.0, 2500.0}, 0.0, rays},
        {"no melanin", {"epidermis.melanosome_fraction=0"}, {450.0}, 0.0, rays},
        {"maximal melanin", {"epidermis.melanosome_fraction=0.5"}, {450.0}, 0.0, rays},
        {"no blood", {"dermis.blood_fraction=0"}, {420.0}, 0.0, rays},
        {"maximal blood", {"dermis.blood_fraction=1"}, {420.0}, 0.0, rays},
        {"no oxygen", {"dermis.oxygen_saturation=0"}, {560.0}, 0.0, rays},
        {"no carotene, bilirubin", {"stratum_corneum.carotene_g_per_l=0", "epidermis.carotene_g_per_l=0", "dermis.carotene_g_per_l=0", "dermis.bilirubin_g_per_l=0"}, {460.0}, 0.0, rays},
        {"grazing incidence", {}, {550.0}, 89.9, rays},
        {"index 1 everywhere", {"stratum_corneum.refractive_index=1", "epidermis.refractive_index=1", "dermis.refractive_index=1"}, {550.0}, 30.0, rays},
        {"index 4 epidermis", {"epidermis.refractive_index=4"}, {550.0}, 0.0, rays},
        {"stratum corneum 1 nm, large budget", {"stratum_corneum.thickness_cm=1e-7"}, {550.0}, 0.0, full ? std::uint64_t{2'000'000} : std::uint64_t{200'000}},
        {"reticular dermis 10 cm", {"reticular_dermis.thickness_cm=10"}, {650.0}, 0.0, rays},
        {"below the tables (240 nm)", {}, {240.0}, 0.0, rays},
        {"above the tables (2510 nm)", {}, {2510.0}, 0.0, rays},
    };
    std::map<std::string, double> r450;
    for (const bool reflector : {true, false}) {
        for (const auto& v : variants) {
            const auto name = fmt::format("{} ({}), {} nm, {} rays{}", v.name, reflector ? "hypodermis reflector" : "open bottom",
                                          fmt::join(v.wavelengths_nm, "/"), v.rays, v.incidence_deg > 0 ? fmt::format(", incidence {:g} deg", v.incidence_deg) : "");
            grid.run("biospec", name, [&](Checks& c) {
                std::vector<MaterialOverride> overrides;
                for (const auto& o : v.overrides) overrides.push_back(parse_override(o));
                if (!reflector) overrides.push_back(parse_override("bottom.boundary=exit"));
                const auto material = load_material("biospec-moderately", overrides);
                SolverRequest request;
                request.spectral.wavelengths = WavelengthGrid::list(v.wavelengths_nm);
                request.spectral.quantities = {true, true, true, false};
                request.spectral.incidence_deg = v.incidence_deg;
                request.spectral.max_rays_per_wavelength = v.rays;
                request.spectral.seed = grid.options().seed;
                request.spectral.cancel = grid.options().cancel;
                const auto result = solve_spectrum(find_solver("biospec"), material, request);
                for (const auto& w : result.wavelengths) {
                    const auto at = fmt::format(" at {:g} nm", w.wavelength_nm);
                    c.estimate("R" + at, w.reflectance);
                    c.estimate("T" + at, w.transmittance);
                    double sum = w.reflectance.value + w.transmittance.value + w.absorptance_surface.value;
                    for (std::size_t k = 0; k < w.absorptance_layers.size(); ++k) {
                        c.estimate(fmt::format("A_{}{}", result.layer_names[k], at), w.absorptance_layers[k]);
                        sum += w.absorptance_layers[k].value;
                    }
                    c.energy(sum);
                    if (w.truncated_rays > 0) c.limit = fmt::format("{} ray(s) stopped at the event limit", w.truncated_rays);
                }
                // A stopped walk may have finished no wavelength.
                if (reflector && v.wavelengths_nm == std::vector<double>{450.0} && !result.wavelengths.empty()) {
                    r450[v.name] = result.wavelengths.front().reflectance.value;
                }
            });
        }
    }
    if (r450.count("no melanin") && r450.count("maximal melanin")) {
        grid.order("biospec", "R at 450 nm: maximal melanin below no melanin", r450["maximal melanin"], r450["no melanin"], 0.0);
    }
}

// Diffusion: the multipole slab and the dipole over extreme coefficients and faces.
void diffusion_cases(Grid& grid) {
    const std::vector<double> scatterings{1e-9, 1.0, 1e6};
    const std::vector<double> absorptions{0.0, 1e-9, 1.0, 1e6};
    const std::vector<double> thicknesses{1e-9, 1.0, 1e3, inf};
    const std::vector<double> faces{0.0, 0.4, 0.999};
    const std::vector<double> radii{0.0, 1e-3, 1.0, 1e3};
    std::map<std::tuple<double, double, double, double>, std::pair<double, double>> totals;  // (s, a, d, F) -> (R, T)
    for (const double s : scatterings) {
        for (const double a : absorptions) {
            for (const double d : thicknesses) {
                for (const double f : faces) {
                    const auto name = fmt::format("sigma_s' {:g}, sigma_a {:g}, thickness {:g}, face reflectance {:g}", s, a, d, f);
                    grid.run("multipole", name, [&](Checks& c) {
                        const Multipole m({s, a, d, f, f});
                        const double r = m.total_reflectance(), t = m.total_transmittance();
                        c.unit("R", r);
                        c.unit("T", t);
                        c.expect(r + t <= 1.0 + energy_tolerance, fmt::format("R + T = {:.17g} > 1", r + t));
                        if (a == 0.0 && std::isfinite(d)) c.energy(r + t);
                        const auto profile = m.reflectance_profile(radii);
                        for (std::size_t i = 0; i < radii.size(); ++i) {
                            c.finite(fmt::format("R({:g})", radii[i]), profile.values[i]);
                            // The image series of a thin slab can dip below 0 (an artifact of the approximation, not
                            // of the summation; docs/STABILITY.md): reported, not hidden.
                            if (profile.values[i] < 0.0) c.limit = fmt::format("R({:g}) = {:.3g} < 0 (multipole approximation)", radii[i], profile.values[i]);
                        }
                        if (!profile.converged) c.limit = fmt::format("profile pairs capped at {}", Multipole::max_pairs);
                        totals[{s, a, d, f}] = {r, t};
                    });
                }
            }
        }
    }
    for (const auto& [key, rt] : totals) {
        const auto [s, a, d, f] = key;
        // More absorption, less reflection; a thicker slab, less transmission.
        const auto more_absorbing = totals.upper_bound({s, a, inf, inf});
        if (more_absorbing != totals.end() && std::get<0>(more_absorbing->first) == s) {
            const auto next = totals.find({s, std::get<1>(more_absorbing->first), d, f});
            if (next != totals.end()) {
                grid.order("multipole", fmt::format("sigma_s' {:g}, thickness {:g}, F {:g}: R falls from sigma_a {:g} to {:g}", s, d, f, a, std::get<1>(next->first)),
                           next->second.first, rt.first, 1e-12);
            }
        }
        const auto thicker = std::find(thicknesses.begin(), thicknesses.end(), d) + 1;
        if (thicker != thicknesses.end()) {
            const auto next = totals.find({s, a, *thicker, f});
            if (next != totals.end()) {
                grid.order("multipole", fmt::format("sigma_s' {:g}, sigma_a {:g}, F {:g}: T falls from thickness {:g} to {:g}", s, a, f, d, *thicker),
                           next->second.second, rt.second, 1e-12);
            }
        }
    }
    for (const double s : scatterings) {
        for (const double a : absorptions) {
            for (const double eta : {0.5, 1.0, 1.3, 4.0}) {
                grid.run("dipole", fmt::format("sigma_s' {:g}, sigma_a {:g}, eta {:g}", s, a, eta), [&](Checks& c) {
                    const Dipole dipole({s, a, eta, 0.9});
                    c.unit("R_d", dipole.total_reflectance());
                    for (const double r : radii) c.non_negative(fmt::format("R_d({:g})", r), dipole.radial_reflectance(r));
                    for (const double cosine : {1.0, 0.5, 1e-6}) c.non_negative(fmt::format("BRDF at cos {:g}", cosine), dipole.brdf(cosine, cosine, 180.0));
                });
            }
        }
    }
}

// Layered skin by every registered solver that takes layered materials (a new solver is covered with no edit), at
// the tables' edges and in the visible, with extreme layers: finite, in [0, 1], R + T <= 1, and energy conserved
// where the solver computes A.
void layered_stack_cases(Grid& grid) {
    const std::vector<std::pair<std::string, std::vector<std::string>>> variants{
        {"preset", {}},
        {"maximal melanin", {"epidermis.melanosome_fraction=0.5"}},
        {"maximal blood", {"dermis.blood_fraction=1"}},
        {"stratum corneum 1 nm", {"stratum_corneum.thickness_cm=1e-7"}},
        {"reticular dermis 10 cm", {"reticular_dermis.thickness_cm=10"}},
        {"open bottom", {"bottom.boundary=exit"}},
        {"index 1 everywhere", {"stratum_corneum.refractive_index=1", "epidermis.refractive_index=1", "dermis.refractive_index=1"}},
        {"index 4 epidermis", {"epidermis.refractive_index=4"}},
    };
    for (const auto* solver : solver_registry()) {
        const auto& caps = solver->capabilities();
        if (!caps.layered_materials) continue;
        for (const auto& variant : variants) {
            const auto& label = variant.first;
            const auto& overrides_text = variant.second;
            for (const double wavelength : {240.0, 250.0, 550.0, 2500.0}) {
                grid.run(std::string(solver->name()) + "-stack", fmt::format("{}: {}, {:g} nm", solver->name(), label, wavelength), [&](Checks& c) {
                    std::vector<MaterialOverride> overrides;
                    for (const auto& o : overrides_text) overrides.push_back(parse_override(o));
                    const auto material = load_material("biospec-moderately", overrides);
                    SolverRequest request;
                    request.spectral.wavelengths = WavelengthGrid::list({wavelength});
                    request.spectral.quantities.transmittance = caps.quantities.transmittance;
                    request.spectral.quantities.absorptance = caps.quantities.absorptance;
                    if (caps.uncertainty) request.fixed_rays_per_wavelength = 1000;
                    const auto result = solve_spectrum(*solver, material, request);
                    const auto& w = result.wavelengths.front();
                    c.unit("R", w.reflectance.value);
                    c.unit("T", w.transmittance.value);
                    c.expect(w.reflectance.value + w.transmittance.value <= 1.0 + energy_tolerance, "R + T > 1");
                    if (caps.quantities.absorptance) {
                        double sum = w.reflectance.value + w.transmittance.value + w.absorptance_surface.value;
                        for (const auto& a : w.absorptance_layers) {
                            if (caps.uncertainty) c.statistical_unit("A", a);
                            else c.unit("A", a.value);
                            sum += a.value;
                        }
                        c.energy(sum, 1e-8);
                    }
                    if (!result.warnings.empty()) c.limit = fmt::format("{} trust warning(s): {}", result.warnings.size(), summarise_warnings(result.warnings).front());
                });
            }
        }
    }
}

// Every number field at its range's ends (an infinite end as 1e300, an open end just inside) and beyond them, in
// every solver that takes layered materials (issue 32): a value beyond is refused when the material is read; at the
// ends the result is finite and in [0, 1] or refused (a documented limit), never NaN, never a hang.
void extreme_field_cases(Grid& grid) {
    struct Probe {
        std::string key;
        FieldRange range;
    };
    std::vector<Probe> probes;
    for (const auto& f : layer_number_fields()) probes.push_back({"epidermis." + std::string(f.key), f.range});
    for (const auto& f : volumetric_fields()) probes.push_back({"epidermis." + std::string(f.key), f.range});
    probes.push_back({"reticular_dermis.thickness_cm", layer_number_fields().front().range});
    for (const auto& f : surface_fields()) probes.push_back({"surface." + std::string(f.key), f.range});
    for (const auto& f : bottom_fields()) probes.push_back({"bottom." + std::string(f.key), f.range});
    for (const auto& f : model_fields()) {
        if (std::holds_alternative<double ModelOptions::*>(f.member)) probes.push_back({"model." + std::string(f.key), f.range});
    }
    constexpr double huge = 1e300;
    for (const auto* solver : solver_registry()) {
        const auto& caps = solver->capabilities();
        if (!caps.layered_materials) continue;
        for (const auto& probe : probes) {
            const auto& r = probe.range;
            std::vector<std::pair<double, bool>> values;  // (value, inside the range)
            values.emplace_back(std::isinf(r.lo) ? -huge : r.lo_open ? std::nextafter(r.lo, huge) : r.lo, true);
            values.emplace_back(std::isinf(r.hi) ? huge : r.hi_open ? std::nextafter(r.hi, -huge) : r.hi, true);
            if (std::isfinite(r.lo)) values.emplace_back(r.lo_open ? r.lo : r.lo - std::max(1.0, std::abs(r.lo)), false);
            if (std::isfinite(r.hi)) values.emplace_back(r.hi_open ? r.hi : r.hi + std::max(1.0, std::abs(r.hi)), false);
            for (const auto& probe_value : values) {
                const double value = probe_value.first;  // not a structured binding: clang 14 cannot capture one
                const bool inside = probe_value.second;
                grid.run(std::string(solver->name()) + "-fields", fmt::format("{}: {} = {:g}", solver->name(), probe.key, value), [&](Checks& c) {
                    const auto material = load_material("biospec-moderately", {MaterialOverride(probe.key, format_number(value))});
                    c.expect(inside, fmt::format("{} = {:g} is outside {} but was accepted", probe.key, value, r.text()));
                    SolverRequest request;
                    request.spectral.wavelengths = WavelengthGrid::list({550.0});
                    request.spectral.quantities.transmittance = caps.quantities.transmittance;
                    if (caps.uncertainty) request.fixed_rays_per_wavelength = 200;
                    const auto result = solve_spectrum(*solver, material, request);
                    c.unit("R", result.wavelengths.front().reflectance.value);
                    c.unit("T", result.wavelengths.front().transmittance.value);
                });
            }
        }
    }
}

}  // namespace

StressReport run_stress_grid(const StressOptions& options) {
    Grid grid(options);
    try {
        diffusion_cases(grid);
        layered_stack_cases(grid);
        extreme_field_cases(grid);
        adding_doubling_cases(grid);
        biospec_cases(grid);
        rte_cases(grid);
    } catch (const Stopped&) {
        grid.report().partial = true;
    }
    return grid.report();
}

}  // namespace skinspec
