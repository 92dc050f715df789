#include "transport/biospec/biospec_walk.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>

#include "materials/path_key.hpp"
#include "transport/adding_doubling/hypodermis_reflectance.hpp"
#include "transport/fresnel.hpp"
#include "transport/skin_fold.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr double roulette_weight = 1e-4;   // weighted estimator: Russian roulette below this weight
constexpr double roulette_survival = 0.1;
const double roulette_depth = -std::log(roulette_weight);     // tau - ln(boost) beyond which a set plays roulette
const double boost_log = -std::log(roulette_survival);
constexpr double dead_limit = std::numeric_limits<double>::infinity();  // the limit of a set that lost the roulette
constexpr std::uint32_t roulette_every = 8;  // crossings between two roulette looks at the sets' weights

}  // namespace

BiospecChannels::BiospecChannels(const Quantities& q, std::size_t layers, std::size_t bins) {
    int next = 0;
    if (q.reflectance) {
        reflectance = next++;
        specular = next++;
    }
    if (q.transmittance) transmittance = next++;
    if (q.absorptance) {
        absorptance_surface = next++;
        absorptance_first_layer = next;
        next += static_cast<int>(layers);
    }
    if (q.angular) {
        brdf_first_bin = next;
        next += static_cast<int>(bins);
        btdf_first_bin = next;
        next += static_cast<int>(bins);
    }
    truncated = next++;
    count = static_cast<std::size_t>(next);
}

// The walk-side bookkeeping of a packet's lanes, in double precision: each ray's key, and per ray and absorption set
// (the sets of one ray contiguous, set_stride apart) the log of the set's roulette boosts, the optical depth beyond
// which it plays roulette next (+inf: it lost), the weight its per-layer absorptance was last charged to; how many of
// its sets are still alive, and its per-ray score (channels a ray reaches more than once). `depth` and `weight` hold
// one ray's sets as find() last found them. Without layer paths (BiospecPacketModel::layer_paths) the packet's
// depth_bound is the one set's optical depth.
struct BiospecWavelength::Lanes {
    static constexpr std::size_t count = BiospecPacket::lanes;
    Lanes(std::size_t layers, std::size_t sets, std::size_t set_stride, std::size_t channels, bool layer_paths)
        : layers(layers), sets(sets), set_stride(set_stride), channels(channels), layer_paths(layer_paths), packet(layers), boost_log(set_stride * count),
          limit(set_stride * count, dead_limit), charged(set_stride * count), path_cm(layers), depth(set_stride), weight(set_stride), due((set_stride + 63) / 64),
          scores(count, RayScore(channels)) {}
    std::size_t layers, sets, set_stride, channels;
    bool layer_paths;
    BiospecPacket packet;
    std::uint64_t key[count] = {};
    std::vector<double> boost_log, limit, charged;  // [lane * set_stride + set]
    std::size_t alive[count] = {};
    std::vector<double> path_cm, depth, weight;
    std::vector<std::uint64_t> due;  // the sets of a roulette look past their depth, one bit each
    std::vector<RayScore> scores;

    bool alive_set(std::size_t set, std::size_t lane) const { return limit[lane * set_stride + set] != dead_limit; }
    // The ray's path length per layer, into path_cm.
    void gather_path(std::size_t lane) {
        for (std::size_t k = 0; k < layers; ++k) path_cm[k] = packet.path_cm[k * count + lane];
    }
    // The ray's path per layer and every set's optical depth, into path_cm and depth; the sets past their roulette
    // depth into due (with_due), every set's weight into weight (with_weights).
    void find(std::size_t lane, const std::vector<double>& mu_a_per_cm, bool with_due, bool with_weights) {
        if (!layer_paths) {
            const std::size_t i = lane * set_stride;
            depth[0] = packet.depth_bound[lane];
            due[0] = with_due && depth[0] > limit[i] ? 1 : 0;
            if (with_weights) weight[0] = std::exp(boost_log[i] - depth[0]);
            return;
        }
        gather_path(lane);
        biospec_sets({mu_a_per_cm.data(), set_stride, sets, layers, path_cm.data(), limit.data() + lane * set_stride,
                      boost_log.data() + lane * set_stride, depth.data(), with_due ? due.data() : nullptr, with_weights ? weight.data() : nullptr});
    }
    // After a roulette look (depth as found): where the packet's depth bound must look next. Every set's depth grows no
    // faster than the bound, so none can pass its roulette depth before the bound has grown by the smallest margin;
    // 1e-5 of it is kept back for the rounding of both sums.
    void set_look(std::size_t lane) {
        const double margin = biospec_set_margin(set_stride, limit.data() + lane * set_stride, depth.data());
        packet.look_at[lane] = static_cast<float>((packet.depth_bound[lane] + margin) * (1.0 - 1e-5));
    }
};

