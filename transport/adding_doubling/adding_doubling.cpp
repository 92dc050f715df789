#include "transport/adding_doubling/adding_doubling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Dense>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"
#include "transport/adding_doubling/gauss_quadrature.hpp"
#include "transport/adding_doubling/phase_moments.hpp"
#include "transport/fresnel.hpp"

namespace skinspec {
namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// Diamond start, then doubled: optical depth <= 2^-8 times the collimated beam's cosine in the layer. The diamond
// difference's error in a beam's exponent is (path depth) (h / mu)^2 / 12 (Wiscombe 1976), so the beam keeps
// ~1e-6 relative per unit path depth at any incidence; a grazing beam costs a few more doublings.
constexpr double thin_layer_depth = 1.0 / 256.0;

// The channels: s = n sin(theta) per channel (increasing) and its measure d(s^2).
struct Channels {
    std::vector<double> s;
    std::vector<double> measure;
    std::size_t incident = 0;  // the collimated beam's channel
    std::size_t size() const { return s.size(); }
    // cos(theta) in a medium of index n (0 where the channel does not propagate) and the flux weight d(s^2) / n^2.
    double cosine(std::size_t k, double n) const { return s[k] < n ? std::sqrt(std::max(0.0, 1.0 - (s[k] / n) * (s[k] / n))) : 0.0; }
    double weight(std::size_t k, double n) const { return s[k] < n ? measure[k] / (n * n) : 0.0; }
};

// `indices`: every medium's index; `layer_indices`: the layers' (where light scatters, so where the quadrature
// should be Gaussian in the cosine).
Channels make_channels(const std::vector<double>& indices, const std::vector<double>& layer_indices, std::size_t per_hemisphere,
                       double incident_s, bool collimated) {
    std::vector<double> breaks{0.0};
    for (const double n : indices) breaks.push_back(n);
    if (collimated && incident_s > 0.0) breaks.push_back(incident_s);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    const double n_max = breaks.back();
    Channels c;
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
        const auto m = std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(share * static_cast<double>(per_hemisphere))));
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

// One element of the stack in flux channels. Fresnel interfaces are diagonal in s (vectors); a homogeneous layer
// is the same from above and below (r, t); the Lambertian reflector only reflects (r from above).
struct Element {
    enum class Kind { interface, layer, reflector } kind = Kind::interface;
    Vector r_top_diagonal, r_bottom_diagonal, t_diagonal;  // interface
    Matrix r, t;                                           // layer (r and t both ways); reflector (r from above)
};

