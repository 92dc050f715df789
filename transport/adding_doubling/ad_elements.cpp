#include "transport/adding_doubling/ad_elements.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "spectral/input_error.hpp"
#include "transport/adding_doubling/gauss_quadrature.hpp"
#include "transport/adding_doubling/phase_moments.hpp"
#include "transport/fresnel.hpp"

namespace skinspec {

double AdChannels::cosine(std::size_t k, double n) const {
    return s[k] < n ? std::sqrt(std::max(0.0, 1.0 - (s[k] / n) * (s[k] / n))) : 0.0;
}

AdElement fresnel_interface(const AdChannels& c, double n1, double n2) {
    const auto size = static_cast<Eigen::Index>(c.size());
    AdElement e{AdElement::Kind::interface, AdVector::Zero(size), AdVector::Zero(size), AdVector::Zero(size), {}, {}, {}, {}};
    for (std::size_t k = 0; k < c.size(); ++k) {
        const auto kk = static_cast<Eigen::Index>(k);
        const bool above = c.s[k] < n1, below = c.s[k] < n2;
        if (above && below) {
            const double f = fresnel_reflectance(c.cosine(k, n1), n1, n2);
            e.r_top_diagonal(kk) = e.r_bottom_diagonal(kk) = f;
            e.t_diagonal(kk) = 1.0 - f;
        } else if (above) {
            e.r_top_diagonal(kk) = 1.0;  // total internal reflection
        } else if (below) {
            e.r_bottom_diagonal(kk) = 1.0;
        }
    }
    return e;
}


namespace {

// `indices`: every medium's index; `layer_indices`: the layers' (where light scatters, so where the quadrature
// should be Gaussian in the cosine). `refinement` multiplies every segment's node count (the accuracy check: 2).
AdChannels make_channels(const std::vector<double>& indices, const std::vector<double>& layer_indices, std::size_t per_hemisphere,
                       double incident_s, bool collimated, std::size_t refinement) {
    std::vector<double> breaks{0.0};
    for (const double n : indices) breaks.push_back(n);
    if (collimated && incident_s > 0.0) breaks.push_back(incident_s);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    const double n_max = breaks.back();
    AdChannels c;
    std::vector<std::pair<double, double>> nodes;  // (s, measure)
    bool incident_found = false;
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
        const double s_lo = breaks[b], s_hi = breaks[b + 1];
        // The segment's own medium, whose cosine is the quadrature variable: the lowest-index layer that covers it
        // (Gaussian where the light scatters; the others see smooth functions of it), else the lowest medium.
        double owner = n_max;
        bool in_a_layer = false;
        for (const double n : layer_indices) {
            if (n >= s_hi) {
                owner = std::min(owner, n);
                in_a_layer = true;
            }
        }
        if (!in_a_layer) {
            for (const double n : indices) {
                if (n >= s_hi) owner = std::min(owner, n);
            }
        }
        const double mu_hi = std::sqrt(std::max(0.0, 1.0 - (s_lo / owner) * (s_lo / owner)));
        const double mu_lo = std::sqrt(std::max(0.0, 1.0 - (s_hi / owner) * (s_hi / owner)));
        const double share = (s_hi * s_hi - s_lo * s_lo) / (n_max * n_max);
        // Every segment gets at least 1/12 of the nodes (2 at the default 24), and the accuracy check doubles every
        // segment's: with a fixed floor of 2, a thin segment (the grazing band that propagates in the epidermis but in
        // no dermal layer, trapped between two total internal reflections) kept 2 nodes up to ~100 channels, so
        // doubling the channels did not refine it and the check missed its error (forearm-nist2017-p10 at 700 nm:
        // off by 0.0086 at 24 channels, stated 0.0047; docs/ADDING_DOUBLING.md, "Convergence in the channels").
        const auto m = refinement * std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(std::max(share, 1.0 / 12.0) *
                                                                                                 static_cast<double>(per_hemisphere))));
        QuadratureRule rule;
        const bool fixed_at_lo_s = collimated && s_lo == incident_s;
        const bool fixed_at_hi_s = collimated && s_hi == incident_s && !incident_found;
        if (fixed_at_lo_s && !incident_found) rule = gauss_radau(m, mu_lo, mu_hi, mu_hi);
        else if (fixed_at_hi_s) rule = gauss_radau(m, mu_lo, mu_hi, mu_lo);
        else rule = gauss_legendre(m, mu_lo, mu_hi);
        for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
            const double mu = rule.nodes[i];
            const double s = owner * std::sqrt(std::max(0.0, 1.0 - mu * mu));
            nodes.emplace_back(s, 2.0 * owner * owner * mu * rule.weights[i]);  // d(s^2) = 2 n^2 mu dmu
        }
        if (fixed_at_lo_s || fixed_at_hi_s) incident_found = true;
    }
    std::sort(nodes.begin(), nodes.end());
    for (const auto& [s, w] : nodes) {
        c.s.push_back(s);
        c.measure.push_back(w);
    }
    if (collimated) {
        // The node placed at the incident s (exact by construction; the nearest within rounding).
        std::size_t best = 0;
        for (std::size_t k = 0; k < c.size(); ++k) {
            if (std::abs(c.s[k] - incident_s) < std::abs(c.s[best] - incident_s)) best = k;
        }
        c.incident = best;
        c.s[best] = incident_s;
    }
    return c;
}