// Single-precision copies of the SC and epidermis profile tables at every tabulated wavelength, concatenated.
struct BiospecWavelength::ProfileArena {
    std::vector<float> cos, sin;
    std::vector<std::int32_t> offset[2];  // [0: SC, 1: epidermis][tabulated wavelength]
};

std::shared_ptr<const BiospecWavelength::ProfileArena> BiospecWavelength::profile_arena(std::size_t entries) {
    static std::mutex mutex;
    static std::map<std::size_t, std::shared_ptr<const ProfileArena>> arenas;
    const std::lock_guard lock(mutex);
    auto& arena = arenas[entries];
    if (!arena) {
        auto built = std::make_shared<ProfileArena>();
        const MeasuredProfile* profiles[2] = {&MeasuredProfile::stratum_corneum(), &MeasuredProfile::epidermis()};
        for (std::size_t p = 0; p < 2; ++p) {
            for (std::size_t i = 0; i < profiles[p]->wavelengths_nm().size(); ++i) {
                const auto table = profiles[p]->tabulated_inverse_table(i, entries);
                built->offset[p].push_back(static_cast<std::int32_t>(built->cos.size()));
                for (std::size_t e = 0; e < table->size(); ++e) {
                    built->cos.push_back(static_cast<float>(table->cos_theta(e)));
                    built->sin.push_back(static_cast<float>(table->sin_theta(e)));
                }
            }
        }
        arena = std::move(built);
    }
    return arena;
}

BiospecWavelength::BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                                     const BiospecOptions& options, std::vector<double> floor_per_cm)
    : BiospecWavelength(stack, wavelength_nm, incidence_deg, geometry, options, BiospecChannels(Quantities{}, stack.layers.size(), 0), {}) {
    if (options.estimator != AbsorptionEstimator::weighted) throw InputError("path recording needs the weighted estimator");
    recording_ = true;
    if (floor_per_cm.empty()) {
        // No absorption: the exits keep the ray's path length in each layer.
        set_absorption(std::vector<double>(layers_, 0.0));
    } else {
        // Analog absorption at the floor (the per-crossing test); the exits still keep their path lengths.
        if (floor_per_cm.size() != layers_) throw InputError("path recording: a floor absorption per layer is needed");
        set_absorption(floor_per_cm);
        options_.estimator = AbsorptionEstimator::random_test;
        floor_per_cm_ = std::move(floor_per_cm);
    }
    finish_model();
}

std::vector<double> BiospecWavelength::sets_absorption_per_cm(const std::vector<const LayerStack*>& sets, double wavelength_nm) {
    const std::size_t layers = sets.front()->layers.size();
    std::vector<double> mu_a(sets.size() * layers);
    for (std::size_t s = 0; s < sets.size(); ++s) {
        for (std::size_t k = 0; k < layers; ++k) {
            mu_a[s * layers + k] = absorption_per_cm(sets[s]->layers[k], wavelength_nm, sets[s]->model);
        }
    }
    return mu_a;
}

