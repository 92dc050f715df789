#include "solvers/spectral_solver.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "materials/path_key.hpp"
#include "skinspec/version.hpp"
#include "solvers/adding_doubling_solver.hpp"
#include "solvers/biospec_adding_doubling_solver.hpp"
#include "solvers/biospec_walk_solver.hpp"
#include "solvers/diffusion_solvers.hpp"
#include "solvers/matched_multipole_solver.hpp"
#include "solvers/result_wire.hpp"
#include "solvers/volumetric_walk_solver.hpp"
#include "spectral/input_error.hpp"
#include "spectral/parallel_indices.hpp"
#include "spectral/text_fields.hpp"
#include "transport/result_quantities.hpp"

namespace skinspec {
namespace {

// Members of a sweep built and solved at a time by a solver that does not replay (solve_sweep).
constexpr std::size_t sweep_block_members = 256;

// Results solved group by group, back in the materials' order, up to the first one not solved (stopped).
std::vector<SpectralResult> solved_prefix(std::vector<std::optional<SpectralResult>>& by_index) {
    std::vector<SpectralResult> out;
    for (auto& r : by_index) {
        if (!r) break;
        out.push_back(std::move(*r));
    }
    return out;
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
    return out.empty() ? std::string("none") : out;
}

// Names of the registered solvers for which `offers` holds.
std::string offered_by(const std::function<bool(const SolverCapabilities&)>& offers) {
    std::vector<std::string> names;
    for (const auto* s : solver_registry()) {
        if (offers(s->capabilities())) names.emplace_back(s->name());
    }
    return join(names);
}

std::string quantity_list(const Quantities& q) {
    std::vector<std::string> names;
    if (q.reflectance) names.emplace_back("R");
    if (q.transmittance) names.emplace_back("T");
    if (q.absorptance) names.emplace_back("A");
    if (q.angular) names.emplace_back("brdf");
    return join(names);
}

void check_material(const SpectralSolver& solver, const Material& material) {
    const auto& caps = solver.capabilities();
    const auto who = [&] { return "solver '" + std::string(solver.name()) + "'"; };
    if (std::holds_alternative<HomogeneousMaterial>(material) && !caps.band_materials) {
        throw InputError(who() + " needs a layered material; '" + material_name(material) +
                         "' is a homogeneous material given per band (solvers for band materials: " +
                         offered_by([](const SolverCapabilities& c) { return c.band_materials; }) + ")");
    }
    if (std::holds_alternative<LayerStack>(material) && !caps.layered_materials) {
        throw InputError(who() + " needs a homogeneous band material; '" + material_name(material) +
                         "' is layered (solvers for layered materials: " +
                         offered_by([](const SolverCapabilities& c) { return c.layered_materials; }) + ")");
    }
}

bool reads(const SolverCapabilities& caps, ScatteringDescription d) {
    return std::find(caps.descriptions.begin(), caps.descriptions.end(), d) != caps.descriptions.end();
}

// A volumetric description derived from the BioSpec one (matched_volumetric.hpp) reads the BioSpec description and,
// of the layers' own volumetric and reduced fields, only the dermal layers' (as on their own description): their
// phase function, and their mu_s, which one factor scales, so that the dermal layers keep their mu_s relative to one
// another. The thin layers take mu_s d = 1 and their crossing's profile. Unset unless the stack derives it, or for a
// dermal layer's field.
std::optional<bool> derived_reads(const SolverCapabilities& caps, const LayerStack* stack, const std::string& key, ScatteringDescription d) {
    if (!stack || !stack->model.volumetric_matched_to_biospec || !reads(caps, ScatteringDescription::volumetric)) return std::nullopt;
    if (d == ScatteringDescription::biospec) return true;
    if (key.starts_with("model.")) return std::nullopt;
    const auto head = std::string_view(key).substr(0, key.find('.'));
    const bool dermal = std::any_of(stack->layers.begin(), stack->layers.end(),
                                    [&](const TissueLayer& l) { return layer_matches(l.name, head) && is_dermal(crossing_in_effect(l, stack->model)); });
    return dermal ? std::nullopt : std::optional<bool>(false);
}

}  // namespace

bool reads_field(const SolverCapabilities& caps, const Material& material, const std::string& key) {
    const auto d = scattering_description(key);
    if (!d) return true;
    const auto* stack = std::get_if<LayerStack>(&material);
    if (const auto derived = derived_reads(caps, stack, key, *d)) return *derived;
    if (reads(caps, *d)) return true;
    if (!stack || *d != ScatteringDescription::reduced || !reads(caps, ScatteringDescription::volumetric)) return false;
    const auto head = std::string_view(key).substr(0, key.find('.'));
    return std::any_of(stack->layers.begin(), stack->layers.end(), [&](const TissueLayer& l) {
        return layer_matches(l.name, head) && l.volumetric && l.volumetric->source == VolumetricSource::from_reduced_scattering;
    });
}

// An override the solver would ignore is refused: of the bottom, by a solver without one (--reflector, --set/--vary
// bottom.FIELD), and of a field of a description of scattering it does not read (--set epidermis.hg_g with
// adding-doubling left R as it was).
void check_overrides(const SpectralSolver& solver, const Material& material, const std::vector<MaterialOverride>& overrides) {
    const auto& caps = solver.capabilities();
    const std::string who = "solver '" + std::string(solver.name()) + "'";
    for (const auto& o : overrides) {
        if (!caps.bottom && o.key.starts_with("bottom.")) {
            throw InputError(o.origin + " sets " + o.key + " = " + o.value + ", but " + who +
                             " treats the skin as one semi-infinite medium, which has no bottom (solvers that model it: " +
                             offered_by([](const SolverCapabilities& c) { return c.bottom; }) + ")");
        }
        const auto* stack = std::get_if<LayerStack>(&material);
        if (!caps.layer_refractive_indices && stack && o.key.ends_with(".refractive_index")) {
            const auto handle = layer_field(*stack, o.key, o.origin);
            if (handle.layers.back() > 0) {
                throw InputError(o.origin + " sets " + o.key + " = " + o.value + ", but " + who + " merges the layers into one semi-infinite medium with the top layer's refractive index ('" +
                                 stack->layers.front().name + "'), so it does not read a deeper layer's (solvers that read it: " +
                                 offered_by([](const SolverCapabilities& c) { return c.layer_refractive_indices; }) + ")");
            }
        }
        if (reads_field(caps, material, o.key)) {
            if (const auto why = stack ? unread_in_layers(*stack, o.key) : std::nullopt) throw InputError(o.origin + " sets " + o.key + " = " + o.value + ", but " + *why);
            continue;
        }
        const auto d = *scattering_description(o.key);
        if (derived_reads(caps, stack, o.key, d)) {
            throw InputError(o.origin + " sets " + o.key + " = " + o.value + ", which " + who +
                             " does not read: model.volumetric_matched_to_biospec = true derives the volumetric description from the BioSpec one, "
                             "taking of the layers' own scattering fields only the dermal layers' (their phase and their mu_s relative to one another; "
                             "the thin layers scatter once per crossing by their crossing's profile)");
        }
        throw InputError(o.origin + " sets " + o.key + " = " + o.value + ", which " + who + " does not read: it belongs to " + std::string(to_string(d)) +
                         " (solvers that read it: " + offered_by([&](const SolverCapabilities& c) { return reads_field(c, material, o.key); }) + ")");
    }
}

namespace {

void check_switches(const SpectralSolver& solver, const SolverSwitches& switches) {
    const auto& caps = solver.capabilities();
    for (const auto s : switches.set()) {
        if (std::find(caps.switches.begin(), caps.switches.end(), s) != caps.switches.end()) continue;
        throw InputError("solver '" + std::string(solver.name()) + "' does not take the switch '" + std::string(to_string(s)) +
                         "' (taken by: " +
                         offered_by([s](const SolverCapabilities& c) {
                             return std::find(c.switches.begin(), c.switches.end(), s) != c.switches.end();
                         }) +
                         ")");
    }
}

}  // namespace

std::vector<SpectralResult> SpectralSolver::solve_many(const std::vector<const Material*>& materials, const SolverRequest& request) const {
    if (materials.size() == 1) return {solve(*materials.front(), request)};
    // The materials in parallel (each result depends on its material alone, so on no thread count); progress counts
    // the members finished, reported one at a time.
    // Solved in place (moving 4096 results out of optionals was 7 % of a dipole sweep).
    std::vector<SpectralResult> results(materials.size());
    std::vector<char> solved(materials.size(), 0);
    auto member = request;
    member.spectral.on_progress = nullptr;
    std::mutex progress;
    std::size_t done = 0;
    const std::size_t wavelengths = request.spectral.wavelengths.size();
    tbb::parallel_for(std::size_t{0}, materials.size(), [&](std::size_t i) {
        if (request.spectral.cancel && request.spectral.cancel->load()) return;
        results[i] = solve(*materials[i], member);
        solved[i] = 1;
        if (results[i].partial || !request.spectral.on_progress) return;
        const std::lock_guard lock(progress);
        ++done;
        request.spectral.on_progress(Progress{0, 0, done * wavelengths, materials.size() * wavelengths});
    });
    // Up to the first member not solved, the first partial one included.
    std::size_t kept = 0;
    while (kept < results.size() && solved[kept] && !results[kept].partial) ++kept;
    if (kept < results.size() && solved[kept]) ++kept;  // the first partial one
    results.resize(kept);
    return results;
}

void SpectralSolver::state_errors(const std::function<Material(std::size_t)>&, const std::vector<std::vector<std::size_t>>&, const SolverRequest&,
                                  std::span<SpectralResult>) const {}

std::vector<std::vector<std::size_t>> SpectralSolver::solve_groups(const std::vector<const Material*>& materials, const SolverRequest&) const {
    std::vector<std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < materials.size(); ++i) groups.push_back({i});
    return groups;
}

