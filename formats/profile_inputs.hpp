#pragma once
// The files `skinspec fit-profile` reads (docs/PROFILE_FIT.md): a patch list CSV, a radial profile CSV, and
// a planar image pair (irradiance and exitance per mm^2, optional mask). Every problem is an InputError
// naming the file, the line or pixel, the field and what is allowed.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "inverse/profile_fit/profile_system.hpp"

namespace skinspec {

// One patch from x_mm, y_mm, z_mm, nx, ny, nz, c, l, visible (a unit normal, c and l >= 0, visible 0 or 1);
// InputError starting with `where` otherwise.
SurfacePatch surface_patch(const std::array<double, 9>& values, const std::string& where);
// x_mm,y_mm,z_mm,nx,ny,nz,c,l,visible (unit normals, c and l >= 0, visible 0 or 1).
std::vector<SurfacePatch> read_patch_list(const std::string& file);

struct RadialSamples {
    std::vector<double> radii_mm;
    std::vector<double> profile_per_mm2;  // per unit power entering the surface
    double entry_transmittance = 1.0;     // what the file's values were divided by (1: given per power entering)
};
// `skinspec profile` writes R per unit incident power, the entry Fresnel transmittance included, and records that
// transmittance per column in a comment line starting with this (" R_550nm_per_mm2=0.97, ...").
inline constexpr std::string_view radial_entry_transmittance_comment = "# entry transmittance per column (1 - specular):";
// r_mm and one profile column (the second, or `column` by name), as R per unit power entering: a column that the
// file records an entry transmittance for is divided by it (the dipole's R_d(r), Jensen et al. 2001 Eq. 4, is per
// unit power entering; fitting R per incident power to it biased marble's sigma_a fourfold).
RadialSamples read_radial_profile(const std::string& file, const std::string& column = {});

struct PlanarInputs {
    std::string irradiance, exitance, mask;  // file names; mask optional
    double pitch_mm = 0.0;
};
// InputError unless 0 < pitch_mm < inf.
void check_pitch(double pitch_mm);
// One channel of a planar image pair: irradiance per mm^2 becomes power per pixel (x pitch^2); row-major values,
// `valid` 1 where the exitance is used. fit_planar checks the values (validate(PlanarScene)).
PlanarScene planar_scene(int width, int height, double pitch_mm, std::vector<double> irradiance_per_mm2, std::vector<double> exitance_per_mm2,
                         std::vector<char> valid);
// One planar scene per colour channel of the image pair (alpha ignored): irradiance per mm^2 becomes power
// per pixel; `channel_names` gets the images' channel names. fit_planar checks the values (validate(PlanarScene)).
std::vector<PlanarScene> read_planar_scenes(const PlanarInputs& inputs, std::vector<std::string>& channel_names);

}  // namespace skinspec