BiospecWavelength::BiospecWavelength(const std::vector<const LayerStack*>& sets, double wavelength_nm, double incidence_deg,
                                     MeasurementGeometry geometry, const BiospecOptions& options, const BiospecChannels& channels,
                                     std::vector<double> edges_deg)
    : BiospecWavelength(*sets.front(), wavelength_nm, incidence_deg, geometry, options, channels, std::move(edges_deg)) {
    sets_ = sets.size();
    if (sets_ > 1 && options.estimator != AbsorptionEstimator::weighted) {
        throw InputError("absorption replay needs the weighted estimator (the random test makes paths depend on absorption)");
    }
    require_shared_paths(sets, TracedPaths::biospec);
    set_absorption(sets_absorption_per_cm(sets, wavelength_nm));
    finish_model();
}

void BiospecWavelength::set_absorption(const std::vector<double>& mu_a_per_cm) {
    sets_ = mu_a_per_cm.size() / layers_;
    set_stride_ = (sets_ + widest_double_vector - 1) / widest_double_vector * widest_double_vector;
    set_mu_a_per_cm_.assign(layers_ * set_stride_, 0.0);
    packet_.mu_a_per_cm.assign(layers_, 0.0f);
    packet_.mu_a_bound_per_cm.assign(layers_, 0.0f);
    for (std::size_t k = 0; k < layers_; ++k) {
        double largest = 0.0;
        for (std::size_t s = 0; s < sets_; ++s) {
            set_mu_a_per_cm_[k * set_stride_ + s] = mu_a_per_cm[s * layers_ + k];
            largest = std::max(largest, mu_a_per_cm[s * layers_ + k]);
        }
        packet_.mu_a_per_cm[k] = static_cast<float>(mu_a_per_cm[k]);
        // Rounded up, so that the bound holds in single precision too.
        float bound = static_cast<float>(largest);
        if (static_cast<double>(bound) < largest) bound = std::nextafter(bound, std::numeric_limits<float>::infinity());
        packet_.mu_a_bound_per_cm[k] = bound;
    }
}