// The Lambertian reflector of reflectance rho under a layer of index n: of any incident flux, rho leaves upward as c_i.
AdElement lambertian_reflector(const AdChannels& c, double n, double rho) {
    const auto size = static_cast<Eigen::Index>(c.size());
    AdElement e{AdElement::Kind::reflector, {}, {}, {}, AdMatrix::Zero(size, size), {}, {}, {}};
    for (std::size_t i = 0; i < c.size(); ++i) {
        for (std::size_t j = 0; j < c.size(); ++j) {
            if (c.s[j] < n) e.r(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rho * c.weight(i, n);
        }
    }
    return e;
}

std::vector<double> cosines_of(const PhaseFunction& phase) {
    std::vector<double> out;
    if (phase.kind == PhaseFunction::Kind::tabulated) {
        for (std::size_t i = 0; i < phase.table->size(); ++i) out.push_back(phase.table->cos_theta(i));
    }
    return out;
}

bool same_scattering(const AdCache::Entry& e, const PhaseFunction& phase, const std::vector<double>& cosines, double n, const AdChannels& c) {
    return e.phase.kind == phase.kind && e.phase.g == phase.g && e.phase.g2 == phase.g2 && e.phase.weight == phase.weight && e.n == n &&
           e.table_cosines == cosines && e.channel_s == c.s;
}

// A tabulated phase function as a density in x = cos theta: its N equal-probability angles, equal ones merged, each
// spread evenly over the cell between the midpoints to its neighbours (the ends at the last point's half-spacing,
// within [-1, 1]). Cells from x = 1 down: bounds[k] > bounds[k + 1], mass[k] in cell k.
struct TableCells {
    std::vector<double> bounds, mass;
};

TableCells table_cells(const InverseCdfTable& table) {
    std::vector<double> x;
    std::vector<double> mass;
    const double each = 1.0 / static_cast<double>(table.size());
    for (std::size_t j = 0; j < table.size(); ++j) {
        const double c = table.cos_theta(j);
        if (!x.empty() && c == x.back()) mass.back() += each;
        else {
            x.push_back(c);
            mass.push_back(each);
        }
    }
    TableCells cells{{}, std::move(mass)};
    const std::size_t n = x.size();
    if (n == 1) {
        cells.bounds = {std::min(1.0, x[0] + 1e-6), std::max(-1.0, x[0] - 1e-6)};
        return cells;
    }
    cells.bounds.push_back(std::min(1.0, x[0] + 0.5 * (x[0] - x[1])));
    for (std::size_t k = 1; k < n; ++k) cells.bounds.push_back(0.5 * (x[k - 1] + x[k]));
    cells.bounds.push_back(std::max(-1.0, x[n - 1] - 0.5 * (x[n - 2] - x[n - 1])));
    return cells;
}

// H(mu_i | -mu_j) = int_0^2pi p(cos Theta) dphi (p per steradian), cos Theta = a + b cos phi, a = -mu_i mu_j,
// b = sqrt(1 - mu_i^2) sqrt(1 - mu_j^2): a cell [lo, hi] of density m / (hi - lo) in x contributes
// m / (hi - lo) (arcsin((hi - a) / b) - arcsin((lo - a) / b)) / pi (the azimuth's density in x is 1 / (pi sqrt(b^2 - (x - a)^2))).
double opposite_azimuthal_mean(const TableCells& cells, double mu_i, double mu_j) {
    const double a = -mu_i * mu_j;
    const double b = std::sqrt(std::max(0.0, (1.0 - mu_i * mu_i) * (1.0 - mu_j * mu_j)));
    const auto arc = [&](double x) { return std::asin(std::clamp((x - a) / b, -1.0, 1.0)); };
    // Only the cells that meet [a - b, a + b] (bounds fall with k; most of a forward profile's mass lies above a + b),
    // each bound's arcsine once (a cell's lower bound is the next one's upper).
    const auto& bounds = cells.bounds;
    const auto below_top = std::upper_bound(bounds.begin(), bounds.end(), a + b, std::greater<>());  // first bound < a + b
    std::size_t k = below_top == bounds.begin() ? 0 : static_cast<std::size_t>(below_top - bounds.begin()) - 1;
    double h = 0.0;
    double arc_hi = arc(bounds[k]);
    for (; k < cells.mass.size() && bounds[k] > a - b; ++k) {
        const double arc_lo = arc(bounds[k + 1]);
        h += cells.mass[k] / (bounds[k] - bounds[k + 1]) * (arc_hi - arc_lo);
        arc_hi = arc_lo;
    }
    return h / std::numbers::pi;
}

// The entry of `e`'s channels and index from the phase function's Legendre moments chi (redistribution_moment_count
// of them).
AdCache::Entry redistribution(AdCache::Entry e, const AdChannels& c, std::vector<double> chi) {
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (c.s[k] < e.n) e.live.push_back(k);
    }
    const double n = e.n;
    const auto m = static_cast<Eigen::Index>(e.live.size());
    // Delta-M with 2m moments kept: f = chi_2m (Wiscombe 1977), for a forward peak only (a backward-peaked phase
    // function has chi_2m > 0 too, but its truncated part is not light going on unscattered).
    const std::size_t moments = 2 * e.live.size();
    const double f = chi[moments];
    // A forward delta (every chi_l = 1: HG with g = 1) deflects nothing: f = 1, and the series below, an expansion
    // of the delta that oscillates, carries no weight (1 - f = 0). Left unscaled it was used as the redistribution
    // (biospec-adding-doubling, dermis HG g = 1: R 0.420 against the walk's 0.508 at 700 nm, 0.027 stated).
    if (f >= 1.0) e.f = 1.0;
    else if (f > 0.0 && chi[moments + 1] > 0.0) {
        e.f = f;
        for (std::size_t l = 0; l < moments; ++l) chi[l] = (chi[l] - f) / (1.0 - f);
    }
    chi.resize(moments);
    AdVector mu(m), w(m), cw(m);
    for (Eigen::Index i = 0; i < m; ++i) {
        const auto k = e.live[static_cast<std::size_t>(i)];
        mu(i) = c.cosine(k, n);
        cw(i) = c.weight(k, n);
        w(i) = cw(i) / (2.0 * mu(i));  // the dmu weight
    }
    // H(mu_i | +-mu_j) = sum_l (2l + 1) / 2 chi_l P_l(mu_i) P_l(+-mu_j); P_l(-x) = (-1)^l P_l(x).
    AdMatrix pl(m, static_cast<Eigen::Index>(moments));
    for (Eigen::Index i = 0; i < m; ++i) {
        const auto p = legendre_polynomials(mu(i), moments);
        for (std::size_t l = 0; l < moments; ++l) pl(i, static_cast<Eigen::Index>(l)) = p[l];
    }
    AdVector even(static_cast<Eigen::Index>(moments)), odd(static_cast<Eigen::Index>(moments));
    for (std::size_t l = 0; l < moments; ++l) {
        const double coefficient = (2.0 * static_cast<double>(l) + 1.0) / 2.0 * chi[l];
        even(static_cast<Eigen::Index>(l)) = coefficient;
        odd(static_cast<Eigen::Index>(l)) = l % 2 == 0 ? coefficient : -coefficient;
    }
    // The truncated series of a strongly forward phase function dips below zero in places (g -> 1): those entries
    // are set to 0 (a redistribution is a probability) before the energy renormalisation below.
    AdMatrix same = (pl * even.asDiagonal() * pl.transpose()).cwiseMax(0.0);
    // A tabulated phase (the measured thin-layer profiles) turns no light back, but its truncated series rings into
    // the backward directions, and what rings above 0 was kept: one layer of the stratum corneum's profile, mu_s d = 1,
    // R_d 0.0053 at 16 channels against the walk's 0.00099 (docs/ADDING_DOUBLING.md). Between opposite hemispheres the
    // forward delta that delta-M removes plays no part, so there the truncated phase is p / (1 - f) exactly: taken
    // from the table over the azimuth instead of from the series.
    AdMatrix opposite(m, m);
    if (e.phase.kind == PhaseFunction::Kind::tabulated && e.phase.table && e.moments.empty() && e.f < 1.0) {
        const auto cells = table_cells(*e.phase.table);
        for (Eigen::Index i = 0; i < m; ++i) {
            for (Eigen::Index j = 0; j < m; ++j) opposite(i, j) = opposite_azimuthal_mean(cells, mu(i), mu(j)) / (1.0 - e.f);
        }
    } else {
        opposite = (pl * odd.asDiagonal() * pl.transpose()).cwiseMax(0.0);
    }
    // Energy: scattered light from every direction j integrates to 1 (correction on the diagonal, Prahl 1995).
    for (Eigen::Index j = 0; j < m; ++j) {
        double total = 0.0;
        for (Eigen::Index i = 0; i < m; ++i) total += (same(i, j) + opposite(i, j)) * w(i);
        same(j, j) += (1.0 - total) / w(j);
    }
    e.mu = mu;
    e.w = w;
    e.cw = cw;
    e.same = std::move(same);
    e.opposite = opposite;
    return e;
}

}  // namespace

