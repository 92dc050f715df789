#include "formats/adding_doubling_reference.hpp"

#include <array>
#include <fstream>

#include <fmt/format.h>

#include "spectral/data_paths.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

RteStack AddingDoublingSlab::stack(double thickness_cm) const {
    const double mu_t = optical_thickness / thickness_cm;
    RteStack s;
    s.layers.push_back({refractive_index, mu_t * (1.0 - albedo), mu_t * albedo, thickness_cm, PhaseFunction::henyey_greenstein(g)});
    return s;
}

std::vector<AddingDoublingSlab> adding_doubling_slabs() {
    const auto file = data_file("reference/adding_doubling_slabs.csv");
    std::ifstream in(file);
    std::vector<AddingDoublingSlab> slabs;
    std::string line;
    bool header = false;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        const auto t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        if (!header) {
            if (t != "a,b,g,n_slab,rd,tt,a_abs") throw InputError(fmt::format("{}:{}: header must be a,b,g,n_slab,rd,tt,a_abs", file.string(), number));
            header = true;
            continue;
        }
        const auto fields = split_fields(t);
        if (fields.size() != 7) throw InputError(fmt::format("{}:{}: {} field(s) (allowed: 7)", file.string(), number, fields.size()));
        std::array<double, 7> v{};
        for (std::size_t k = 0; k < 7; ++k) {
            const auto x = parse_double(fields[k]);
            if (!x) throw InputError(fmt::format("{}:{}: field {} = '{}' is not a number", file.string(), number, k + 1, fields[k]));
            v[k] = *x;
        }
        slabs.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
    }
    if (slabs.empty()) throw InputError(file.string() + ": no reference slab");
    return slabs;
}

}  // namespace skinspec
