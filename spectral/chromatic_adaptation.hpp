#pragma once
// Bradford chromatic adaptation (Lam 1985; the linearised form of CIE 160:2004 Sec. 5 and ICC.1:2010
// Annex E): von Kries scaling of cone-like responses M_BFD * XYZ from a source white to a destination white.
#include "spectral/colorimetry.hpp"

namespace skinspec {

// XYZ of a white given by its chromaticity, scaled to Y = 1.
XYZ white_from_chromaticity(const Chromaticity& xy);

// XYZ seen under `source_white` -> corresponding XYZ under `destination_white`.
XYZ bradford_adapt(const XYZ& xyz, const XYZ& source_white, const XYZ& destination_white);

}  // namespace skinspec