namespace {

// Least recently used last out: a spectrum's tabulated phases inside 400-546 nm differ at every wavelength, so an
// unbounded cache would grow with the wavelength count.
template <typename Same, typename Make>
const std::shared_ptr<const AdCache::Entry>& cached_entry(AdCache& cache, const Same& same, const Make& make) {
    constexpr std::size_t capacity = 16;
    auto& entries = cache.entries;
    for (auto it = entries.begin(); it != entries.end(); ++it) {
        if (same(**it)) {
            std::rotate(it, it + 1, entries.end());
            return entries.back();
        }
    }
    if (entries.size() == capacity) entries.erase(entries.begin());
    entries.push_back(std::make_shared<const AdCache::Entry>(make()));
    return entries.back();
}

}  // namespace

std::size_t redistribution_moment_count(const AdChannels& c, double n) {
    std::size_t live = 0;
    for (const double s : c.s) live += s < n ? 1 : 0;
    return 2 * live + 2;
}

const std::shared_ptr<const AdCache::Entry>& cached_redistribution(const AdChannels& c, double n, const PhaseFunction& phase, AdCache& cache) {
    auto cosines = cosines_of(phase);
    return cached_entry(
        cache, [&](const AdCache::Entry& e) { return e.moments.empty() && same_scattering(e, phase, cosines, n, c); },
        [&] {
            const auto count = redistribution_moment_count(c, n);
            return redistribution(AdCache::Entry{phase, std::move(cosines), {}, n, c.s, {}, 0.0, {}, {}, {}, {}, {}}, c, legendre_moments(phase, count));
        });
}