std::vector<std::vector<std::size_t>> replay_groups(const std::vector<const Material*>& materials, std::size_t max_sets, TracedPaths paths) {
    std::vector<std::vector<std::size_t>> groups;
    std::vector<PathKey> keys;  // one per group
    std::unordered_multimap<std::size_t, std::size_t> by_hash;  // key hash -> the groups with that hash (the lowest index joins)
    for (std::size_t i = 0; i < materials.size(); ++i) {
        auto key = path_key(std::get<LayerStack>(*materials[i]), paths);
        std::optional<std::size_t> joined;
        const auto [first, last] = by_hash.equal_range(key.hash);
        for (auto it = first; it != last; ++it) {
            if (groups[it->second].size() < max_sets && keys[it->second] == key && (!joined || it->second < *joined)) joined = it->second;
        }
        if (joined) {
            groups[*joined].push_back(i);
            continue;
        }
        by_hash.emplace(key.hash, groups.size());
        keys.push_back(std::move(key));
        groups.push_back({i});
    }
    return groups;
}

SpectralRequest PartProgress::part(const SpectralRequest& request, std::size_t part) {
    auto out = request;
    rays_of_part_ = 0;
    if (!whole_) return out;
    out.on_progress = [this, part](const Progress& p) {
        rays_of_part_ = p.rays_done;
        const std::size_t to_come = parts_ - part;  // this part included
        const std::uint64_t expected = p.rays_expected > 0 ? rays_before_ + p.rays_expected * to_come : 0;
        whole_(Progress{rays_before_ + p.rays_done, expected, part * p.wavelengths_total + p.wavelengths_done, parts_ * p.wavelengths_total,
                        p.wavelengths_in_progress});
    };
    return out;
}