BiospecWavelength::BiospecWavelength(const LayerStack& stack, double wavelength_nm, double incidence_deg, MeasurementGeometry geometry,
                                     const BiospecOptions& options, const BiospecChannels& channels,
                                     std::vector<double> edges_deg)
    : layers_(stack.layers.size()),
      n_above_(stack.above_refractive_index),
      n_below_(stack.below_refractive_index),
      reflector_(has_reflector(stack.bottom)),
      reflector_reflectance_(bottom_reflectance(stack, wavelength_nm)),
      fold_sigma_(stack.fold_aspect_ratio),
      model_(stack.model),
      geometry_(geometry),
      incident_(std::sin(incidence_deg * deg), 0.0, std::cos(incidence_deg * deg)),
      options_(options),
      channels_(channels) {
    for (const double e : edges_deg) bin_edges_cos_.push_back(std::cos(e * deg));
    if (geometry == MeasurementGeometry::zero_45) {
        if (incidence_deg != 0.0) throw InputError("geometry 0-45 needs normal incidence (incidence " + std::to_string(incidence_deg) + " deg given)");
        band_cos_lo_ = std::cos(zero_45_band_hi_deg * deg);
        band_cos_hi_ = std::cos(zero_45_band_lo_deg * deg);
        // A perfect diffuser sends sin^2 hi - sin^2 lo = cos^2 lo - cos^2 hi of its light into the band.
        band_factor_ = 1.0 / (band_cos_hi_ * band_cos_hi_ - band_cos_lo_ * band_cos_lo_);
    }
    auto& m = packet_;
    m.layers = static_cast<std::int32_t>(layers_);
    std::vector<double> n;
    for (std::size_t k = 0; k < layers_; ++k) {
        auto o = stack.optics(k, wavelength_nm, OpticsScope{false, false});
        if (options.thin_layer_hg && o.crossing == CrossingScattering::measured_stratum_corneum) {
            o.crossing = CrossingScattering::henyey_greenstein;
            o.hg_g = options.thin_layer_hg->stratum_corneum_g(wavelength_nm);
        } else if (options.thin_layer_hg && o.crossing == CrossingScattering::measured_epidermis) {
            o.crossing = CrossingScattering::henyey_greenstein;
            o.hg_g = options.thin_layer_hg->epidermis_g(wavelength_nm);
        }
        const bool measured = o.crossing == CrossingScattering::measured_stratum_corneum || o.crossing == CrossingScattering::measured_epidermis;
        PacketScattering kind = PacketScattering::cosine;
        switch (o.crossing) {
            case CrossingScattering::measured_stratum_corneum:
            case CrossingScattering::measured_epidermis: kind = PacketScattering::table; break;
            case CrossingScattering::henyey_greenstein: kind = PacketScattering::henyey_greenstein; break;
            case CrossingScattering::rayleigh_cosine: kind = PacketScattering::rayleigh_cosine; break;
            case CrossingScattering::cosine: kind = PacketScattering::cosine; break;
        }
        m.scattering.push_back(static_cast<std::int32_t>(kind));
        // Authors' behaviour 4: their SC keeps a perturbation that reverses the travel sense.
        m.redraw.push_back(o.crossing != CrossingScattering::measured_stratum_corneum || model_.redraw_reversals_in_stratum_corneum ? 1 : 0);
        if (measured) {
            if (!arena_) arena_ = profile_arena(options.profile_table_entries);
            const std::size_t which = o.crossing == CrossingScattering::measured_stratum_corneum ? 0 : 1;
            const auto mixture = (which == 0 ? MeasuredProfile::stratum_corneum() : MeasuredProfile::epidermis()).mixture(wavelength_nm);
            m.table_offset.push_back(arena_->offset[which][mixture.lower]);
            m.table_offset_upper.push_back(arena_->offset[which][mixture.upper]);
            m.table_upper_weight.push_back(static_cast<float>(mixture.upper_weight));
            m.table_size.push_back(static_cast<std::int32_t>(options.profile_table_entries));
        } else {
            m.table_offset.push_back(0);
            m.table_offset_upper.push_back(0);
            m.table_upper_weight.push_back(0.0f);
            m.table_size.push_back(1);
        }
        m.thickness_cm.push_back(static_cast<float>(o.thickness_cm));
        m.turn_mean_free_path_cm.push_back(o.turn_per_cm() > 0.0 ? static_cast<float>(1.0 / o.turn_per_cm())
                                                                      : std::numeric_limits<float>::infinity());
        m.hg_g.push_back(static_cast<float>(o.hg_g));
        n.push_back(o.refractive_index);
    }
    if (!arena_) arena_ = profile_arena(1);  // the step's table pointers are valid even without a measured layer
    m.table_cos = arena_->cos.data();
    m.table_sin = arena_->sin.data();
    n_top_ = n.front();
    entry_reflectance_ = fresnel_reflectance(incident_.z, n_above_, n_top_);
    entry_direction_ = refract(incident_, n_above_, n_top_).value_or(incident_);  // unused under total reflection (Fresnel 1)
    for (std::size_t k = 0; k < layers_; ++k) {
        const double below = k + 1 == layers_ ? n_below_ : n[k + 1];
        const double above = k == 0 ? n_above_ : n[k - 1];
        const bool swap = model_.swapped_upward_indices;
        m.eta_down.push_back(static_cast<float>(n[k] / below));
        m.inverse_eta_down.push_back(static_cast<float>(below / n[k]));
        m.eta_up.push_back(static_cast<float>(swap ? above / n[k] : n[k] / above));
        m.inverse_eta_up.push_back(static_cast<float>(swap ? n[k] / above : above / n[k]));
    }
}

void BiospecWavelength::finish_model() {
    auto& m = packet_;
    m.reflector = reflector_;
    m.reflector_reflectance = static_cast<float>(reflector_reflectance_);
    m.bottom_exit_fresnel = model_.bottom_exit_fresnel;
    m.weighted = options_.estimator == AbsorptionEstimator::weighted;
    m.roulette = !recording_;
    m.flag_every_event = channels_.absorptance_first_layer >= 0 && m.weighted;
    // One set needs no per-layer paths unless the absorptance or a recording asks for them, or a mu_a beyond single
    // precision would make its depth inf * 0 at a crossing of no length (the per-layer paths keep depths in double).
    const bool single_precision = std::all_of(m.mu_a_per_cm.begin(), m.mu_a_per_cm.end(), [](float mu) { return std::isfinite(mu); });
    m.layer_paths = sets_ > 1 || m.flag_every_event || recording_ || !single_precision;
    if (!m.layer_paths) m.mu_a_bound_per_cm = m.mu_a_per_cm;
    m.rayleigh_turn = model_.rayleigh_turn;
    m.max_events = options_.max_events_per_ray;
    m.roulette_every = roulette_every;
    m.pad();
}