const std::shared_ptr<const AdCache::Entry>& cached_redistribution(const AdChannels& c, double n, const std::vector<double>& moments, AdCache& cache) {
    return cached_entry(
        cache, [&](const AdCache::Entry& e) { return e.moments == moments && e.n == n && e.channel_s == c.s; },
        [&] { return redistribution(AdCache::Entry{{}, {}, moments, n, c.s, {}, 0.0, {}, {}, {}, {}, {}}, c, moments); });
}


namespace {

struct Solution {
    double specular = 0.0, diffuse = 0.0, transmittance = 0.0;
    std::vector<double> absorbed;
};

// Everything below a level as one reflection operator S (flux from above -> flux back up), built bottom-up by adding
// one element E on top (van de Hulst 1980, Eq. 4.25; Prahl 1995, Eq. 5.17):
//   S' = R_E + T'_E S (1 - R'_E S)^-1 T_E,
// with the factor 1 - R'_E S kept for the fluxes: the downward flux under E is x = (1 - R'_E S)^-1 T_E d for the
// flux d arriving on E, and S x goes back up through it.
struct Level {
    AdMatrix reflection;                    // S of this element and everything below it
    Eigen::PartialPivLU<AdMatrix> factor;   // of 1 - R'_E S_below (empty for the bottom element)
    bool identity = false;                  // R'_E = 0 (BioSpec's layers reflect nothing back down): the factor is 1
};

// X M^-1 for the factored M, as (M^T)^-1 X^T transposed.
AdMatrix right_solve(const Eigen::PartialPivLU<AdMatrix>& factor, const AdMatrix& x) {
    const AdMatrix rhs = x.transpose();
    const AdMatrix solved = factor.transpose().solve(rhs);
    return solved.transpose();
}

AdMatrix reflection_with(const AdElement& e, const AdMatrix& below, Level& level) {
    auto& factor = level.factor;
    const auto n = below.rows();
    if (e.kind == AdElement::Kind::reflector) return e.r;
    const AdMatrix identity = AdMatrix::Identity(n, n);
    if (e.kind == AdElement::Kind::interface) {
        factor.compute(identity - e.r_bottom_diagonal.asDiagonal() * below);
        // S (1 - R' S)^-1 by a transposed solve, then the diagonal transmissions on both sides.
        const AdMatrix y = right_solve(factor, below);
        AdMatrix s = e.t_diagonal.asDiagonal() * y * e.t_diagonal.asDiagonal();
        s.diagonal() += e.r_top_diagonal;
        return s;
    }
    if (e.reflection_from_below().isZero(0.0)) {
        level.identity = true;
        return e.r + e.transmission_up() * below * e.t;
    }
    factor.compute(identity - e.reflection_from_below() * below);
    const AdMatrix y = right_solve(factor, below);
    return e.r + e.transmission_up() * y * e.t;
}

AdVector transmit(const AdElement& e, const AdVector& flux) {
    if (e.kind == AdElement::Kind::interface) return e.t_diagonal.cwiseProduct(flux);
    if (e.kind == AdElement::Kind::layer) return e.t * flux;
    return AdVector::Zero(flux.size());
}

// Two diagonal elements (interfaces, a transparent layer's propagation), `upper` over `lower`, as one: adding with
// diagonal operators (van de Hulst 1980, ch. 4; per channel R = r1 + t1^2 r2 / (1 - r1' r2), T = t1 t2 / (1 - r1' r2)).
// A channel that crosses neither never reaches the denominator (it is 0 only under total reflection on both sides).
AdElement added_diagonal(const AdElement& upper, const AdElement& lower) {
    const auto size = upper.t_diagonal.size();
    AdElement e{AdElement::Kind::interface, AdVector::Zero(size), AdVector::Zero(size), AdVector::Zero(size), {}, {}, {}, {}};
    for (Eigen::Index k = 0; k < size; ++k) {
        const double tu = upper.t_diagonal(k), tl = lower.t_diagonal(k);
        const double bounce = 1.0 - upper.r_bottom_diagonal(k) * lower.r_top_diagonal(k);
        e.r_top_diagonal(k) = upper.r_top_diagonal(k) + (tu > 0.0 ? tu * tu * lower.r_top_diagonal(k) / bounce : 0.0);
        e.r_bottom_diagonal(k) = lower.r_bottom_diagonal(k) + (tl > 0.0 ? tl * tl * upper.r_bottom_diagonal(k) / bounce : 0.0);
        e.t_diagonal(k) = tu > 0.0 && tl > 0.0 ? tu * tl / bounce : 0.0;
    }
    return e;
}

// A transparent layer of index n as a diagonal element: every channel that propagates in it crosses it unchanged.
AdElement clear_propagation(const AdChannels& c, double n) {
    const auto size = static_cast<Eigen::Index>(c.size());
    AdElement e{AdElement::Kind::interface, AdVector::Zero(size), AdVector::Zero(size), AdVector::Zero(size), {}, {}, {}, {}};
    for (std::size_t k = 0; k < c.size(); ++k) e.t_diagonal(static_cast<Eigen::Index>(k)) = c.s[k] < n ? 1.0 : 0.0;
    return e;
}

Solution solve_with(const AdStackShape& shape, const AdIncidence& incidence, std::size_t per_hemisphere, std::size_t refinement,
                    const AdLayerMaker& make_layer, const std::atomic<bool>* cancel) {
    std::vector<double> indices{shape.above_refractive_index};
    indices.insert(indices.end(), shape.layer_indices.begin(), shape.layer_indices.end());
    if (!shape.bottom_reflector) indices.push_back(shape.below_refractive_index);
    constexpr double deg = std::numbers::pi / 180.0;
    const double n0 = shape.above_refractive_index;
    const double incident_s = incidence.diffuse ? 0.0 : n0 * std::sin(incidence.angle_deg * deg);
    const auto channels = make_channels(indices, shape.layer_indices, per_hemisphere, incident_s, !incidence.diffuse, refinement);
    const auto n = static_cast<Eigen::Index>(channels.size());

    std::vector<AdElement> elements;
    std::vector<int> layer_of;  // per element: layer index or -1
    double above = n0;
    // A diagonal element (interface, transparent layer) under another is added into it.
    const auto push_diagonal = [&](AdElement e) {
        if (!elements.empty() && layer_of.back() < 0) {
            elements.back() = added_diagonal(elements.back(), e);
        } else {
            elements.push_back(std::move(e));
            layer_of.push_back(-1);
        }
    };
    const std::size_t layers = shape.layer_indices.size();
    for (std::size_t k = 0; k < layers; ++k) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return {};
        const double index = shape.layer_indices[k];
        push_diagonal(fresnel_interface(channels, above, index));
        above = index;
        // A transparent layer with an interface under it: one with the interfaces around it (AdStackShape).
        if (k < shape.transparent.size() && shape.transparent[k] && (k + 1 < layers || !shape.bottom_reflector)) {
            push_diagonal(clear_propagation(channels, index));
            continue;
        }
        // The collimated beam's cosine in this layer (Snell: the same s); 1 for diffuse incidence.
        const double beam = incidence.diffuse || channels.s[channels.incident] >= index ? 1.0 : std::max(channels.cosine(channels.incident, index), 1e-6);
        elements.push_back(make_layer(channels, k, beam));
        layer_of.push_back(static_cast<int>(k));
    }
    if (shape.bottom_reflector) {
        elements.push_back(lambertian_reflector(channels, above, shape.bottom_reflectance));
        layer_of.push_back(-1);
    } else {
        push_diagonal(fresnel_interface(channels, above, shape.below_refractive_index));
    }