void PartProgress::finish_part() {
    rays_before_ += rays_of_part_;
    rays_of_part_ = 0;
}

std::vector<SpectralResult> solve_in_replay_groups(
    const std::vector<const Material*>& materials, const SolverRequest& request, const std::vector<std::vector<std::size_t>>& groups,
    const std::function<std::vector<SpectralResult>(const std::vector<const LayerStack*>&, const SpectralRequest&)>& solve_group) {
    std::vector<std::optional<SpectralResult>> by_index(materials.size());
    PartProgress progress(request.spectral.on_progress, groups.size());
    for (std::size_t k = 0; k < groups.size(); ++k) {
        if (request.spectral.cancel && request.spectral.cancel->load()) break;
        const auto& g = groups[k];
        std::vector<const LayerStack*> stacks;
        for (const auto i : g) stacks.push_back(&std::get<LayerStack>(*materials[i]));
        auto results = solve_group(stacks, progress.part(request.spectral, k));
        progress.finish_part();
        for (std::size_t j = 0; j < results.size(); ++j) by_index[g[j]] = std::move(results[j]);
    }
    return solved_prefix(by_index);
}

const SpectralSolver& default_profile_solver() { return find_solver(default_profile_solver_name); }

SpectralProfiles SpectralSolver::profiles(const Material&, const ProfileRequest&) const {
    throw InputError("solver '" + std::string(name()) + "' does not compute radial profiles");
}

