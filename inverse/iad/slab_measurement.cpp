#include "inverse/iad/slab_measurement.hpp"

#include <cmath>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

using field_ranges::fraction, field_ranges::non_negative, field_ranges::positive;
constexpr FieldRange index_range = field_ranges::refractive_index;
constexpr FieldRange switch_range{0.0, 1.0, false, false};

SpherePorts ports(double sphere_mm, double sample_mm, double third_mm, double detector_mm) {
    const auto area = [&](double d) { return (d / (2.0 * sphere_mm)) * (d / (2.0 * sphere_mm)); };
    SpherePorts p{area(sample_mm), area(third_mm), area(detector_mm), 0.0};
    p.wall = 1.0 - p.sample - p.third - p.detector;
    return p;
}

}  // namespace

SpherePorts SlabSetup::r_ports() const { return ports(r_sphere_mm, r_sample_port_mm, r_entrance_port_mm, r_detector_port_mm); }
SpherePorts SlabSetup::t_ports() const { return ports(t_sphere_mm, t_sample_port_mm, t_third_port_mm, t_detector_port_mm); }

const std::vector<SetupField>& setup_fields() {
    using S = SlabSetup;
    static const std::vector<SetupField> fields{
        {"sample_index", 'n', "1", index_range, &S::sample_index, "refractive index of the sample"},
        {"slide_index", 'N', "1", index_range, &S::slide_index, "refractive index of the slides on both faces (1: no slides)"},
        {"sample_thickness_mm", 'd', "mm", positive, &S::sample_thickness_mm, "thickness of the sample"},
        {"slide_thickness_mm", 'D', "mm", non_negative, &S::slide_thickness_mm, "thickness of each slide (0: no slides)"},
        {"beam_diameter_mm", 'B', "mm", positive, &S::beam_diameter_mm,
         "diameter of the incident beam (iad's lost-light Monte Carlo only: recorded, not used)"},
        {"incidence_deg", 'i', "deg", {0.0, 90.0, false, true}, &S::incidence_deg, "polar angle of the incident beam in air"},
        {"spheres", 'S', "1", {0.0, 2.0, false, false}, &S::spheres, "integrating spheres used at a time: 0, 1 or 2"},
        {"r_standard", 'R', "1", {0.0, 1.0, true, false}, &S::r_standard, "diffuse reflectance of the reflection standard (what M_R reads on it)"},
        {"t_standard", 'T', "1", {0.0, 1.0, true, false}, &S::t_standard, "reflectance of the standard in the transmission sphere's third port"},
        {"r_unscattered_collected", 'c', "1", fraction, &S::r_unscattered_collected, "fraction of the unscattered reflection M_R includes"},
        {"t_unscattered_collected", 'C', "1", fraction, &S::t_unscattered_collected, "fraction of the unscattered transmission M_T includes"},
        {"wall_first", 'f', "1", {0.0, 1.0, false, true}, &S::wall_first, "fraction of the beam hitting the reflection sphere's wall before the sample"},
        {"g", 'g', "1", {-1.0, 1.0, true, true}, &S::g, "scattering anisotropy assumed when M_U is not measured"},
        {"r_sphere_mm", '\0', "mm", positive, &S::r_sphere_mm, "reflection sphere: diameter"},
        {"r_sample_port_mm", '\0', "mm", non_negative, &S::r_sample_port_mm, "reflection sphere: sample port diameter"},
        {"r_entrance_port_mm", '\0', "mm", non_negative, &S::r_entrance_port_mm, "reflection sphere: entrance port diameter"},
        {"r_detector_port_mm", '\0', "mm", non_negative, &S::r_detector_port_mm, "reflection sphere: detector port diameter"},
        {"r_wall", 'w', "1", fraction, &S::r_wall, "reflection sphere: wall reflectance (the letter also sets t_wall unless W is given)"},
        {"r_detector", '\0', "1", fraction, &S::r_detector, "reflection sphere: detector reflectance"},
        {"r_baffle", '\0', "1", switch_range, &S::r_baffle, "reflection sphere: 1 with a baffle between sample and detector, 0 without"},
        {"t_sphere_mm", '\0', "mm", positive, &S::t_sphere_mm, "transmission sphere: diameter"},
        {"t_sample_port_mm", '\0', "mm", non_negative, &S::t_sample_port_mm, "transmission sphere: sample port diameter"},
        {"t_third_port_mm", '\0', "mm", non_negative, &S::t_third_port_mm, "transmission sphere: third port diameter (0: none)"},
        {"t_detector_port_mm", '\0', "mm", non_negative, &S::t_detector_port_mm, "transmission sphere: detector port diameter"},
        {"t_wall", 'W', "1", fraction, &S::t_wall, "transmission sphere: wall reflectance"},
        {"t_detector", '\0', "1", fraction, &S::t_detector, "transmission sphere: detector reflectance"},
        {"t_baffle", '\0', "1", switch_range, &S::t_baffle, "transmission sphere: 1 with a baffle between sample and detector, 0 without"},
    };
    return fields;
}

const SetupField* setup_field(std::string_view key) {
    for (const auto& f : setup_fields()) {
        if (f.key == key) return &f;
    }
    return nullptr;
}

const SetupField* setup_field_by_letter(char letter) {
    for (const auto& f : setup_fields()) {
        if (f.rxt_letter == letter) return &f;
    }
    return nullptr;
}

void validate(const SlabSetup& setup, std::string_view where) {
    const std::string at = where.empty() ? std::string() : std::string(where) + ": ";
    for (const auto& f : setup_fields()) {
        const double v = setup.*(f.member);
        if (!f.range.contains(v)) throw InputError(at + std::string(f.key) + " = " + format_number(v) + " is outside " + f.range.text());
    }
    const auto whole = [&](std::string_view key, double v, std::string_view allowed) {
        if (v != std::floor(v)) throw InputError(at + std::string(key) + " = " + format_number(v) + " is not one of " + std::string(allowed));
    };
    whole("spheres", setup.spheres, "0, 1, 2");
    whole("r_baffle", setup.r_baffle, "0, 1");
    whole("t_baffle", setup.t_baffle, "0, 1");
    if (setup.spheres > 0.0) {
        for (const auto& [name, p] : {std::pair{"reflection", setup.r_ports()}, std::pair{"transmission", setup.t_ports()}}) {
            if (!(p.wall > 0.0)) {
                throw InputError(at + "the " + std::string(name) + " sphere's ports cover " + format_number(1.0 - p.wall) +
                                 " of its surface (their areas (d_port / (2 d_sphere))^2 must sum to less than 1)");
            }
        }
    }
}

}  // namespace skinspec