    AdVector incident = AdVector::Zero(n);
    if (incidence.diffuse) {
        for (std::size_t k = 0; k < channels.size(); ++k) incident(static_cast<Eigen::Index>(k)) = channels.weight(k, n0);
    } else {
        incident(static_cast<Eigen::Index>(channels.incident)) = 1.0;
    }
    // Bottom-up: the reflection of every suffix (levels[e] = element e and all below it); nothing returns from
    // under the last element.
    const std::size_t count = elements.size();
    std::vector<Level> levels(count + 1);
    levels[count].reflection = AdMatrix::Zero(n, n);
    for (std::size_t e = count; e-- > 0;) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return {};
        levels[e].reflection = reflection_with(elements[e], levels[e + 1].reflection, levels[e]);
    }

    Solution out;
    const double total_r = (levels[0].reflection * incident).sum();
    out.specular = elements.front().r_top_diagonal.cwiseProduct(incident).sum();
    out.diffuse = total_r - out.specular;
    // Top-down: the downward flux under each element and the net flux (down - up) there; A of a layer is the net
    // flux entering it minus the net flux leaving its bottom.
    AdVector down = incident;
    double net_above = incident.sum() - total_r;
    out.absorbed.assign(shape.layer_indices.size(), 0.0);
    for (std::size_t e = 0; e < count; ++e) {
        // What enters the reflector and does not come back is T (the hypodermis keeps it; 0 for the ideal one).
        if (elements[e].kind == AdElement::Kind::reflector && shape.bottom_reflectance < 1.0) out.transmittance = std::max(0.0, net_above);
        const AdVector through = transmit(elements[e], down);
        down = e + 1 < count && !levels[e].identity ? AdVector(levels[e].factor.solve(through)) : through;
        const double net_below = down.sum() - (levels[e + 1].reflection * down).sum();
        if (layer_of[e] >= 0) {
            // A difference of fluxes: a layer without absorption absorbs exactly nothing, and roundoff (~1e-11 in
            // thick conservative layers) does not make an absorbing layer's A negative.
            const auto k = static_cast<std::size_t>(layer_of[e]);
            out.absorbed[k] = shape.absorbing[k] ? std::max(0.0, net_above - net_below) : 0.0;
        }
        net_above = net_below;
    }
    if (!shape.bottom_reflector) out.transmittance = net_above;
    return out;
}

}  // namespace

