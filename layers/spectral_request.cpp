#include "layers/spectral_request.hpp"

namespace skinspec {

std::vector<double> default_angular_bin_edges_deg() {
    std::vector<double> edges{0.0};
    for (double e = 2.5; e < 90.0; e += 5.0) edges.push_back(e);
    edges.push_back(90.0);
    return edges;
}

}  // namespace skinspec