void BiospecWavelength::trace(RandomStream& random, std::uint64_t rays, RayTally& tally) const {
    if (recording_) throw InputError("a path-recording walk records paths (BiospecWavelength::record)");
    walk(random, rays, tally, nullptr);
}

void BiospecWavelength::record(RandomStream& random, std::uint64_t rays, ExitPaths& paths) const {
    if (!recording_) throw InputError("only a path-recording walk records paths");
    RayTally unused(channels_.count * sets_);
    paths.resize_layers(layers_);
    paths.factor = geometry_ == MeasurementGeometry::zero_45 ? band_factor_ : 1.0;
    if (!floor_per_cm_.empty()) paths.thinned_at_per_cm = floor_per_cm_;
    walk(random, rays, unused, &paths);
    paths.rays += rays;
}

double BiospecWavelength::geometry_factor(double cos_exit, bool first_surface) const {
    switch (geometry_) {
        case MeasurementGeometry::sci: return 1.0;
        case MeasurementGeometry::sce: return first_surface ? 0.0 : 1.0;
        case MeasurementGeometry::zero_45: return cos_exit >= band_cos_lo_ && cos_exit <= band_cos_hi_ ? band_factor_ : 0.0;
    }
    return 0.0;
}

std::size_t BiospecWavelength::exit_bin(double cos_exit) const {
    // Edges are stored as decreasing cosines; find the bin whose [cos_hi, cos_lo] holds cos_exit.
    const auto it = std::upper_bound(bin_edges_cos_.begin(), bin_edges_cos_.end(), cos_exit, std::greater<>());
    const auto upper = static_cast<std::size_t>(it - bin_edges_cos_.begin());
    return upper == 0 ? 0 : std::min(upper - 1, bin_edges_cos_.size() - 2);
}

void BiospecWavelength::walk(RandomStream& random, std::uint64_t rays, RayTally& tally, ExitPaths* paths) const {
    // The lanes' buffers are this thread's, kept from batch to batch (a spectrum of many wavelengths with few rays
    // each would otherwise spend its time allocating them); every lane is empty between two walks.
    thread_local std::unique_ptr<Lanes> scratch;
    if (!scratch || scratch->layers != layers_ || scratch->sets != sets_ || scratch->channels != channels_.count * sets_ ||
        scratch->layer_paths != packet_.layer_paths) {
        scratch = std::make_unique<Lanes>(layers_, sets_, set_stride_, channels_.count * sets_, packet_.layer_paths);
    }
    Lanes& lanes = *scratch;
    auto& packet = lanes.packet;
    std::uint64_t started = 0;
    std::size_t active = 0;
    // A lane whose ray ended takes the next ray (rays that end at the surface are tallied on the way).
    const auto refill = [&](std::size_t lane) {
        while (started < rays) {
            ++started;
            if (enter(lane, random.bits64(), lanes, tally, paths)) return true;
        }
        packet.active[lane] = 0;
        return false;
    };
    try {
        for (std::size_t lane = 0; lane < Lanes::count; ++lane) active += refill(lane) ? 1 : 0;
        while (active > 0) {
            for (std::uint64_t flags = step_biospec_packet(packet_, packet); flags != 0; flags &= flags - 1) {
                const auto lane = static_cast<std::size_t>(std::countr_zero(flags));
                if (!settle(lane, lanes, tally, paths)) continue;
                if (!paths) tally.add_ray(lanes.scores[lane]);
                if (!refill(lane)) --active;
            }
        }
    } catch (...) {
        scratch.reset();  // lanes left mid-ray are not reused
        throw;
    }
}