std::vector<SpectralProfiles> SpectralSolver::profiles_many(const std::vector<const Material*>& materials, const ProfileRequest& request) const {
    // Progress counts the channels of the members finished before this one on.
    std::vector<SpectralProfiles> out;
    auto member = request;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        if (request.on_progress) {
            member.on_progress = [&, i](const Progress& p) {
                request.on_progress(Progress{p.rays_done, 0, i * p.wavelengths_total + p.wavelengths_done, materials.size() * p.wavelengths_total});
            };
        }
        out.push_back(profiles(*materials[i], member));
        if (out.back().partial) break;
    }
    return out;
}

const std::vector<const SpectralSolver*>& solver_registry() {
    // Adding a solver: its own files and one entry here (docs/SOLVERS.md).
    static const std::vector<const SpectralSolver*> solvers{&biospec_walk_solver(), &volumetric_walk_solver(), &adding_doubling_solver(),
                                                            &biospec_adding_doubling_solver(), &matched_multipole_solver(),
                                                            &multipole_solver(), &dipole_solver()};
    return solvers;
}

std::string solver_names() {
    std::vector<std::string> names;
    for (const auto* s : solver_registry()) names.emplace_back(s->name());
    return join(names);
}

const SpectralSolver& find_solver(std::string_view name, std::string_view what) {
    for (const auto* s : solver_registry()) {
        if (s->name() == name) return *s;
    }
    throw InputError(std::string(what) + ": '" + std::string(name) + "' is not a solver (allowed: " + solver_names() + ")");
}

namespace {

// A deterministic solver has no seed, ray budget or other Monte Carlo setting: one given is refused, not ignored.
void refuse_sampling_options(const SpectralSolver& solver, const std::vector<std::string>& given) {
    if (solver.capabilities().uncertainty || given.empty()) return;
    throw InputError(join(given) + ": solver '" + std::string(solver.name()) + "' is deterministic and takes no Monte Carlo setting (Monte Carlo solvers: " +
                     offered_by([](const SolverCapabilities& c) { return c.uncertainty; }) + ")");
}

}  // namespace

void check_request(const SpectralSolver& solver, const Material& material, const SolverRequest& request) {
    check_material(solver, material);
    check_request_settings(solver, request);
    check_overrides(solver, material, request.overrides);
}

