#pragma once
// One interface for every spectral solver (docs/SOLVERS.md): a solver declares what it supports, and every
// consumer (spectrum, swatch, profile, bench, stress, the phase comparison) asks the registry for it by name.
// A request for something a solver does not declare is refused by check_request() with one message naming
// the solver, what was asked and which solvers do offer it; solvers never see such a request.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "materials/material_fields.hpp"
#include "materials/material_file.hpp"
#include "materials/path_key.hpp"
#include "materials/parameter_sweep.hpp"
#include "solvers/solver_switches.hpp"
#include "solvers/work_share.hpp"
#include "transport/biospec/biospec_options.hpp"
#include "transport/diffusion/diffusion_profiles.hpp"
#include "transport/rte/rte_model.hpp"
#include "transport/spectral_request.hpp"

namespace skinspec {

struct SolverCapabilities {
    Quantities quantities;           // which of R, T, A (per layer), brdf (angular bins) it computes
    bool layered_materials = true;   // LayerStack materials (wavelength rows)
    bool band_materials = false;     // homogeneous materials given per band (band rows)
    bool uncertainty = true;         // Monte Carlo: standard errors, ray budgets and stderr targets
    bool radial_profiles = false;    // R(r), T(r) per wavelength or band (profile command, lit swatches)
    std::vector<SolverSwitch> switches;
    std::vector<std::string> replay_fields;  // material fields re-weighted from traced paths (absorption replay)
    std::string material_needs;      // what a layered material must describe for this solver, "" when nothing
    std::vector<MeasurementGeometry> geometries{MeasurementGeometry::sci};  // what its R can be measured as
    bool bottom = true;  // models the material's bottom (false: semi-infinite; a bottom.* override is refused)
    // Reads every layer's refractive index (false: one medium with the top layer's, the dipole; an override of a
    // deeper layer's refractive_index is refused).
    bool layer_refractive_indices = true;
    // The descriptions of scattering it reads (materials/material_fields.hpp); an override of a field of another is
    // refused. A volumetric solver also reads a layer's reduced scattering where that layer's volumetric mu_s is
    // derived from it (volumetric_scattering = from_reduced_scattering).
    std::vector<ScatteringDescription> descriptions{ScatteringDescription::biospec, ScatteringDescription::volumetric, ScatteringDescription::reduced};
};

// A request for one material. `spectral` is what the transport solvers consume; `overrides` are recorded in
// the result's provenance (they were applied when the material was loaded).
struct SolverRequest {
    SpectralRequest spectral;
    SolverSwitches switches;
    std::optional<std::uint64_t> fixed_rays_per_wavelength;  // exactly this many rays, no stderr target
    std::vector<MaterialOverride> overrides;
    // Monte Carlo settings the caller gave (e.g. "--seed", "--max-rays"): a deterministic solver refuses them, as it
    // refuses a ray count, rather than ignore them.
    std::vector<std::string> sampling_options;
};

// The precision of a Monte Carlo profile unless the caller sets one: the standard error of the reflectance leaving within
// each of the radii a kernel gathers from (transport/rte/rte_profiles.hpp), the same figure as a spectrum's default
// --stderr for R, within a budget of photons per wavelength (docs/PROFILES.md).
inline constexpr double default_profile_stderr = 0.002;
inline constexpr std::uint64_t default_profile_max_rays = 10'000'000;

struct ProfileRequest {
    WavelengthGrid wavelengths = WavelengthGrid::list({550.0});  // layered materials; band materials: all bands
    std::vector<double> radii_mm;
    bool transmittance = false;
    SolverSwitches switches;
    std::optional<std::uint64_t> rays_per_wavelength;  // Monte Carlo solvers: exactly this many, no target; refused by the others
    // Monte Carlo solvers without a fixed count: the precision target and the budget (given by the user: named in
    // sampling_options, so that a deterministic solver refuses them).
    double stderr_target = default_profile_stderr;
    std::uint64_t max_rays_per_wavelength = default_profile_max_rays;
    std::uint64_t seed = 1;
    const CancelFlag* cancel = nullptr;  // a stop leaves the channels finished so far (SpectralProfiles::partial)
    std::vector<std::string> sampling_options;  // as SolverRequest's
    std::function<void(const Progress&)> on_progress;  // channels (wavelengths or bands) done, and rays for the walks
    std::vector<MaterialOverride> overrides;  // as SolverRequest's: one the solver would ignore is refused
};

class SpectralSolver {
public:
    virtual ~SpectralSolver() = default;
    virtual std::string_view name() const = 0;
    virtual std::string_view description() const = 0;
    virtual const SolverCapabilities& capabilities() const = 0;

