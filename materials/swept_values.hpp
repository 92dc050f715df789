#pragma once
// A sweep member's values of the swept fields (materials/parameter_sweep.hpp), as results record them.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace skinspec {

// One combination of swept values: the fields' names, shared by every member of a sweep (12,288 copies of the
// same names were a tenth of a dipole sweep's memory), and this member's value of each, in axis order.
struct SweptValues {
    std::shared_ptr<const std::vector<std::string>> fields;  // null: nothing swept
    std::vector<double> values;
    std::size_t size() const { return values.size(); }
    const std::string& field(std::size_t i) const { return (*fields)[i]; }
    bool operator==(const SweptValues& other) const;  // the same names (by text) and values
};

}  // namespace skinspec