bool BiospecWavelength::enter(std::size_t lane, std::uint64_t key, Lanes& lanes, RayTally& tally, ExitPaths* paths) const {
    auto random = RandomStream::for_ray(key);
    auto& score = lanes.scores[lane];
    const auto ended = [&] {
        if (!paths) tally.add_ray(score);
        return false;
    };
    // Step 1: air -> stratum corneum. Reflection is perturbed by the skin-fold distribution.
    if (random.uniform() < entry_reflectance_) {
        for (int attempt = 0; attempt < max_redraws; ++attempt) {
            const double u = random.uniform();
            const double c = model_.fold_formula == FoldFormula::biospec_2004 ? skin_fold_sample_cos(fold_sigma_, u)
                                                                             : skin_fold_authors_sample_cos(fold_sigma_, u);
            const Direction out = deflect(mirror(incident_), c, std::sqrt(std::max(0.0, 1.0 - c * c)), sample_azimuth(random));
            if (out.z < 0.0) {
                const double f = geometry_factor(-out.z, true);
                if (paths) {
                    ++paths->surface_reflections;
                    if (f > 0.0) ++paths->surface_exits;
                    return false;
                }
                for (std::size_t s = 0; s < sets_; ++s) {
                    tally_exit(tally, s, channels_.reflectance, f, channels_.brdf_first_bin, -out.z, 1.0);
                    tally_exit(tally, s, channels_.specular, 1.0, -1, 0.0, 0.0);
                }
                return ended();
            }
            if (options_.fold_into_skin == FoldIntoSkin::drop) break;
        }
        if (channels_.absorptance_surface >= 0) {
            for (std::size_t s = 0; s < sets_; ++s) score.add(s * channels_.count + static_cast<std::size_t>(channels_.absorptance_surface), 1.0);
        }
        return ended();
    }
    const Direction& d = entry_direction_;
    auto& p = lanes.packet;
    p.dx[lane] = static_cast<float>(d.x);
    p.dy[lane] = static_cast<float>(d.y);
    p.dz[lane] = static_cast<float>(d.z);
    p.layer[lane] = 0;
    p.event[lane] = 0;
    p.attempts[lane] = 0;
    p.active[lane] = 1;
    p.seed_lane(lane, key);
    p.depth_bound[lane] = 0.0f;
    for (std::size_t i = lane * set_stride_; i < lane * set_stride_ + sets_; ++i) {
        lanes.boost_log[i] = 0.0;
        lanes.limit[i] = roulette_depth;
        lanes.charged[i] = 1.0;
    }
    for (std::size_t k = 0; k < layers_; ++k) p.path_cm[k * Lanes::count + lane] = 0.0f;
    p.look_at[lane] = static_cast<float>(roulette_depth * (1.0 - 1e-5));
    lanes.key[lane] = key;
    lanes.alive[lane] = sets_;
    return true;
}

void BiospecWavelength::tally_exit(RayTally& tally, std::size_t set, int channel, double value, int first_bin, double cos_exit,
                                   double bin_value) const {
    const std::size_t offset = set * channels_.count;
    if (channel >= 0) tally.add_single(offset + static_cast<std::size_t>(channel), value);
    if (first_bin >= 0) tally.add_single(offset + static_cast<std::size_t>(first_bin) + exit_bin(cos_exit), bin_value);
}

void BiospecWavelength::leave_top(std::size_t lane, double cos_exit, Lanes& lanes, RayTally& tally, ExitPaths* paths) const {
    const double f = geometry_factor(cos_exit, false);
    if (paths) {
        if (f > 0.0) {
            lanes.gather_path(lane);
            paths->add_exit(lanes.path_cm);
        }
        return;
    }
    lanes.find(lane, set_mu_a_per_cm_, false, true);
    for (std::size_t s = 0; s < sets_; ++s) {
        if (!lanes.alive_set(s, lane)) continue;
        const double w = lanes.weight[s];
        tally_exit(tally, s, channels_.reflectance, w * f, channels_.brdf_first_bin, cos_exit, w);
    }
}