// Fresnel interface from index n1 (above) to n2 (below).
Element interface(const Channels& c, double n1, double n2) {
    const auto size = static_cast<Eigen::Index>(c.size());
    Element e{Element::Kind::interface, Vector::Zero(size), Vector::Zero(size), Vector::Zero(size), {}, {}};
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

// The ideal Lambertian reflector under a layer of index n: any incident flux leaves upward as c_i.
Element lambertian_reflector(const Channels& c, double n) {
    const auto size = static_cast<Eigen::Index>(c.size());
    Element e{Element::Kind::reflector, {}, {}, {}, Matrix::Zero(size, size), {}};
    for (std::size_t i = 0; i < c.size(); ++i) {
        for (std::size_t j = 0; j < c.size(); ++j) {
            if (c.s[j] < n) e.r(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = c.weight(i, n);
        }
    }
    return e;
}

}  // namespace

// The layer's scattering in the channels it propagates in: delta-M scaled phase function (its fraction f) and the
// redistribution matrices, which depend on the phase function, the index and the channels only (not on mu_a, mu_s).
struct AdCache::Entry {
    PhaseFunction phase;
    std::vector<double> table_cosines;  // tabulated phases compare by content (each wavelength has its own table)
    double n = 0.0;
    std::vector<double> channel_s;
    std::vector<std::size_t> live;
    double f = 0.0;
    Vector mu, w, cw;
    Matrix same, opposite;
};

// A layer's r and t (flux operators on every channel) for its scattering entry (phase, index, channels: held, so
// compared by identity), optics and the collimated beam's cosine in it.
struct AdCache::Slab {
    std::shared_ptr<const Entry> scattering;
    double mu_a_per_cm = 0.0, mu_s_per_cm = 0.0, thickness_cm = 0.0, beam_cosine = 0.0;
    Matrix r, t;
};

namespace {

std::vector<double> cosines_of(const PhaseFunction& phase) {
    std::vector<double> out;
    if (phase.kind == PhaseFunction::Kind::tabulated) {
        for (std::size_t i = 0; i < phase.table->size(); ++i) out.push_back(phase.table->cos_theta(i));
    }
    return out;
}

bool same_scattering(const AdCache::Entry& e, const PhaseFunction& phase, const std::vector<double>& cosines, double n, const Channels& c) {
    return e.phase.kind == phase.kind && e.phase.g == phase.g && e.phase.g2 == phase.g2 && e.phase.weight == phase.weight && e.n == n &&
           e.table_cosines == cosines && e.channel_s == c.s;
}

AdCache::Entry redistribution(const Channels& c, double n, const PhaseFunction& phase, std::vector<double> cosines) {
    AdCache::Entry e{phase, std::move(cosines), n, c.s, {}, 0.0, {}, {}, {}, {}, {}};
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (c.s[k] < n) e.live.push_back(k);
    }
    const auto m = static_cast<Eigen::Index>(e.live.size());
    // Delta-M with 2m moments kept: f = chi_2m (Wiscombe 1977), for a forward peak only (a backward-peaked phase
    // function has chi_2m > 0 too, but its truncated part is not light going on unscattered).
    const std::size_t moments = 2 * e.live.size();
    auto chi = legendre_moments(phase, moments + 2);
    const double f = chi[moments];
    if (f > 0.0 && f < 1.0 && chi[moments + 1] > 0.0) {
        e.f = f;
        for (std::size_t l = 0; l < moments; ++l) chi[l] = (chi[l] - f) / (1.0 - f);
    }
    chi.resize(moments);
    Vector mu(m), w(m), cw(m);
    for (Eigen::Index i = 0; i < m; ++i) {
        const auto k = e.live[static_cast<std::size_t>(i)];
        mu(i) = c.cosine(k, n);
        cw(i) = c.weight(k, n);
        w(i) = cw(i) / (2.0 * mu(i));  // the dmu weight
    }
    // H(mu_i | +-mu_j) = sum_l (2l + 1) / 2 chi_l P_l(mu_i) P_l(+-mu_j); P_l(-x) = (-1)^l P_l(x).
    Matrix pl(m, static_cast<Eigen::Index>(moments));
    for (Eigen::Index i = 0; i < m; ++i) {
        const auto p = legendre_polynomials(mu(i), moments);
        for (std::size_t l = 0; l < moments; ++l) pl(i, static_cast<Eigen::Index>(l)) = p[l];
    }
    Vector even(static_cast<Eigen::Index>(moments)), odd(static_cast<Eigen::Index>(moments));
    for (std::size_t l = 0; l < moments; ++l) {
        const double coefficient = (2.0 * static_cast<double>(l) + 1.0) / 2.0 * chi[l];
        even(static_cast<Eigen::Index>(l)) = coefficient;
        odd(static_cast<Eigen::Index>(l)) = l % 2 == 0 ? coefficient : -coefficient;
    }
    // The truncated series of a strongly forward phase function dips below zero in places (g -> 1): those entries
    // are set to 0 (a redistribution is a probability) before the energy renormalisation below.
    Matrix same = (pl * even.asDiagonal() * pl.transpose()).cwiseMax(0.0);
    const Matrix opposite = (pl * odd.asDiagonal() * pl.transpose()).cwiseMax(0.0);
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

const std::shared_ptr<const AdCache::Entry>& cached_redistribution(const Channels& c, double n, const PhaseFunction& phase, AdCache& cache) {
    // Least recently used last out: a spectrum's tabulated phases inside 400-546 nm differ at every wavelength, so an
    // unbounded cache would grow with the wavelength count.
    constexpr std::size_t capacity = 16;
    auto cosines = cosines_of(phase);
    auto& entries = cache.entries;
    for (auto it = entries.begin(); it != entries.end(); ++it) {
        if (same_scattering(**it, phase, cosines, n, c)) {
            std::rotate(it, it + 1, entries.end());
            return entries.back();
        }
    }
    if (entries.size() == capacity) entries.erase(entries.begin());
    entries.push_back(std::make_shared<const AdCache::Entry>(redistribution(c, n, phase, std::move(cosines))));
    return entries.back();
}

// A homogeneous layer: delta-M scaled albedo and depth, diamond thin layer, doubling. Flux channels.
// A layer thicker than this many optical depths is solved at this depth: its T (< e^-1e6) is 0 in doubles and its R
// has converged (the doublings stay ~28; an unbounded depth, e.g. 1e307 cm, never ended).
constexpr double max_optical_depth = 1e6;

Element slab(const Channels& c, const RteLayer& layer, const AdCache::Entry& scattering, double beam_cosine, const std::atomic<bool>* cancel) {
    const auto& live = scattering.live;
    const auto m = static_cast<Eigen::Index>(live.size());
    const double mu_t = layer.mu_a_per_cm + layer.mu_s_per_cm;
    double albedo = mu_t > 0.0 ? layer.mu_s_per_cm / mu_t : 0.0;
    double depth = std::min(mu_t * layer.thickness_cm, max_optical_depth);
    const double f = scattering.f;
    if (f > 0.0) {
        depth *= 1.0 - albedo * f;
        albedo = albedo * (1.0 - f) / (1.0 - albedo * f);
    }
    const Vector& mu = scattering.mu;
    const Vector& w = scattering.w;
    const Vector& cw = scattering.cw;
    const Matrix& same = scattering.same;
    const Matrix& opposite = scattering.opposite;
    // Thin layer by the diamond difference: with C = M^-1 (1 - a H++ W), S = M^-1 a H+- W, h = depth/2,
    // A = 1 + h C, B = h S: T = (A - B)^-1 + (A + B)^-1 - 1, R = (A - B)^-1 - (A + B)^-1 (radiance operators).
    int doublings = 0;
    double thin = depth;
    const double thin_limit = thin_layer_depth * beam_cosine;
    while (thin > thin_limit) {
        thin *= 0.5;
        ++doublings;
    }
    const Matrix identity = Matrix::Identity(m, m);
    const Matrix inv_mu = mu.cwiseInverse().asDiagonal();
    const Matrix cmat = inv_mu * (identity - albedo * same * w.asDiagonal());
    const Matrix smat = inv_mu * (albedo * opposite * w.asDiagonal());
    const double h = 0.5 * thin;
    const Matrix minus = (identity + h * cmat - h * smat).partialPivLu().inverse();
    const Matrix plus = (identity + h * cmat + h * smat).partialPivLu().inverse();
    // Flux operators: D R D^-1 with D = diag(c) (flux of a channel = pi c L).
    Matrix r = cw.asDiagonal() * (minus - plus) * cw.cwiseInverse().asDiagonal();
    Matrix t = cw.asDiagonal() * (minus + plus - identity) * cw.cwiseInverse().asDiagonal();
    for (int d = 0; d < doublings; ++d) {
        if (cancel && cancel->load(std::memory_order_relaxed)) break;
        const Eigen::PartialPivLU<Matrix> lu(identity - r * r);
        const Matrix x = lu.solve(t);
        r = r + t * r * x;
        t = t * x;
        // Transmission of thick layers decays towards the subnormal range, where arithmetic is ~100x slower.
        t = (t.array().abs() < 1e-250).select(0.0, t);
    }
    const auto size = static_cast<Eigen::Index>(c.size());
    Element e{Element::Kind::layer, {}, {}, {}, Matrix::Zero(size, size), Matrix::Zero(size, size)};
    for (Eigen::Index i = 0; i < m; ++i) {
        for (Eigen::Index j = 0; j < m; ++j) {
            const auto a = static_cast<Eigen::Index>(live[static_cast<std::size_t>(i)]);
            const auto b = static_cast<Eigen::Index>(live[static_cast<std::size_t>(j)]);
            e.r(a, b) = r(i, j);
            e.t(a, b) = t(i, j);
        }
    }
    return e;
}

// slab() through the cache: the same layer under the same scattering entry is doubled once.
Element cached_slab(const Channels& c, const RteLayer& layer, const std::shared_ptr<const AdCache::Entry>& scattering, double beam_cosine,
                    AdCache& cache, const std::atomic<bool>* cancel) {
    constexpr std::size_t capacity = 64;
    auto& slabs = cache.slabs;
    for (auto it = slabs.begin(); it != slabs.end(); ++it) {
        const auto& s = **it;
        if (s.scattering == scattering && s.mu_a_per_cm == layer.mu_a_per_cm && s.mu_s_per_cm == layer.mu_s_per_cm &&
            s.thickness_cm == layer.thickness_cm && s.beam_cosine == beam_cosine) {
            std::rotate(it, it + 1, slabs.end());
            return Element{Element::Kind::layer, {}, {}, {}, slabs.back()->r, slabs.back()->t};
        }
    }
    auto e = slab(c, layer, *scattering, beam_cosine, cancel);
    if (cancel && cancel->load()) return e;  // possibly unfinished: never cached
    if (slabs.size() == capacity) slabs.erase(slabs.begin());
    slabs.push_back(std::make_shared<const AdCache::Slab>(AdCache::Slab{scattering, layer.mu_a_per_cm, layer.mu_s_per_cm, layer.thickness_cm, beam_cosine, e.r, e.t}));
    return e;
}

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
    Matrix reflection;                    // S of this element and everything below it
    Eigen::PartialPivLU<Matrix> factor;   // of 1 - R'_E S_below (empty for the bottom element)
};

// X M^-1 for the factored M, as (M^T)^-1 X^T transposed.
Matrix right_solve(const Eigen::PartialPivLU<Matrix>& factor, const Matrix& x) {
    const Matrix rhs = x.transpose();
    const Matrix solved = factor.transpose().solve(rhs);
    return solved.transpose();
}

Matrix reflection_with(const Element& e, const Matrix& below, Eigen::PartialPivLU<Matrix>& factor) {
    const auto n = below.rows();
    if (e.kind == Element::Kind::reflector) return e.r;
    const Matrix identity = Matrix::Identity(n, n);
    if (e.kind == Element::Kind::interface) {
        factor.compute(identity - e.r_bottom_diagonal.asDiagonal() * below);
        // S (1 - R' S)^-1 by a transposed solve, then the diagonal transmissions on both sides.
        const Matrix y = right_solve(factor, below);
        Matrix s = e.t_diagonal.asDiagonal() * y * e.t_diagonal.asDiagonal();
        s.diagonal() += e.r_top_diagonal;
        return s;
    }
    factor.compute(identity - e.r * below);
    const Matrix y = right_solve(factor, below);
    return e.r + e.t * y * e.t;
}

Vector transmit(const Element& e, const Vector& flux) {
    if (e.kind == Element::Kind::interface) return e.t_diagonal.cwiseProduct(flux);
    if (e.kind == Element::Kind::layer) return e.t * flux;
    return Vector::Zero(flux.size());
}

Solution solve_with(const RteStack& stack, const AdIncidence& incidence, std::size_t per_hemisphere, AdCache& cache, const std::atomic<bool>* cancel) {
    std::vector<double> indices{stack.above_refractive_index};
    for (const auto& l : stack.layers) indices.push_back(l.refractive_index);
    if (!stack.bottom_reflector) indices.push_back(stack.below_refractive_index);
    constexpr double deg = std::numbers::pi / 180.0;
    const double n0 = stack.above_refractive_index;
    const double incident_s = incidence.diffuse ? 0.0 : n0 * std::sin(incidence.angle_deg * deg);
    std::vector<double> layer_indices;
    for (const auto& l : stack.layers) layer_indices.push_back(l.refractive_index);
    const auto channels = make_channels(indices, layer_indices, per_hemisphere, incident_s, !incidence.diffuse);
    const auto n = static_cast<Eigen::Index>(channels.size());

    std::vector<Element> elements;
    std::vector<int> layer_of;  // per element: layer index or -1
    double above = n0;
    for (std::size_t k = 0; k < stack.layers.size(); ++k) {
        elements.push_back(interface(channels, above, stack.layers[k].refractive_index));
        layer_of.push_back(-1);
        const auto& layer = stack.layers[k];
        // The collimated beam's cosine in this layer (Snell: the same s); 1 for diffuse incidence.
        const double beam = incidence.diffuse || channels.s[channels.incident] >= layer.refractive_index
                                ? 1.0 : std::max(channels.cosine(channels.incident, layer.refractive_index), 1e-6);
        elements.push_back(cached_slab(channels, layer, cached_redistribution(channels, layer.refractive_index, layer.phase, cache), beam, cache, cancel));
        layer_of.push_back(static_cast<int>(k));
        above = stack.layers[k].refractive_index;
    }
    elements.push_back(stack.bottom_reflector ? lambertian_reflector(channels, above) : interface(channels, above, stack.below_refractive_index));
    layer_of.push_back(-1);

    Vector incident = Vector::Zero(n);
    if (incidence.diffuse) {
        for (std::size_t k = 0; k < channels.size(); ++k) incident(static_cast<Eigen::Index>(k)) = channels.weight(k, n0);
    } else {
        incident(static_cast<Eigen::Index>(channels.incident)) = 1.0;
    }
    // Bottom-up: the reflection of every suffix (levels[e] = element e and all below it); nothing returns from
    // under the last element.
    const std::size_t count = elements.size();
    std::vector<Level> levels(count + 1);
    levels[count].reflection = Matrix::Zero(n, n);
    for (std::size_t e = count; e-- > 0;) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return {};
        levels[e].reflection = reflection_with(elements[e], levels[e + 1].reflection, levels[e].factor);
    }

    Solution out;
    const double total_r = (levels[0].reflection * incident).sum();
    out.specular = elements.front().r_top_diagonal.cwiseProduct(incident).sum();
    out.diffuse = total_r - out.specular;
    // Top-down: the downward flux under each element and the net flux (down - up) there; A of a layer is the net
    // flux entering it minus the net flux leaving its bottom.
    Vector down = incident;
    double net_above = incident.sum() - total_r;
    out.absorbed.assign(stack.layers.size(), 0.0);
    for (std::size_t e = 0; e < count; ++e) {
        const Vector through = transmit(elements[e], down);
        down = e + 1 < count ? Vector(levels[e].factor.solve(through)) : through;
        const double net_below = down.sum() - (levels[e + 1].reflection * down).sum();
        if (layer_of[e] >= 0) {
            // A difference of fluxes: a layer without absorption absorbs exactly nothing, and roundoff (~1e-11 in
            // thick conservative layers) does not make an absorbing layer's A negative.
            const auto k = static_cast<std::size_t>(layer_of[e]);
            out.absorbed[k] = stack.layers[k].mu_a_per_cm == 0.0 ? 0.0 : std::max(0.0, net_above - net_below);
        }
        net_above = net_below;
    }
    out.transmittance = stack.bottom_reflector ? 0.0 : net_above;
    return out;
}

}  // namespace

