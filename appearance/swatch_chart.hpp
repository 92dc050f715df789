#pragma once
// Colour charts of simulated skin: a grid over one or two fields of a material, each patch the colour of the
// reflectance from a registered solver (default the BioSpec walk); a Monte Carlo solver computes it only as
// precisely as the picture needs (a CIEDE2000 tolerance), a deterministic one exactly.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "materials/parameter_sweep.hpp"
#include "solvers/spectral_solver.hpp"
#include "materials/material_file.hpp"
#include "spectral/color_uncertainty.hpp"
#include "spectral/colorimetry.hpp"

namespace skinspec {


// The wavelengths a colour needs: 380-780 nm (where the CIE observers reach 1e-4 of their peak) at 5 nm
// below a tolerance of 1 (CIE 015:2018 Sec. 7.1 asks for 5 nm or finer; the haemoglobin bands of skin are
// ~20 nm wide), 10 nm for coarser tolerances.
WavelengthGrid swatch_wavelengths(double delta_e);

// The one geometry of every image skinspec makes of skin (the swatch chart, a lit patch, the look-up texture) and of
// what fit-image assumes of an image that does not state its own: sce, the light that entered the skin (docs/PROFILES.md,
// "One geometry"). Skin's surface is rough: its first-surface reflection is a glossy lobe about each light's mirror
// direction, which a view sees only where it sits in that lobe, while the light from inside leaves in every direction;
// an albedo (a renderer adds its own specular lobe, a cross-polarised capture removes it) is that diffuse part. sci (a
// spectrophotometer's sphere, `spectrum`'s default) is one --geometry away, and every image states its geometry.
inline constexpr MeasurementGeometry image_geometry = MeasurementGeometry::sce;

struct SwatchRequest {
    std::string material = "biospec-moderately";
    std::vector<MaterialOverride> overrides;
    std::vector<ParameterSweep> sweeps;  // first: columns, second: rows
    IlluminantKind illuminant = IlluminantKind::d65;
    ObserverKind observer = ObserverKind::cie1931_2deg;
    double delta_e = 0.3;
    std::uint64_t seed = 1;
    std::uint64_t max_rays_per_wavelength = 1'000'000;
    std::vector<std::string> sampling_options;  // as SolverRequest's: seed and ray budget given by the caller
    std::string solver = "biospec";  // a registry name (solvers/spectral_solver.hpp)
    MeasurementGeometry geometry = image_geometry;  // the colour of R measured this way
    std::size_t patches_per_sweep = 64;  // patches solved together (replayed); 1: each patch traced on its own
    SolverSwitches switches;
    std::function<void(std::size_t patches_done, std::size_t patches_total)> on_progress;
    const CancelFlag* cancel = nullptr;
    // Several processes (solvers/work_share.hpp): each solves every size()-th chunk; rank 0's chart has every
    // patch, equal bit for bit to a one-process chart, the other ranks' charts none.
    const WorkShare* work_share = nullptr;
};

struct SwatchPatch {
    std::vector<double> parameters;  // one value per sweep
    XYZ xyz;                         // perfect reflector Y = 1 under the request's illuminant
    Lab lab;
    ColorUncertainty uncertainty;  // from the spectral standard errors and the solver's stated error (color_uncertainty.hpp)
    std::vector<double> reflectance;         // R at the chart's wavelengths (the request's geometry)
    std::vector<double> reflectance_stderr;  // its standard errors (0 for deterministic solvers)
    std::uint64_t rays = 0;
    bool converged = true;
};

struct SwatchChart {
    std::size_t columns = 1;
    std::size_t rows = 1;
    std::vector<SwatchPatch> patches;  // row-major; finished patches only when cancelled
    XYZ white;
    WavelengthGrid wavelengths = WavelengthGrid::list({550.0});
    std::map<std::string, SettingValue> settings;
    std::vector<ResultWarning> warnings;  // every patch's, the patch's parameters in `at`
    bool partial = false;
};

// InputError for bad sweeps or materials before any ray is traced.
SwatchChart compute_swatch(const SwatchRequest& request);

// The sweeps a swatch of `material` makes when none are given: melanosome fraction (8, log) by dermal blood (5) for
// a skin with an epidermis and dermal layers, none (one patch) for anything else.
std::vector<ParameterSweep> default_swatch_sweeps(const Material& material);

}  // namespace skinspec
