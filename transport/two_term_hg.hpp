#pragma once
// Two-term Henyey-Greenstein phase function (Baranoski et al. 2005 Eq. 2; Kattawar 1975):
//   p = u p_HG(g1) + (1 - u) p_HG(g2),
// sampled by choosing a term with probability u, then HG warping (henyey_greenstein.hpp).
#include "transport/henyey_greenstein.hpp"

namespace skinspec {

inline double two_term_hg_sample_cos(double g1, double g2, double u_weight, double u_term, double u_angle) {
    return hg_sample_cos(u_term < u_weight ? g1 : g2, u_angle);
}
inline double two_term_hg_cdf_cos(double g1, double g2, double u_weight, double c) {
    return u_weight * hg_cdf_cos(g1, c) + (1.0 - u_weight) * hg_cdf_cos(g2, c);
}
inline double two_term_hg_pdf_cos(double g1, double g2, double u_weight, double c) {
    return u_weight * hg_pdf_cos(g1, c) + (1.0 - u_weight) * hg_pdf_cos(g2, c);
}

}  // namespace skinspec
