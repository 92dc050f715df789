#pragma once
// The linear system of Mukaigawa, Suzuki & Yagi 2009 (Sec. 3.2-3.3): the observed exitance of patch
// j is l_j = sum_k R(d_jk) c_k (Eq. 10); quantising distances into bins d'_i = i * step with linear weights
// (Eq. 16-19) turns it into l = W r (Eq. 22-23) with r the profile at the bins.
//
// Units: positions and distances in mm, c_k the power entering patch k (irradiance x patch area), l_j the
// exitance per mm^2 (pi L_o / F_t, Eq. 8), so R is per mm^2 as in the diffusion models.
#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Dense>
#include <glm/vec3.hpp>

namespace skinspec {

// A flat sample seen square-on: a pixel grid of `pitch_mm`, row-major.
struct PlanarScene {
    int width = 0;
    int height = 0;
    double pitch_mm = 0.0;
    std::vector<double> incident;  // c per pixel
    std::vector<double> observed;  // l per pixel
    std::vector<char> valid;       // 1: the pixel's l is used (its c is always used)
};

// A general surface patch (Mukaigawa et al. 2009 Sec. 3.2).
struct SurfacePatch {
    glm::dvec3 position_mm{0.0};
    double incident = 0.0;  // c_k, Eq. 9
    double observed = 0.0;  // l_j, Eq. 8
    bool visible = true;    // rows of W only for visible patches (Sec. 3.3)
};

struct ProfileSystem {
    double step_mm = 0.0;
    Eigen::MatrixXd w;                 // rows: used patches, columns: bins
    Eigen::VectorXd l;                 // observed values of the rows
    std::vector<std::size_t> rows;     // patch (pixel) index of each row
    std::vector<char> bin_has_data;    // 0 where no patch pair falls near the bin
    double bin_distance_mm(std::size_t i) const { return static_cast<double>(i) * step_mm; }
    std::size_t bins() const { return static_cast<std::size_t>(w.cols()); }
};

// InputError naming the problem: sizes that differ, no valid pixel, NaN or negative values, a non-positive
// pitch or step, more bins than valid patches (n > m: the least-squares problem would be under-determined).
// Planar scenes never loop over pixel pairs: each column of W is the incident image convolved with the
// bin's linear-weight tent, by FFT (layers/image_convolution.hpp).
ProfileSystem planar_system(const PlanarScene& scene, double step_mm);
// O(m^2) over patch pairs, in parallel.
ProfileSystem patch_system(const std::vector<SurfacePatch>& patches, double step_mm);

// Eq. 10 for a given profile R(d) (per mm^2), every pixel / patch: the re-synthesised observation.
std::vector<double> render_planar(const PlanarScene& scene, const std::function<double(double)>& profile);
std::vector<double> render_patches(const std::vector<SurfacePatch>& patches, const std::function<double(double)>& profile);

// Peak signal-to-noise ratio (dB) of `synthesised` against `observed` over the used entries; the peak is the
// largest observed value (Mukaigawa et al. 2009 Sec. 4.1).
double psnr_db(const std::vector<double>& observed, const std::vector<double>& synthesised, const std::vector<char>& used);

// Checks the scene (sizes, pitch, finite non-negative values, a non-empty mask); InputError otherwise.
void validate(const PlanarScene& scene);

}  // namespace skinspec