void check_request_settings(const SpectralSolver& solver, const SolverRequest& request) {
    const auto& caps = solver.capabilities();
    const std::string who = "solver '" + std::string(solver.name()) + "'";
    const auto& q = request.spectral.quantities;
    const std::vector<std::pair<bool, const char*>> asked{{q.reflectance && !caps.quantities.reflectance, "R"},
                                                          {q.transmittance && !caps.quantities.transmittance, "T"},
                                                          {q.absorptance && !caps.quantities.absorptance, "A"},
                                                          {q.angular && !caps.quantities.angular, "brdf"}};
    for (const auto& [missing, quantity] : asked) {
        if (!missing) continue;
        const std::string wanted = quantity;
        throw InputError(who + " does not compute " + wanted + " (it computes " + quantity_list(caps.quantities) + "; " + wanted +
                         " is computed by: " + offered_by([&](const SolverCapabilities& c) {
                             return wanted == "R" ? c.quantities.reflectance
                                    : wanted == "T" ? c.quantities.transmittance
                                    : wanted == "A" ? c.quantities.absorptance
                                                    : c.quantities.angular;
                         }) + ")");
    }
    const auto geometry = request.spectral.geometry;
    if (std::find(caps.geometries.begin(), caps.geometries.end(), geometry) == caps.geometries.end()) {
        std::string own;
        for (const auto g : caps.geometries) own += (own.empty() ? "" : ", ") + std::string(to_string(g));
        throw InputError(who + " does not measure R in geometry " + std::string(to_string(geometry)) + " (it offers " + own +
                         "; " + std::string(to_string(geometry)) + " is offered by: " + offered_by([&](const SolverCapabilities& c) {
                             return std::find(c.geometries.begin(), c.geometries.end(), geometry) != c.geometries.end();
                         }) + ")");
    }
    if (!caps.uncertainty && (request.spectral.stderr_target || request.spectral.stderr_targets || request.fixed_rays_per_wavelength)) {
        throw InputError(who + " is deterministic: it takes no standard-error target or ray count (Monte Carlo solvers: " +
                         offered_by([](const SolverCapabilities& c) { return c.uncertainty; }) + ")");
    }
    if (caps.uncertainty) {
        const auto count = [](std::string_view name, std::uint64_t rays) {
            if (rays < minimum_rays_per_wavelength || rays > maximum_rays_per_wavelength) {
                throw InputError(fmt::format("{} = {} is outside [{}, {}]: a Monte Carlo standard error needs at least {} rays per wavelength",
                                             name, rays, minimum_rays_per_wavelength, maximum_rays_per_wavelength, minimum_rays_per_wavelength));
            }
        };
        if (request.fixed_rays_per_wavelength) count("--rays", *request.fixed_rays_per_wavelength);
        else count("--max-rays", request.spectral.max_rays_per_wavelength);
    }
    refuse_sampling_options(solver, request.sampling_options);
    check_switches(solver, request.switches);
}

void check_request(const SpectralSolver& solver, const Material& material, const ProfileRequest& request) {
    if (!solver.capabilities().radial_profiles) {
        throw InputError("solver '" + std::string(solver.name()) + "' does not compute radial profiles R(r) (solvers that do: " +
                         offered_by([](const SolverCapabilities& c) { return c.radial_profiles; }) + ")");
    }
    check_material(solver, material);
    check_switches(solver, request.switches);
    check_overrides(solver, material, request.overrides);
    refuse_sampling_options(solver, request.sampling_options);
    if (!solver.capabilities().uncertainty && request.rays_per_wavelength) {
        throw InputError("solver '" + std::string(solver.name()) + "' is deterministic: it takes no ray count (Monte Carlo solvers with radial profiles: " +
                         offered_by([](const SolverCapabilities& c) { return c.uncertainty && c.radial_profiles; }) + ")");
    }
    if (request.rays_per_wavelength && *request.rays_per_wavelength < minimum_rays_per_wavelength) {
        throw InputError(fmt::format("--rays = {} is outside [{}, {}]: a Monte Carlo standard error needs at least {} rays per wavelength",
                                     *request.rays_per_wavelength, minimum_rays_per_wavelength, maximum_rays_per_wavelength, minimum_rays_per_wavelength));
    }
}

