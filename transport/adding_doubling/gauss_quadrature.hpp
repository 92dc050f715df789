#pragma once
// Gauss-Legendre and Gauss-Radau quadrature on an interval (Golub & Welsch 1969, Math. Comp. 23:221, the
// eigenvalues of the Jacobi matrix of the Legendre polynomials; Radau by Golub 1973, SIAM Rev. 15:318, Sec. 7:
// the last diagonal entry modified so that a prescribed end point is a node).
#include <cstddef>
#include <vector>

namespace skinspec {

struct QuadratureRule {
    std::vector<double> nodes;    // increasing
    std::vector<double> weights;  // sum = b - a
};

// n-point Gauss-Legendre on [a, b]: exact for polynomials of degree 2n - 1.
QuadratureRule gauss_legendre(std::size_t n, double a, double b);
// n-point Gauss-Radau on [a, b] with the end point `fixed` (a or b) a node: exact to degree 2n - 2.
QuadratureRule gauss_radau(std::size_t n, double a, double b, double fixed);

}  // namespace skinspec
