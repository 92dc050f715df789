#pragma once
// Spectral results as bytes, for results computed in another process (solvers/work_share.hpp): a flat binary
// layout of this build (numbers in the machine's own representation, doubles as IEEE binary64), so a result read
// back equals the one written bit for bit. Not a file format: both ends are the same program.
#include <string>
#include <vector>

#include "transport/spectral_request.hpp"

namespace skinspec {

std::string results_to_bytes(const std::vector<SpectralResult>& results);
// InputError for bytes that are not results_to_bytes output (truncated or corrupted).
std::vector<SpectralResult> results_from_bytes(const std::string& bytes);

}  // namespace skinspec