namespace {

// A fixed ray count replaces the budget and clears the targets.
SolverRequest effective_request(const SolverRequest& request) {
    auto out = request;
    if (request.fixed_rays_per_wavelength) {
        out.spectral.max_rays_per_wavelength = *request.fixed_rays_per_wavelength;
        out.spectral.stderr_target.reset();
        out.spectral.stderr_targets = nullptr;
    }
    return out;
}

// Nothing non-finite or unphysical leaves a solver: every requested value finite and within its quantity's range
// (a Monte Carlo estimate may stray outside by 5 of its standard errors, plus rounding), or the request is refused.
void check_result_values(const SpectralSolver& solver, const SpectralResult& result, const std::function<std::vector<MaterialOverride>()>& given) {
    const auto quantities = quantities_of(result);
    for (const auto& w : result.wavelengths) {
        for (const auto* q : quantities) {
            for (const auto& e : q->values(w)) {
                const double slack = 1e-9 + (result.has_uncertainty ? 5.0 * e.stderr : 0.0);
                if (std::isfinite(e.value) && std::isfinite(e.stderr) && e.stderr >= 0.0 && e.value >= -slack && e.value <= q->upper_bound() + slack) continue;
                std::string inputs;
                for (const auto& o : given()) inputs += (inputs.empty() ? "" : ", ") + o.origin + " " + o.key + "=" + o.value;
                const std::string at = result.bands.empty() ? format_number(w.wavelength_nm) + " nm" : "a band";
                throw InputError("solver '" + std::string(solver.name()) + "' computed " + std::string(q->key) + " = " + format_number(e.value) +
                                 (result.has_uncertainty ? " +- " + format_number(e.stderr) : std::string()) + " at " + at + " for '" + result.material +
                                 "', outside " + (q->upper_bound() == 1.0 ? "[0, 1]" : "[0, inf)") +
                                 ": the material is outside what the model can compute" + (inputs.empty() ? std::string() : " (given: " + inputs + ")"));
            }
        }
    }
}

// A result reports what was asked for: a solver that computes more on the way (the volumetric walk tallies T and A
// always) does not fill the output with columns nobody requested.
void keep_requested(SpectralResult& result, const SolverRequest& request) {
    const auto& asked = request.spectral.quantities;
    auto& q = result.quantities;
    q = Quantities{q.reflectance && asked.reflectance, q.transmittance && asked.transmittance, q.absorptance && asked.absorptance, q.angular && asked.angular};
}

// One shared copy of the settings of each distinct material model among a request's results.
class ModelSettingsCache {
public:
    std::shared_ptr<const ResultSettings> operator()(const Material& material) {
        const auto* stack = std::get_if<LayerStack>(&material);
        if (!stack) return nullptr;
        for (const auto& [model, settings] : seen_) {
            if (model == stack->model) return settings;
        }
        return seen_.emplace_back(stack->model, std::make_shared<const ResultSettings>(model_result_settings(stack->model))).second;
    }

private:
    std::vector<std::pair<ModelOptions, std::shared_ptr<const ResultSettings>>> seen_;
};

void record_provenance(SpectralResult& result, const SpectralSolver& solver, std::shared_ptr<const ResultSettings> model_settings,
                       std::shared_ptr<const std::string> material_toml, const std::vector<MaterialOverride>& overrides, SweptValues varied) {
    result.provenance.solver = std::string(solver.name());
    result.model_settings = std::move(model_settings);
    result.provenance.material_toml = std::move(material_toml);
    for (const auto& o : overrides) result.provenance.overrides.emplace_back(o.key, o.value);
    result.provenance.varied = std::move(varied);
    result.provenance.version = version;
}

}  // namespace

SpectralResult solve_spectrum(const SpectralSolver& solver, const Material& material, const SolverRequest& request) {
    check_request(solver, material, request);
    const auto effective = effective_request(request);
    std::vector<SpectralResult> one{solver.solve(material, effective)};
    keep_requested(one.front(), request);
    check_result_values(solver, one.front(), [&] { return request.overrides; });
    solver.state_errors([&](std::size_t) { return material; }, {{}}, effective, one);
    auto result = std::move(one.front());
    record_provenance(result, solver, ModelSettingsCache()(material), std::make_shared<const std::string>(to_toml(material)), request.overrides, {});
    return result;
}

SweepMembers::SweepMembers(std::vector<SweepMember> list) : list_(std::move(list)) {}

SweepMembers::SweepMembers(std::shared_ptr<const Material> base, std::shared_ptr<const std::string> base_toml, std::vector<SweepAxis> axes)
    : base_(std::move(base)), base_toml_(std::move(base_toml)), axes_(std::move(axes)), fields_(swept_fields(axes_)), lattice_size_(1) {
    for (const auto& a : axes_) lattice_size_ *= a.values.size();
}

SweepMember SweepMembers::operator[](std::size_t i) const {
    if (!list_.empty()) return list_[i];
    SweepMember m{base_, {axes_.empty() ? nullptr : fields_, {}}, base_toml_, {}};
    // Its index on each axis: the first axis fastest (sweep_grid's order).
    m.position.reserve(axes_.size());
    m.varied.values.reserve(axes_.size());
    for (std::size_t a = 0, rest = i; a < axes_.size(); ++a) {
        m.position.push_back(rest % axes_[a].values.size());
        m.varied.values.push_back(axes_[a].values[m.position.back()]);
        rest /= axes_[a].values.size();
    }
    return m;
}