    // Only called through solve_spectrum() / solve_sweep() / solve_profiles(), i.e. with requests
    // check_request() accepted.
    virtual SpectralResult solve(const Material& material, const SolverRequest& request) const = 0;
    // Several materials under one request, one result each in order. Default: solve() each. A solver that
    // declares replay_fields traces each group of materials differing only in those fields once.
    virtual std::vector<SpectralResult> solve_many(const std::vector<const Material*>& materials, const SolverRequest& request) const;
    // The groups (indices into `materials`) that solve_many solves together, in the order it solves them: a result
    // depends on the other members of its group (one trace replayed for all), never on other groups. Default:
    // each material alone. What a sweep may share among processes (solve_sweep with a WorkShare).
    virtual std::vector<std::vector<std::size_t>> solve_groups(const std::vector<const Material*>& materials, const SolverRequest& request) const;
    virtual SpectralProfiles profiles(const Material& material, const ProfileRequest& request) const;
    // Several materials under one profile request, one result each in order (fewer after a stop: the finished ones,
    // the first partial one last). Default: profiles() of each in turn. A solver that declares replay_fields computes
    // each group of materials differing only in those fields from one set of paths.
    virtual std::vector<SpectralProfiles> profiles_many(const std::vector<const Material*>& materials, const ProfileRequest& request) const;
    // For solvers that state their error by comparison with a reference (SpectralResult::stated_error), called on
    // the finished results (possibly fewer than the materials: a stop) of solve_spectrum and solve_sweep, so that a
    // sweep can measure its error at some members and interpolate between them. `material_of(i)` builds material i
    // (a sweep's members are not held at once); `positions`: per material, its index on each sweep axis
    // (SweepMember::position; empty: unrelated materials, each measured), one per material. Default: nothing.
    virtual void state_errors(const std::function<Material(std::size_t)>& material_of, const std::vector<std::vector<std::size_t>>& positions,
                              const SolverRequest& request, std::span<SpectralResult> results) const;
};

// For solve_groups implementations that replay absorption: the layered materials that trace alike (equal path
// keys, materials/path_key.hpp: only absorption-only fields differ), at most `max_sets` per group, each joining
// the first group it fits.
std::vector<std::vector<std::size_t>> replay_groups(const std::vector<const Material*>& materials, std::size_t max_sets, TracedPaths paths);
// For solve_many implementations that replay absorption: solves each of `groups` with `solve_group` (one result per
// stack, in order) and returns the results in the materials' order, up to the first one not solved (cancelled).
// `solve_group` gets the request for that group: its progress reports into the whole sweep's (PartProgress).
std::vector<SpectralResult> solve_in_replay_groups(
    const std::vector<const Material*>& materials, const SolverRequest& request, const std::vector<std::vector<std::size_t>>& groups,
    const std::function<std::vector<SpectralResult>(const std::vector<const LayerStack*>&, const SpectralRequest&)>& solve_group);

// Progress of work done in parts one after another (a sweep's replay groups), each reporting its own progress from 0,
// as progress of the whole: the parts finished count, and the rays to come are estimated as the current part's for
// each part still to come (a per-part bar reset at every group, and the estimates swung to "16 h" for 2 minutes).
class PartProgress {
public:
    PartProgress(std::function<void(const Progress&)> whole, std::size_t parts) : whole_(std::move(whole)), parts_(parts) {}
    // `request` with its progress reporting as part `part` of the whole (nothing reported without a whole).
    SpectralRequest part(const SpectralRequest& request, std::size_t part);
    // The last part reported is finished: its rays count as done.
    void finish_part();

private:
    std::function<void(const Progress&)> whole_;
    std::size_t parts_;
    std::uint64_t rays_before_ = 0;  // rays of the parts finished
    std::uint64_t rays_of_part_ = 0;  // the current part's rays reported so far
};

// The registered solvers, in the order `--mode` lists them.
const std::vector<const SpectralSolver*>& solver_registry();
// The solver every command that needs radial profiles uses when none is named (profile, export profile, swatch --lit,
// their Python calls): the exact transport, the volumetric walk on the material's volumetric description (for the
// skin presets the one derived from the BioSpec model; band materials as semi-infinite media), docs/PROFILES.md.
inline constexpr std::string_view default_profile_solver_name = "rte";
const SpectralSolver& default_profile_solver();
// InputError naming the allowed solvers for an unknown name; `what` is the option (e.g. "--mode").
const SpectralSolver& find_solver(std::string_view name, std::string_view what = "--mode");
// "biospec, rte, dipole, multipole".
std::string solver_names();

// Whether a solver of `caps` reads the field `key` of `material` (after its overrides): a field of every description
// of scattering, of one the solver declares, or a layer's reduced scattering from which that layer's volumetric mu_s is
// derived; on a volumetric description derived from the BioSpec one, the BioSpec fields and the dermal layers' phase
// function (transport/adding_doubling/matched_volumetric.hpp). check_request refuses an override of a field it does
// not read.
bool reads_field(const SolverCapabilities& caps, const Material& material, const std::string& key);
// InputError for an override the solver would ignore: of a field it does not read, of the bottom by a solver without
// one, of a deeper layer's refractive index by a solver that reads only the top's (check_request's, for the commands
// that evaluate a solver's model without a request, e.g. fit-spectrum).
void check_overrides(const SpectralSolver& solver, const Material& material, const std::vector<MaterialOverride>& overrides);

// InputError for anything the solver does not declare: the material's kind, a quantity, a measurement geometry,
// a switch, a standard-error target or a ray count for a deterministic solver.
void check_request(const SpectralSolver& solver, const Material& material, const SolverRequest& request);
// The part of check_request that does not depend on the material (a sweep checks it once for all its members).
void check_request_settings(const SpectralSolver& solver, const SolverRequest& request);
void check_request(const SpectralSolver& solver, const Material& material, const ProfileRequest& request);

// check_request, solve, and the provenance (material TOML, overrides, switches, seed, version) filled in.
SpectralResult solve_spectrum(const SpectralSolver& solver, const Material& material, const SolverRequest& request);

// One member of a sweep: its base material, the swept values that make it (applied as --vary FIELD=VALUE, after the
// request's own overrides) and recorded in its result's provenance with the base's text (one text shared by every
// member, so that an output carries the base once and each member's values), and its index on each sweep axis.
struct SweepMember {
    std::shared_ptr<const Material> base;
    SweptValues varied;
    std::shared_ptr<const std::string> base_toml;  // unset: the member's own material is recorded
    std::vector<std::size_t> position;  // its index on each axis of the sweep (empty: not on a lattice)
    std::vector<MaterialOverride> overrides() const { return sweep_overrides(varied); }
    Material material() const { return with_overrides(*base, overrides()); }
    void build(Material& into) const { assign_with_values(into, *base, varied); }  // material() into `into`
};

// A sweep's members, made one at a time when they are solved: a list given whole, or a lattice (every combination
// of the axes' values on one base) that holds only its axes (a 64 x 64 sweep's 4096 stored members were 7 MB and
// a tenth of its time).
class SweepMembers {
public:
    SweepMembers(std::vector<SweepMember> list);  // NOLINT(google-explicit-constructor): a list is members
    SweepMembers(std::shared_ptr<const Material> base, std::shared_ptr<const std::string> base_toml, std::vector<SweepAxis> axes);
    std::size_t size() const { return list_.empty() ? lattice_size_ : list_.size(); }
    // Member i; a lattice's in sweep_grid order (the first axis fastest).
    SweepMember operator[](std::size_t i) const;
    const std::shared_ptr<const Material>& base(std::size_t i) const { return list_.empty() ? base_ : list_[i].base; }

private:
    std::vector<SweepMember> list_;
    std::shared_ptr<const Material> base_;
    std::shared_ptr<const std::string> base_toml_;
    std::vector<SweepAxis> axes_;
    std::shared_ptr<const std::vector<std::string>> fields_;
    std::size_t lattice_size_ = 0;
};

// The members of a sweep over `axes`, one per combination of their values (sweep_grid order; no axis: one
// member): `base` cut to the sub-stack of `layers` when given, each combination's overrides on it. The request and
// the sweep's corners (its extremes) are checked against the solver here, so that a bad input is refused before
// anything is solved.
SweepMembers sweep_members(const SpectralSolver& solver, const SolverRequest& request, const std::vector<SweepAxis>& axes,
                           const std::vector<std::string>& layers, const Material& base);
// Every member checked first, then solved together (solve_many: replayed where the solver can), the members of a
// solver that does not replay made, built and solved a block at a time. With `share` (several processes, e.g. MPI
// ranks), each process solves its share of the solver's groups and the first process gets every result, equal bit
// for bit to a one-process run; the others get none.
std::vector<SpectralResult> solve_sweep(const SpectralSolver& solver, const SweepMembers& members, const SolverRequest& request,
                                        const WorkShare* share = nullptr);
// The same, appended to `results` (what is there stays): a command gathers several sweeps' results in one list, each
// solved in place (moving a 64 x 64 sweep's results from list to list was fresh memory and a tenth of its time).
void solve_sweep(const SpectralSolver& solver, const SweepMembers& members, const SolverRequest& request, std::vector<SpectralResult>& results,
                 const WorkShare* share = nullptr);
SpectralProfiles solve_profiles(const SpectralSolver& solver, const Material& material, const ProfileRequest& request);
// Every material checked as solve_profiles checks it, then their profiles together (profiles_many).
std::vector<SpectralProfiles> solve_profiles(const SpectralSolver& solver, const std::vector<const Material*>& materials, const ProfileRequest& request);

}  // namespace skinspec
