#pragma once
// A material's radial profile R(r) as renderers take it: fitted as a sum of Gaussians with shared variances
// (inverse/gaussian_sum/gaussian_sum_fit.hpp; d'Eon, Luebke & Enderton 2007) per colour band (the profile's colour
// at each radius, in a linear RGB space) or per wavelength. `skinspec export profile` and skinspec.export_profile
// write the same JSON and table from here.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inverse/gaussian_sum/gaussian_sum_fit.hpp"
#include "materials/parameter_sweep.hpp"
#include "solvers/profile_shape_check.hpp"
#include "spectral/colorimetry.hpp"
#include "transport/diffusion/diffusion_profiles.hpp"

namespace skinspec {

enum class ProfileChannels { rgb, wavelength };
// "rgb" or "wavelength"; InputError naming `option` for anything else.
ProfileChannels parse_profile_channels(const std::string& text, std::string_view option);

struct ProfileExportRequest {
    ProfileChannels per = ProfileChannels::rgb;
    std::string space = "ACEScg";  // the linear RGB space of the bands (an OCIO colour space)
    IlluminantKind illuminant = IlluminantKind::d65;
    ObserverKind observer = ObserverKind::cie1931_2deg;
    std::size_t gaussians = 6;  // [1, 12]
};

struct ProfileExport {
    std::string material;
    std::string model;
    std::string channels_text;  // "bands", "RGB in ACEScg (D65, 2 deg)", "wavelengths"
    std::vector<std::string> names;
    std::vector<double> radii_mm;
    std::vector<double> total_reflectance;  // per channel: the solver's total diffuse R (the whole plane)
    GaussianSumFit fit;
    std::optional<ProfileShapeCheck> shape;  // the profiles' shape against the exact transport, where it was checked
};

// The wavelengths an RGB fit needs: CIE 015:2018 Sec. 7.1's 380-780 nm, every 10 nm.
WavelengthGrid rgb_profile_wavelengths();
// The wavelengths to solve: an RGB fit's own (InputError when wavelengths are `given` too: they would change nothing),
// else those given or 450, 550, 650 nm. `option` names them in the message.
WavelengthGrid profile_export_wavelengths(const ProfileExportRequest& request, const std::optional<WavelengthGrid>& given, std::string_view option);
// InputError, before any solve, for a band material fitted per wavelength or a Gaussian count outside [1, 12].
void check_profile_export(const std::string& material, bool bands, const ProfileExportRequest& request);
// `profiles`: per wavelength (an RGB fit integrates them against the observer) or per band (`bands`). InputError as
// check_profile_export and fit_gaussian_sum.
ProfileExport fit_profile_export(const SpectralProfiles& profiles, bool bands, const ProfileExportRequest& request);

// A grid of materials (a pigmentation sweep) fitted as a renderer interpolates it between texels: one set of variances
// for every member (fitted to the grid's corners and middle member together, every channel of each), each member's
// weights for them by non-negative least squares, each member's own errors. Axes: the swept fields and their values;
// members in sweep_grid order (the first axis fastest).
struct ProfileExportGrid {
    std::vector<SweepAxis> axes;
    std::vector<ProfileExport> members;
    std::vector<std::size_t> variances_fitted_to;  // member indices
};
// Beyond this many members a grid's materials and recorded exits outgrow a workstation's memory: split it.
inline constexpr std::size_t max_profile_grid_members = 4096;
// Every member of the grid `axes` (one or two) over `base`, in sweep_grid order, each built (refused as the reader
// refuses) before anything is solved. InputError for no axis, more than two or more than max_profile_grid_members.
std::vector<Material> profile_grid_members(const Material& base, const std::vector<SweepAxis>& axes);
// The members at the corners and the middle of a grid with these axis sizes (indices, increasing, no repeats).
std::vector<std::size_t> grid_corners_and_middle(const std::vector<std::size_t>& axis_sizes);
// InputError as fit_profile_export, and for a member count other than the product of the axis sizes.
ProfileExportGrid fit_profile_export_grid(const std::vector<SpectralProfiles>& members, std::vector<SweepAxis> axes, bool bands,
                                          const ProfileExportRequest& request);
// The grid as `skinspec export profile --vary ... -o F.json` writes it: the shared variances, then per member its
// values of the swept fields and its channels' weights and errors (as profile_export_json's "fit").
nlohmann::ordered_json profile_export_grid_json(const ProfileExportGrid& grid);
// Its CSV table: one row per member and channel: the swept fields' values, the channel, its weight per Gaussian (the
// variances in the header), the fit's total and relative L2 error.
std::string profile_export_grid_table_csv(const ProfileExportGrid& grid);

// The fit as `skinspec export profile -o F.json` writes it: variances, per channel weights and the fit's errors, and the
// profiles' shape check where there is one (appearance/profile_shape_report.hpp).
nlohmann::ordered_json profile_export_json(const ProfileExport& exported);
// "# skinspec ... sum-of-N-Gaussians fit of R(r): material ..., model ..., channels ..., r A-B mm" (one line).
std::string profile_export_header(const ProfileExport& exported);
// The CSV table (--table): header, units, then one row per Gaussian: variance_mm2, weight per channel.
std::string profile_export_table_csv(const ProfileExport& exported);

}  // namespace skinspec