SweepMembers sweep_members(const SpectralSolver& solver, const SolverRequest& request, const std::vector<SweepAxis>& axes,
                           const std::vector<std::string>& layers, const Material& base) {
    auto cut = std::make_shared<Material>(base);
    if (!layers.empty()) {
        if (const auto* stack = std::get_if<LayerStack>(&base)) *cut = stack->sub_stack(layers);
        else throw InputError("--layers: material '" + material_name(base) + "' is homogeneous and has no layers");
    }
    // Overrides keep the material's kind and every member sets the same fields: the request is checked once.
    check_request(solver, *cut, request);
    SweepMembers members(cut, std::make_shared<const std::string>(to_toml(*cut)), axes);
    if (members.size() == 0) return members;
    check_overrides(solver, members[0].material(), members[0].overrides());
    // The corners are built and checked here: every range a material checks is an interval and the one joint bound
    // (melanosome + blood fraction <= 1) is linear, so a sweep's extremes are its corners. solve_sweep builds every
    // member again (refusing as the reader does) before it traces any ray of a replaying solver's sweep.
    std::vector<std::size_t> corners{0};
    for (std::size_t a = 0, stride = 1; a < axes.size(); stride *= axes[a].values.size(), ++a) {
        const std::size_t far = (axes[a].values.size() - 1) * stride, n = corners.size();
        for (std::size_t c = 0; c < n && far > 0; ++c) corners.push_back(corners[c] + far);
    }
    std::sort(corners.begin(), corners.end());
    Material checked;
    for (const auto i : corners) members[i].build(checked);
    return members;
}

namespace {

// Each process solves the groups share->mine() gives it; the first process gathers them (result_wire.hpp) in
// the materials' order, up to the first one not solved (a rank stopped before it).
std::vector<SpectralResult> solve_shared(const SpectralSolver& solver, const std::vector<const Material*>& materials, const SolverRequest& request,
                                         const WorkShare& share) {
    const auto groups = solver.solve_groups(materials, request);
    std::vector<std::pair<std::size_t, std::string>> mine;
    std::size_t own = 0, done = 0;
    for (std::size_t g = 0; g < groups.size(); ++g) own += share.mine(g) ? 1 : 0;
    PartProgress progress(request.spectral.on_progress, own);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        if (!share.mine(g)) continue;
        if (request.spectral.cancel && request.spectral.cancel->load()) break;
        std::vector<const Material*> group;
        for (const auto i : groups[g]) group.push_back(materials[i]);
        auto part = request;
        part.spectral = progress.part(request.spectral, done++);
        mine.emplace_back(g, results_to_bytes(solver.solve_many(group, part)));
        progress.finish_part();
    }
    const auto gathered = share.gather(mine, groups.size());
    if (share.rank() != 0) return {};
    std::vector<std::optional<SpectralResult>> by_index(materials.size());
    for (std::size_t g = 0; g < groups.size(); ++g) {
        if (gathered[g].empty()) continue;
        auto results = results_from_bytes(gathered[g]);
        for (std::size_t j = 0; j < results.size(); ++j) by_index[groups[g][j]] = std::move(results[j]);
    }
    return solved_prefix(by_index);
}

}  // namespace

std::vector<SpectralResult> solve_sweep(const SpectralSolver& solver, const SweepMembers& members, const SolverRequest& request,
                                        const WorkShare* share) {
    std::vector<SpectralResult> results;
    solve_sweep(solver, members, request, results, share);
    return results;
}

