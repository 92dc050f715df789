#include "transport/adding_doubling/phase_moments.hpp"

#include <cmath>

namespace skinspec {

std::vector<double> legendre_polynomials(double x, std::size_t count) {
    std::vector<double> p(count, 0.0);
    if (count > 0) p[0] = 1.0;
    if (count > 1) p[1] = x;
    for (std::size_t l = 2; l < count; ++l) {
        const double ll = static_cast<double>(l);
        p[l] = ((2.0 * ll - 1.0) * x * p[l - 1] - (ll - 1.0) * p[l - 2]) / ll;
    }
    return p;
}

std::vector<double> legendre_moments(const PhaseFunction& phase, std::size_t count) {
    std::vector<double> chi(count, 0.0);
    if (count == 0) return chi;
    using K = PhaseFunction::Kind;
    switch (phase.kind) {
        case K::henyey_greenstein:
            for (std::size_t l = 0; l < count; ++l) chi[l] = std::pow(phase.g, static_cast<double>(l));
            break;
        case K::two_term_hg:
            for (std::size_t l = 0; l < count; ++l) {
                const double ll = static_cast<double>(l);
                chi[l] = phase.weight * std::pow(phase.g, ll) + (1.0 - phase.weight) * std::pow(phase.g2, ll);
            }
            break;
        case K::isotropic: chi[0] = 1.0; break;
        case K::rayleigh:
            chi[0] = 1.0;
            if (count > 2) chi[2] = 0.1;
            break;
        case K::tabulated: {
            // Bonnet's recurrence per entry, accumulated in place: (l + 1) P_l+1 = (2l + 1) x P_l - l P_l-1.
            const auto& table = *phase.table;
            std::vector<double> a(count), b(count);
            for (std::size_t l = 1; l < count; ++l) {
                const double ll = static_cast<double>(l);
                a[l] = (2.0 * ll - 1.0) / ll;
                b[l] = (ll - 1.0) / ll;
            }
            for (std::size_t i = 0; i < table.size(); ++i) {
                const double x = table.cos_theta(i);
                double previous = 1.0, current = x;
                chi[0] += 1.0;
                if (count > 1) chi[1] += x;
                for (std::size_t l = 2; l < count; ++l) {
                    const double next = a[l] * x * current - b[l] * previous;
                    chi[l] += next;
                    previous = current;
                    current = next;
                }
            }
            for (auto& c : chi) c /= static_cast<double>(table.size());
            break;
        }
    }
    return chi;
}

}  // namespace skinspec