AdResult solve_stack(const AdStackShape& shape, const AdIncidence& incidence, const AdOptions& options, const AdLayerMaker& make_layer) {
    const auto full = solve_with(shape, incidence, options.channels, 1, make_layer, options.cancel);
    AdResult result;
    if (options.cancel && options.cancel->load()) {
        result.cancelled = true;
        return result;
    }
    result.specular_reflectance = full.specular;
    result.diffuse_reflectance = full.diffuse;
    result.transmittance = full.transmittance;
    result.absorbed_layers = full.absorbed;
    result.channels = options.channels;
    if (options.accuracy_check) {
        // The quadrature-doubling check: the same stack with twice the nodes in every segment. With an error ~ 1/N
        // (the measured forward peaks converge that slowly: docs/ADDING_DOUBLING.md), the change is half the error, so
        // twice it.
        const auto fine = solve_with(shape, incidence, options.channels, 2, make_layer, options.cancel);
        if (options.cancel && options.cancel->load()) {
            result.cancelled = true;
            return result;
        }
        double change = std::max(std::abs(full.diffuse - fine.diffuse), std::abs(full.transmittance - fine.transmittance));
        for (std::size_t k = 0; k < full.absorbed.size(); ++k) change = std::max(change, std::abs(full.absorbed[k] - fine.absorbed[k]));
        result.accuracy = 2.0 * change;
    }
    return result;
}

}  // namespace skinspec
