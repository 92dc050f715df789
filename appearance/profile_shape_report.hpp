#pragma once
// The R(r) shape check (solvers/profile_shape_check.hpp) as the files and the terminal state it: lines of text (the
// terminal, the profile CSV's comments, a lit swatch's image metadata) and JSON (`export profile`, Python).
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solvers/profile_shape_check.hpp"

namespace skinspec {

// A share off by more than this is worth a warning (else a note): diffusion in the regime it is made for (a thick,
// weakly absorbing, strongly scattering medium) is 0.08-0.14 off in this measure (tests/test_profile_shape_check.cpp).
inline constexpr double profile_shape_worth_a_warning = 0.15;

// One line that says what was compared, then one per checked wavelength; or the one line of not_checked; empty when
// nothing was checked.
std::vector<std::string> profile_shape_lines(const ProfileShapeCheck& check);
// What a Monte Carlo profile is and how precise (empty for a deterministic one): the exact transport, its photons per
// channel, and the largest standard error of the reflectance within a radius against the target (rte_profiles.hpp).
std::string profile_precision_line(const SpectralProfiles& profiles);
// The same over the members of a grid (each member's channels; their photons shared when one walk served them all).
std::string profile_precision_line(std::span<const SpectralProfiles> members);
// The lines joined by newlines (a lit swatch's image metadata).
std::string profile_shape_text(const ProfileShapeCheck& check);
// Whether the lines are a warning: a share off by more than profile_shape_worth_a_warning, or no check possible.
bool profile_shape_warns(const ProfileShapeCheck& check);
nlohmann::ordered_json profile_shape_json(const ProfileShapeCheck& check);

}  // namespace skinspec