AdResult solve_adding_doubling(const RteStack& stack, const AdIncidence& incidence, const AdOptions& options, AdCache* cache) {
    validate(stack);
    if (!incidence.diffuse) check_incidence_deg(incidence.angle_deg);
    if (options.channels < 4 || options.channels > 256) {
        throw InputError("adding-doubling channels " + std::to_string(options.channels) + " is outside [4, 256]");
    }
    AdCache own;
    auto& phases = cache ? *cache : own;
    const auto full = solve_with(stack, incidence, options.channels, phases, options.cancel);
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
        // The quadrature-doubling check: the same stack with twice the channels. With an error ~ 1/N (the measured
        // forward peaks converge that slowly: docs/ADDING_DOUBLING.md), the change is half the error, so twice it.
        const auto fine = solve_with(stack, incidence, 2 * options.channels, phases, options.cancel);
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

RteResult rte_totals(const AdResult& result) {
    RteResult totals;
    totals.specular_reflectance = {result.specular_reflectance, 0.0};
    totals.diffuse_reflectance = {result.diffuse_reflectance, 0.0};
    totals.transmittance = {result.transmittance, 0.0};
    double absorbed = 0.0;
    for (const double a : result.absorbed_layers) {
        totals.absorption_layers.push_back({a, 0.0});
        absorbed += a;
    }
    totals.absorbed = {absorbed, 0.0};
    return totals;
}

}  // namespace skinspec
