#pragma once
// CIEDE2000 colour difference (CIE 142-2001), implemented as in Sharma, Wu & Dalal 2005,
// Color Res. Appl. 30(1):21-30, Eq. 1-22, with parametric factors kL = kC = kH = 1 by default.
#include "spectral/colorimetry.hpp"

namespace skinspec {

struct Ciede2000Factors {
    double kL = 1.0;
    double kC = 1.0;
    double kH = 1.0;
};

double ciede2000(const Lab& reference, const Lab& sample, const Ciede2000Factors& factors = {});

}  // namespace skinspec