bool BiospecWavelength::settle(std::size_t lane, Lanes& lanes, RayTally& tally, ExitPaths* paths) const {
    auto& p = lanes.packet;
    auto& score = lanes.scores[lane];
    const auto absorb = [&](std::size_t set, std::size_t layer, double value) {
        if (channels_.absorptance_first_layer >= 0) {
            score.add(set * channels_.count + static_cast<std::size_t>(channels_.absorptance_first_layer) + layer, value);
        }
    };
    const auto k = static_cast<std::size_t>(p.crossing_layer[lane]);
    // The sets' depths, once: their weights for the absorptance, the sets past their roulette depth for the roulette.
    const bool absorptance = packet_.flag_every_event;
    if (absorptance || p.roulette_due[lane]) lanes.find(lane, set_mu_a_per_cm_, p.roulette_due[lane] != 0, absorptance);
    // Step 4's absorptance: the weight lost on this crossing, from the depths the packet step accumulated.
    if (absorptance) {
        for (std::size_t s = 0; s < sets_; ++s) {
            if (!lanes.alive_set(s, lane)) continue;
            const double w = lanes.weight[s];
            absorb(s, k, lanes.charged[lane * set_stride_ + s] - w);
            lanes.charged[lane * set_stride_ + s] = w;
        }
    }
    // Russian roulette for the sets whose weight fell below roulette_weight, conserving each ray's energy exactly:
    // a survivor's added weight is taken back from this layer's absorption, a loser's weight is absorbed; both
    // unbiased. One number per (ray, event) for all sets. The step flags a lane when the depth bound says some set
    // may be due; the sets' own depths decide.
    if (p.roulette_due[lane]) {
        // The sets that lost (and the padding) have limit inf: never due. The weights before the roulette are needed
        // only for the absorptance, which has them.
        const double u = RandomStream::keyed_uniform(lanes.key[lane], p.event[lane] - 1);
        const auto play = [&](std::size_t s) {
            const std::size_t i = lane * set_stride_ + s;
            const double w = absorptance ? lanes.weight[s] : 0.0;
            if (u < roulette_survival) {
                lanes.boost_log[i] += boost_log;
                lanes.limit[i] += boost_log;
                lanes.charged[i] = w / roulette_survival;
                absorb(s, k, w - lanes.charged[i]);
            } else {
                absorb(s, k, w);
                lanes.limit[i] = dead_limit;
                --lanes.alive[lane];
            }
        };
        for (std::size_t word = 0; word < lanes.due.size(); ++word) {
            for (std::uint64_t bits = lanes.due[word]; bits != 0; bits &= bits - 1) play(word * 64 + static_cast<std::size_t>(std::countr_zero(bits)));
        }
        if (lanes.alive[lane] == 0) return true;
        lanes.set_look(lane);
    }
    switch (static_cast<LaneStatus>(p.status[lane])) {
        case LaneStatus::walking: return false;
        case LaneStatus::left_top: leave_top(lane, p.exit_cos[lane], lanes, tally, paths); return true;
        case LaneStatus::left_bottom:
            if (paths) return true;
            lanes.find(lane, set_mu_a_per_cm_, false, true);
            for (std::size_t s = 0; s < sets_; ++s) {
                if (!lanes.alive_set(s, lane)) continue;
                const double w = lanes.weight[s];
                tally_exit(tally, s, channels_.transmittance, w, channels_.btdf_first_bin, p.exit_cos[lane], w);
            }
            return true;
        case LaneStatus::absorbed: absorb(0, k, 1.0); return true;
        case LaneStatus::truncated:
            if (paths) {
                ++paths->truncated_rays;
                return true;
            }
            lanes.find(lane, set_mu_a_per_cm_, false, true);
            for (std::size_t s = 0; s < sets_; ++s) {
                if (!lanes.alive_set(s, lane)) continue;
                absorb(s, static_cast<std::size_t>(p.layer[lane]), lanes.weight[s]);
                score.add(s * channels_.count + static_cast<std::size_t>(channels_.truncated), 1.0);
            }
            return true;
    }
    return true;
}

}  // namespace skinspec
