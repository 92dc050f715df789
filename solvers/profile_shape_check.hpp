#pragma once
// How far a deterministic solver's radial profile R(r) is in shape from the exact transport of the same skin, stated
// where the profile is used (`profile`, `export profile`, `swatch --lit`; issue 31: a mode's model error is stated where
// it is used). The reference is the volumetric walk's R(r) (solver 'rte', the layers' volumetric description: for the
// BioSpec presets the one derived from the BioSpec model), at a few wavelengths. Both profiles are normalised to their
// diffuse reflectance within 0-5 mm, so the comparison is of shape only (the totals are stated by the spectra), as the
// share of that reflectance leaving within each radius: a renderer's kernel spreads light by that share.
// docs/DIFFUSION.md, "The R(r) shape stated where it is used".
#include <cstdint>
#include <string>
#include <vector>

#include "solvers/spectral_solver.hpp"

namespace skinspec {

struct ProfileShapeError {
    double wavelength_nm = 0.0;
    std::uint64_t photons = 0;  // of the walk
    bool compared = true;       // false: the walk's or the solver's profile carries no light within 5 mm (all below 0)
    // The largest difference, over the rings' outer radii up to 5 mm, of the share of R leaving within that radius
    // (the solver's minus the walk's), where it is largest in size, and the walk's standard error of its share there
    // (rings taken as independent: a photon leaves once).
    double largest_share_difference = 0.0;
    double at_radius_mm = 0.0;
    double walk_share_stderr = 0.0;
    // The shares of the rings of radius up to 0.1 mm and from 1 mm on (a ring's radius is its centre).
    double solver_share_within_0_1_mm = 0.0, walk_share_within_0_1_mm = 0.0;
    double solver_share_beyond_1_mm = 0.0, walk_share_beyond_1_mm = 0.0;
};

struct ProfileShapeCheck {
    std::vector<ProfileShapeError> errors;  // per checked wavelength (fewer when stopped)
    bool stopped = false;
    std::string not_checked;  // stated_profile_shape: why a solver's profiles that are checked could not be (the walk's refusal)
};

// Photons of the walk per checked wavelength: the share's standard error is then about 0.005 or less on the presets.
inline constexpr std::uint64_t profile_shape_photons = 100'000;

// Whether check_profile_shape states something for `solver` on `material`: a deterministic solver with radial profiles
// (a walk's profile is the reference itself) and a layered material (band materials have no layers for the walk).
bool profile_shape_checked(const SpectralSolver& solver, const Material& material);

// The wavelengths checked out of `wavelengths`: those nearest 450, 550 and 650 nm, each once, in order.
std::vector<double> profile_shape_wavelengths(const WavelengthGrid& wavelengths);

// The check at profile_shape_wavelengths(wavelengths), the walk with `photons` per wavelength and seed 1, rings of
// 0.01 mm to 5 mm; the solver with `switches` on the same radii. `cancel` stops the walk (stopped, the wavelengths
// finished). InputError from either solver (e.g. a layer the walk cannot describe) passes through.
ProfileShapeCheck check_profile_shape(const SpectralSolver& solver, const Material& material, const WavelengthGrid& wavelengths,
                                      const SolverSwitches& switches, std::uint64_t photons = profile_shape_photons,
                                      const CancelFlag* cancel = nullptr);
// What a command states: nothing unless profile_shape_checked, else check_profile_shape with profile_shape_photons, an
// InputError of it as not_checked.
ProfileShapeCheck stated_profile_shape(const SpectralSolver& solver, const Material& material, const WavelengthGrid& wavelengths,
                                       const SolverSwitches& switches, const CancelFlag* cancel);

}  // namespace skinspec
