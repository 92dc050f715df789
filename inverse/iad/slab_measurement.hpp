#pragma once
// How a slab sample was measured for inverse adding-doubling (docs/IAD.md): the sample and its slides, the
// incident beam, and the integrating spheres (none, one or two) with their standards, as Prahl's `iad` describes
// them (its manual, "The Data File"; Pickering et al. 1993, Appl. Opt. 32:399). One table declares every number
// of the setup: the .rxt reader (header and data-column letters), the `skinspec iad` options, the Python keywords,
// the JSON output and the range checks all come from it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "materials/material_fields.hpp"

namespace skinspec {

// Port areas as fractions of the sphere's surface: (d_port / (2 d_sphere))^2 (iad manual, "The header").
struct SpherePorts {
    double sample = 0.0;
    double third = 0.0;  // the entrance port of a reflection sphere, the port opposite the sample of a transmission sphere
    double detector = 0.0;
    double wall = 1.0;
};

struct SlabSetup {
    double sample_index = 1.0;
    double slide_index = 1.0;
    double sample_thickness_mm = 1.0;
    double slide_thickness_mm = 0.0;
    double beam_diameter_mm = 1.0;  // recorded: only iad's lost-light Monte Carlo uses it, which skinspec does not model
    double incidence_deg = 0.0;
    double spheres = 0.0;  // 0, 1 or 2 (a number in the table; whole values only)
    double r_standard = 1.0;   // diffuse reflectance of the reflection standard
    double t_standard = 1.0;   // of the standard in the transmission sphere's third port
    double r_unscattered_collected = 1.0;  // fraction of the unscattered reflection the R measurement includes
    double t_unscattered_collected = 1.0;  // fraction of the unscattered transmission the T measurement includes
    double wall_first = 0.0;   // fraction of the beam hitting the reflection sphere's wall before the sample
    double g = 0.0;            // the anisotropy assumed when no unscattered transmission is measured
    double r_sphere_mm = 203.2, r_sample_port_mm = 25.4, r_entrance_port_mm = 12.7, r_detector_port_mm = 1.0;
    double r_wall = 0.96, r_detector = 0.0, r_baffle = 1.0;  // baffle: 1 present, 0 absent
    double t_sphere_mm = 203.2, t_sample_port_mm = 25.4, t_third_port_mm = 12.7, t_detector_port_mm = 1.0;
    double t_wall = 0.96, t_detector = 0.0, t_baffle = 1.0;

    SpherePorts r_ports() const;
    SpherePorts t_ports() const;
};

// One number of the setup: its key (option --key with '-' for '_', JSON and Python keyword), the letter of iad's
// data legend that sets it per row ('\0': none), unit, range and meaning.
struct SetupField {
    std::string_view key;
    char rxt_letter;
    std::string_view unit;
    FieldRange range;
    double SlabSetup::*member;
    std::string_view doc;
};
const std::vector<SetupField>& setup_fields();
const SetupField* setup_field(std::string_view key);  // nullptr: no such field
const SetupField* setup_field_by_letter(char letter);

// InputError naming `where`, the field, the value and its range for anything outside the table's ranges, a sphere
// count other than 0, 1, 2, a baffle other than 0, 1, or ports covering a sphere.
void validate(const SlabSetup& setup, std::string_view where);

// One row of measurements: M_R, M_T and the unscattered transmission M_U (absent: not measured), with the setup
// that row was measured in (the file's, with the row's own columns).
struct SlabMeasurement {
    std::optional<double> wavelength_nm;
    std::optional<double> m_r, m_t, m_u;
    SlabSetup setup;
    std::string source;  // "file.rxt:31" or "--r/--t", for messages
};

}  // namespace skinspec
