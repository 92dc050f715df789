#include "spectral/chromatic_adaptation.hpp"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace skinspec {
namespace {

// Bradford cone-response matrix M_BFD (Lam 1985), rows written out; GLM is column-major, hence transpose.
const glm::dmat3 bradford = glm::transpose(glm::dmat3(0.8951, 0.2664, -0.1614,   //
                                                      -0.7502, 1.7135, 0.0367,   //
                                                      0.0389, -0.0685, 1.0296));

glm::dvec3 vec(const XYZ& xyz) { return {xyz.X, xyz.Y, xyz.Z}; }

}  // namespace

XYZ white_from_chromaticity(const Chromaticity& xy) { return {xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y}; }

XYZ bradford_adapt(const XYZ& xyz, const XYZ& source_white, const XYZ& destination_white) {
    const glm::dvec3 cone_source = bradford * vec(source_white);
    const glm::dvec3 cone_destination = bradford * vec(destination_white);
    const glm::dvec3 cone = bradford * vec(xyz) * (cone_destination / cone_source);
    const glm::dvec3 out = glm::inverse(bradford) * cone;
    return {out.x, out.y, out.z};
}

}  // namespace skinspec