void solve_sweep(const SpectralSolver& solver, const SweepMembers& members, const SolverRequest& request, std::vector<SpectralResult>& results,
                 const WorkShare* share) {
    check_request_settings(solver, request);
    // Overrides keep a material's kind: each base is checked before anything is solved.
    for (std::size_t i = 0; i < members.size(); ++i) {
        if (i == 0 || members.base(i) != members.base(i - 1)) check_material(solver, *members.base(i));
    }
    const auto effective = effective_request(request);
    // A solver that replays traces groups of the members together: it gets them all at once. The others get blocks
    // of members, made and built as they are solved (4096 materials held at once were a third of a dipole sweep's
    // time).
    const std::size_t block = solver.capabilities().replay_fields.empty() ? sweep_block_members : std::max<std::size_t>(1, members.size());
    const std::size_t blocks = (members.size() + block - 1) / block;
    PartProgress progress(effective.spectral.on_progress, blocks);
    const std::size_t first = results.size();
    results.reserve(first + members.size());
    std::vector<std::vector<std::size_t>> positions;
    positions.reserve(members.size());
    ModelSettingsCache model_settings;
    std::vector<SweepMember> made;  // a block's members
    std::vector<Material> built;    // their materials, built into the previous block's
    for (std::size_t b = 0; b < blocks; ++b) {
        const std::size_t begin = b * block, end = std::min(members.size(), begin + block);
        made.resize(end - begin);
        built.resize(end - begin);
        parallel_indices(built.size(), [&](std::size_t i) {
            made[i] = members[begin + i];
            made[i].build(built[i]);
        });
        std::vector<const Material*> materials;
        for (const auto& m : built) materials.push_back(&m);
        auto part = effective;
        part.spectral = progress.part(effective.spectral, b);
        auto solved = share ? solve_shared(solver, materials, part, *share) : solver.solve_many(materials, part);
        progress.finish_part();
        const bool complete = solved.size() == materials.size() && (solved.empty() || !solved.back().partial);
        // Each member's values after the request's own overrides: in its messages and its provenance. A member's
        // values change its model's switches only when they name one (model.FIELD).
        std::vector<std::shared_ptr<const ResultSettings>> settings_of;
        for (std::size_t i = 0; i < solved.size(); ++i) {
            const auto& v = made[i].varied;
            bool own_model = false;
            for (std::size_t f = 0; f < v.size(); ++f) own_model = own_model || v.field(f).starts_with("model.");
            settings_of.push_back(model_settings(own_model ? built[i] : *made[i].base));
        }
        parallel_indices(solved.size(), [&](std::size_t i) {
            auto& m = made[i];
            keep_requested(solved[i], request);
            check_result_values(solver, solved[i], [&] {
                auto given = request.overrides;
                for (auto& o : m.overrides()) given.push_back(std::move(o));
                return given;
            });
            record_provenance(solved[i], solver, settings_of[i], m.base_toml ? m.base_toml : std::make_shared<const std::string>(to_toml(built[i])),
                              request.overrides, std::move(m.varied));
        });
        for (std::size_t i = 0; i < solved.size(); ++i) positions.push_back(std::move(made[i].position));
        std::move(solved.begin(), solved.end(), std::back_inserter(results));
        if (!complete) break;
    }
    if (results.size() > first) {
        solver.state_errors([&](std::size_t i) { return members[i].material(); }, positions, effective, std::span(results).subspan(first));
    }
}

namespace {

// Profiles are densities (a transform's ringing may dip below 0): finite is what is required of them.
void require_finite(const SpectralSolver& solver, const SpectralProfiles& profiles, const ProfileRequest& request) {
    for (const auto& c : profiles.channels) {
        const auto finite = [](const std::vector<double>& v) { return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }); };
        const bool ok = finite(c.reflectance_per_mm2) && finite(c.transmittance_per_mm2) && finite(c.reflectance_stderr_per_mm2) &&
                        finite(c.transmittance_stderr_per_mm2) && std::isfinite(c.total_reflectance) && std::isfinite(c.total_transmittance);
        if (!ok) {
            throw InputError("solver '" + std::string(solver.name()) + "' computed a non-finite profile at " + c.label + " for '" + profiles.material +
                             "': the material or the radii (largest " + format_number(request.radii_mm.empty() ? 0.0 : request.radii_mm.back()) +
                             " mm) are outside what the model can compute");
        }
    }
}

}  // namespace

SpectralProfiles solve_profiles(const SpectralSolver& solver, const Material& material, const ProfileRequest& request) {
    check_request(solver, material, request);
    auto profiles = solver.profiles(material, request);
    require_finite(solver, profiles, request);
    return profiles;
}

std::vector<SpectralProfiles> solve_profiles(const SpectralSolver& solver, const std::vector<const Material*>& materials, const ProfileRequest& request) {
    for (const auto* material : materials) check_request(solver, *material, request);
    auto profiles = solver.profiles_many(materials, request);
    for (const auto& p : profiles) require_finite(solver, p, request);
    return profiles;
}

}  // namespace skinspec
