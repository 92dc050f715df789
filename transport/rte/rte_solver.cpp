// The volumetric walk: MCML's photon loop (Wang, Jacques & Zheng 1995, Comput. Methods Programs Biomed.
// 47:131-146, Sec. 3-4): exponential free paths (Eq. 3.7), absorption by weight mu_a / mu_t at each
// interaction (Eq. 3.23), scattering by the layer's phase function, Fresnel at every boundary (Eq. 3.31),
// Russian roulette below weight 1e-4 with survival 0.1 (Sec. 3.9). Differences from MCML: photons traced in SIMD
// packets (rte_packet.hpp) with a stream per photon keyed from its batch's PCG32 stream (no ran3), oblique incidence,
// an optional Lambertian bottom reflector, roulette that conserves each photon's energy exactly (the survivor's gain
// is taken back from the absorption tally where it happened), and standard errors for every tally.
#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <span>

#include <tbb/parallel_for.h>

#include "materials/path_key.hpp"
#include "transport/biospec/exit_paths.hpp"
#include "transport/direction.hpp"
#include "transport/fresnel.hpp"
#include "transport/rte/rte_model.hpp"
#include "transport/rte/rte_packet.hpp"
#include "transport/ray_planner.hpp"
#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double roulette_weight = 1e-4;
constexpr double roulette_survival = 0.1;

// Channel layout of a photon's score.
struct Channels {
    std::size_t layers, nz, nr, na, nw;
    std::size_t specular = 0, reflectance = 1, transmittance = 2, absorbed = 3, first_layer = 4;
    std::size_t a_z, r_r, t_r, r_a, t_a, a_rz, r_ra, t_ra, r_within, t_within, count = 0;
    Channels(std::size_t l, const RteGrid& g, std::size_t within)
        : layers(l), nz(static_cast<std::size_t>(g.nz)), nr(static_cast<std::size_t>(g.nr)), na(static_cast<std::size_t>(g.na)), nw(within) {
        a_z = first_layer + layers;
        r_r = a_z + nz;
        t_r = r_r + nr;
        r_a = t_r + nr;
        t_a = r_a + na;
        a_rz = t_a + na;
        r_ra = a_rz + nr * nz;
        t_ra = r_ra + nr * na;
        truncated = t_ra + nr * na;
        r_within = truncated + 1;
        t_within = r_within + nw;
        count = t_within + nw;
    }
    std::size_t truncated;  // 1 for a photon stopped at the step limit (per absorption set in white mode)
};

// The exits of one batch of the exit replay (solve_rte_exit_sets), a photon's exits consecutive: per exit its path in
// each layer, its weight at the floor's absorption (roulette boosts and the fractions split boundaries kept included),
// its radius, side and photon.
struct BatchExits {
    ExitPaths paths;
    std::vector<double> weight;
    std::vector<float> r_cm;
    std::vector<std::uint32_t> photon;
    std::vector<unsigned char> top;
    std::vector<std::uint32_t> ring;  // side * rings + ring of R_r / T_r (rings_of)
    std::uint64_t photons = 0;        // launched
    double specular = 0.0;            // each photon's first-surface reflection
    void add(std::span<const double> path_cm, double w, double r, std::uint32_t p, bool leaves_top) {
        for (std::size_t k = 0; k < path_cm.size(); ++k) paths.layer_path_cm[k].push_back(static_cast<float>(path_cm[k]));
        weight.push_back(w);
        r_cm.push_back(static_cast<float>(r));
        photon.push_back(p);
        top.push_back(leaves_top ? 1 : 0);
    }
    std::size_t size() const { return weight.size(); }
    // Exits reordered so that each photon's are consecutive (split boundaries let a photon leave several times, packet
    // lanes interleave photons), in photon order, each photon's in the order they happened.
    void group_by_photon() {
        std::vector<std::size_t> order(size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return photon[a] < photon[b]; });
        const auto permute = [&](auto& v) {
            auto copy = v;
            for (std::size_t i = 0; i < order.size(); ++i) v[i] = copy[order[i]];
        };
        for (auto& l : paths.layer_path_cm) permute(l);
        permute(weight);
        permute(r_cm);
        permute(photon);
        permute(top);
    }
    // Each exit's ring of width dr_cm (the last, nr - 1, also collecting everything beyond, as MCML's), R's rings first.
    void rings_of(double dr_cm, std::size_t nr) {
        ring.resize(size());
        for (std::size_t e = 0; e < size(); ++e) {
            const auto i = std::min(static_cast<std::size_t>(static_cast<double>(r_cm[e]) / dr_cm), nr - 1);
            ring[e] = static_cast<std::uint32_t>((top[e] ? 0 : nr) + i);
        }
    }
};

// The walk-side state of a packet's lanes, in double precision: each photon's key, weight (MCML's way) or its
// absorption sets' optical depths, roulette boosts, limits and the log of the weight kept at split boundaries
// (white), the energy it has deposited in each layer (per set), and its per-photon score of the other channels.
struct Lanes {
    static constexpr std::size_t count = RtePacket::lanes;
    Lanes(std::size_t sets, std::size_t layers, std::size_t channels)
        : sets(sets), layers(layers), channels(channels), tau(sets * count), boost_log(sets * count), limit(sets * count),
          deposited(count * sets * layers), path_cm(count * layers), scores(count, RayScore(channels)) {}
    std::size_t sets, layers, channels;
    RtePacket packet;
    std::uint64_t key[count] = {};
    double weight[count] = {};
    double log_common[count] = {};
    std::size_t alive[count] = {};
    std::vector<double> tau, boost_log, limit;  // [set * count + lane]
    std::vector<double> deposited;              // [(lane * sets + set) * layers + layer]
    std::vector<double> path_cm;                // exit replay: the photon's path so far in each layer, [lane * layers + layer]
    std::uint32_t photon[count] = {};           // exit replay: the photon's index in its batch
    std::vector<RayScore> scores;
    RayTally* tally = nullptr;  // the batch's tally while a walk runs
    BatchExits* exits = nullptr;  // the exit replay's record while a walk runs
};

constexpr double dead_limit = std::numeric_limits<double>::infinity();  // the limit of a set that lost the roulette


class Walk {
public:
    // `mu_a_sets` (white mode): per set, mu_a per layer in 1/cm; empty: the stack's own absorption, MCML's way.
    // `exit_sets` > 0 (the exit replay, with one set: the floor): the exits are recorded instead of tallied, the tally
    // holds that many sets (the batch's exits are replayed into it by the caller).
    Walk(const RteRequest& r, const Channels& c, const std::vector<std::vector<double>>& mu_a_sets, std::size_t exit_sets = 0)
        : request_(r), stack_(r.stack), ch_(c), sets_(std::max<std::size_t>(1, mu_a_sets.size())), white_(!mu_a_sets.empty()),
          recording_(exit_sets > 0), tally_sets_(exit_sets > 0 ? exit_sets : sets_) {
        const std::size_t layers = stack_.layers.size();
        for (std::size_t k = 0; k < layers; ++k) {
            const auto& l = stack_.layers[k];
            for (std::size_t s = 0; s < mu_a_sets.size(); ++s) mu_a_per_cm_.push_back(mu_a_sets[s].at(k));
            const double mu_t = l.mu_a_per_cm + l.mu_s_per_cm;
            absorbed_fraction_.push_back(mu_t > 0.0 ? l.mu_a_per_cm / mu_t : 0.0);  // Eq. 3.23
        }
        const double theta = r.incidence_deg * pi / 180.0;
        const Direction incident{std::sin(theta), 0.0, std::cos(theta)};
        specular_ = fresnel_reflectance(incident.z, stack_.above_refractive_index, stack_.layers.front().refractive_index);
        entry_ = refract(incident, stack_.above_refractive_index, stack_.layers.front().refractive_index).value_or(incident);
        if (ch_.nz > 0) inverse_dz_ = 1.0 / r.grid.dz_cm;
        if (r.grid.nr > 0) inverse_dr_ = 1.0 / r.grid.dr_cm;
        last_z_ = static_cast<std::int64_t>(ch_.nz) - 1;
        last_r_ = static_cast<std::int64_t>(r.grid.nr) - 1;
        build_model();
    }

    // With the exit replay the batch's exits go to `exits` (grouped by photon), nothing of them to `tally`.
    void trace(RandomStream& random, std::uint64_t photons, RayTally& tally, BatchExits* exits = nullptr) const {
        // The lanes' buffers are this thread's, kept from batch to batch; every lane is empty between two walks.
        thread_local std::unique_ptr<Lanes> scratch;
        const std::size_t channels = ch_.count * tally_sets_;
        const std::size_t layers = stack_.layers.size();
        if (!scratch || scratch->sets != sets_ || scratch->layers != layers || scratch->channels != channels) {
            scratch = std::make_unique<Lanes>(sets_, layers, channels);
        }
        Lanes& lanes = *scratch;
        lanes.tally = &tally;
        lanes.exits = exits;
        if (exits) exits->paths.resize_layers(layers);
        for (std::size_t set = 0; set < tally_sets_; ++set) tally.use_batch_means(set * ch_.count + ch_.a_z, ch_.truncated - ch_.a_z);
        std::uint64_t started = 0, truncated = 0;
        std::size_t active = 0;
        // A lane whose photon ended takes the next one (photons that end at the surface are tallied on the way).
        const auto refill = [&](std::size_t lane) {
            while (started < photons) {
                ++started;
                lanes.photon[lane] = static_cast<std::uint32_t>(started - 1);
                if (launch(lane, random.bits64(), lanes, tally)) return true;
            }
            lanes.packet.active[lane] = 0;
            return false;
        };
        try {
            for (std::size_t lane = 0; lane < Lanes::count; ++lane) active += refill(lane) ? 1 : 0;
            while (active > 0) {
                for (std::uint64_t flags = step_rte_packet(model_, lanes.packet); flags != 0; flags &= flags - 1) {
                    const auto lane = static_cast<std::size_t>(std::countr_zero(flags));
                    const bool finished = white_ ? settle_white(lane, lanes) : settle(lane, lanes, truncated);
                    if (!finished) continue;
                    finish(lane, lanes, tally);
                    if (!refill(lane)) --active;
                }
            }
        } catch (...) {
            scratch.reset();  // lanes left mid-photon are not reused
            throw;
        }
        tally.add_truncated(truncated);
        if (exits) {
            exits->group_by_photon();
            exits->photons = photons;
            exits->specular = specular_;
        }
    }

private:
    void build_model() {
        auto& m = model_;
        m.layers = static_cast<std::int32_t>(stack_.layers.size());
        double z = 0.0;
        for (std::size_t k = 0; k < stack_.layers.size(); ++k) {
            const auto& l = stack_.layers[k];
            const double mu = white_ ? l.mu_s_per_cm : l.mu_a_per_cm + l.mu_s_per_cm;
            m.mu_per_cm.push_back(static_cast<float>(mu));
            m.top_cm.push_back(static_cast<float>(z));
            z += l.thickness_cm;
            m.bottom_cm.push_back(static_cast<float>(z));
            PacketPhase phase = PacketPhase::none;
            std::int32_t offset = 0, size = 1;
            if (l.mu_s_per_cm > 0.0) {
                switch (l.phase.kind) {
                    case PhaseFunction::Kind::henyey_greenstein:
                    case PhaseFunction::Kind::isotropic: phase = PacketPhase::henyey_greenstein; break;
                    case PhaseFunction::Kind::two_term_hg: phase = PacketPhase::two_term_hg; break;
                    case PhaseFunction::Kind::rayleigh: phase = PacketPhase::rayleigh; break;
                    case PhaseFunction::Kind::tabulated:
                        phase = PacketPhase::tabulated;
                        offset = static_cast<std::int32_t>(m.table_cos.size());
                        size = static_cast<std::int32_t>(l.phase.table->size());
                        for (std::size_t i = 0; i < l.phase.table->size(); ++i) m.table_cos.push_back(static_cast<float>(l.phase.table->cos_theta(i)));
                        break;
                }
            }
            m.phase.push_back(static_cast<std::int32_t>(phase));
            m.table_offset.push_back(offset);
            m.table_size.push_back(size);
            m.g.push_back(static_cast<float>(l.phase.kind == PhaseFunction::Kind::isotropic ? 0.0 : l.phase.g));
            m.g2.push_back(static_cast<float>(l.phase.g2));
            m.first_term_weight.push_back(static_cast<float>(l.phase.weight));
            const double n = l.refractive_index;
            const double below = k + 1 == stack_.layers.size() ? stack_.below_refractive_index : stack_.layers[k + 1].refractive_index;
            const double above = k == 0 ? stack_.above_refractive_index : stack_.layers[k - 1].refractive_index;
            m.eta_down.push_back(static_cast<float>(n / below));
            m.inverse_eta_down.push_back(static_cast<float>(below / n));
            m.eta_up.push_back(static_cast<float>(n / above));
            m.inverse_eta_up.push_back(static_cast<float>(above / n));
        }
        m.reflector = stack_.bottom_reflector;
        m.reflector_reflectance = static_cast<float>(stack_.bottom_reflectance);
        m.split = request_.boundaries == BoundaryMode::split;
        m.flag_every_segment = white_;
        m.radius = request_.grid.nr > 0 || ch_.nw > 0;
        m.max_steps = static_cast<std::uint32_t>(request_.max_steps_per_photon);
        m.pad();
    }

    std::size_t r_bin(double r_cm) const {
        return static_cast<std::size_t>(std::min<std::int64_t>(static_cast<std::int64_t>(r_cm * inverse_dr_), last_r_));  // beyond: last bin (MCML)
    }
    std::size_t a_bin(double cos_exit) const {
        const double a = std::acos(std::clamp(cos_exit, 0.0, 1.0));
        return std::min(static_cast<std::size_t>(a / (0.5 * pi / static_cast<double>(ch_.na))), ch_.na - 1);
    }

    // A deposit of lane `lane`'s photon in `layer` at radius r_cm and depth z (cm): per photon into its layer's sum, into the grids by
    // batch means. `set` offsets the channels of one absorption set (white mode); 0 otherwise.
    void absorb(Lanes& lanes, std::size_t lane, std::size_t layer, double r_cm, double z, double w, std::size_t set = 0) const {
        if (recording_) return;  // the exit replay tallies escapes only
        lanes.deposited[(lane * sets_ + set) * lanes.layers + layer] += w;
        if (ch_.nz > 0) {
            const std::size_t o = set * ch_.count;
            const auto iz = static_cast<std::size_t>(std::clamp<std::int64_t>(static_cast<std::int64_t>(z * inverse_dz_), 0, last_z_));
            lanes.tally->add_to_batch(o + ch_.a_z + iz, w);
            if (ch_.nr > 0) lanes.tally->add_to_batch(o + ch_.a_rz + r_bin(r_cm) * ch_.nz + iz, w);
        }
    }

    // Weight w of lane `lane`'s photon escaping at radius r_cm with |cos| cos_exit: R or T per photon, the grids by batch means.
    void escape(Lanes& lanes, std::size_t lane, bool top, double r_cm, double cos_exit, double w, std::size_t set = 0) const {
        const std::size_t o = set * ch_.count;
        lanes.scores[lane].add(o + (top ? ch_.reflectance : ch_.transmittance), w);
        auto& t = *lanes.tally;
        if (ch_.nr > 0) t.add_to_batch(o + (top ? ch_.r_r : ch_.t_r) + r_bin(r_cm), w);
        if (ch_.na > 0) t.add_to_batch(o + (top ? ch_.r_a : ch_.t_a) + a_bin(cos_exit), w);
        if (ch_.nr > 0 && ch_.na > 0) t.add_to_batch(o + (top ? ch_.r_ra : ch_.t_ra) + r_bin(r_cm) * ch_.na + a_bin(cos_exit), w);
        if (ch_.nw == 0) return;
        const auto& within = request_.within_radii_cm;
        for (auto k = static_cast<std::size_t>(std::lower_bound(within.begin(), within.end(), r_cm) - within.begin()); k < ch_.nw; ++k) {
            lanes.scores[lane].add(o + (top ? ch_.r_within : ch_.t_within) + k, w);
        }
    }

    // A finished photon: its deposits per layer (and in all) join its score, which joins the tally.
    void finish(std::size_t lane, Lanes& lanes, RayTally& tally) const {
        auto& s = lanes.scores[lane];
        double* deposited = &lanes.deposited[lane * sets_ * lanes.layers];
        for (std::size_t set = 0; set < sets_; ++set, deposited += lanes.layers) {
            double all = 0.0;
            for (std::size_t k = 0; k < lanes.layers; ++k) {
                if (deposited[k] == 0.0) continue;
                s.add(set * ch_.count + ch_.first_layer + k, deposited[k]);
                all += deposited[k];
                deposited[k] = 0.0;
            }
            if (all != 0.0) s.add(set * ch_.count + ch_.absorbed, all);
        }
        tally.add_ray(s);
    }

    // Launch (MCML Sec. 3.3): the specular reflection taken deterministically, the rest refracted into layer 1.
    // False when nothing enters (the photon is tallied).
    bool launch(std::size_t lane, std::uint64_t key, Lanes& lanes, RayTally& tally) const {
        auto& s = lanes.scores[lane];
        if (!recording_) {  // the exit replay adds the batch's specular reflection to every set at once
            for (std::size_t set = 0; set < sets_; ++set) s.add(set * ch_.count + ch_.specular, specular_);
        }
        if (1.0 - specular_ <= 0.0) {
            tally.add_ray(s);
            return false;
        }
        lanes.key[lane] = key;
        lanes.weight[lane] = 1.0 - specular_;
        lanes.log_common[lane] = std::log(1.0 - specular_);
        lanes.alive[lane] = sets_;
        if (recording_) std::fill_n(lanes.path_cm.begin() + static_cast<std::ptrdiff_t>(lane * lanes.layers), lanes.layers, 0.0);
        for (std::size_t set = 0; set < sets_; ++set) {
            lanes.tau[set * Lanes::count + lane] = 0.0;
            lanes.boost_log[set * Lanes::count + lane] = 0.0;
            lanes.limit[set * Lanes::count + lane] = -std::log(roulette_weight);
        }
        lanes.packet.launch(lane, key, static_cast<float>(entry_.x), static_cast<float>(entry_.y), static_cast<float>(entry_.z));
        return true;
    }

    // MCML's way after a segment: absorption by weight at an interaction (Eq. 3.23), Russian roulette below weight
    // 1e-4 with survival 0.1 (Sec. 3.9; energy-conserving: the survivor's gain is taken back where it happened; the
    // draw is keyed by the photon and its step), escapes and the step limit. True when the photon is finished.
    bool settle(std::size_t lane, Lanes& lanes, std::uint64_t& truncated) const {
        const auto& p = lanes.packet;
        double& w = lanes.weight[lane];
        const int bits = p.event_bits[lane];
        const auto k = static_cast<std::size_t>(p.segment_layer[lane]);
        const double r = p.r_cm[lane], z = p.z[lane];
        if (bits & rte_interaction) {
            const double absorbed = w * absorbed_fraction_[k];
            absorb(lanes, lane, k, r, z, absorbed);
            w -= absorbed;
            if (w < roulette_weight) {
                if (w <= 0.0) return true;
                if (RandomStream::keyed_uniform(lanes.key[lane], p.steps[lane]) < roulette_survival) {
                    absorb(lanes, lane, k, r, z, w - w / roulette_survival);  // negative: the survivor's gain
                    w /= roulette_survival;
                } else {
                    absorb(lanes, lane, k, r, z, w);
                    return true;
                }
            }
        }
        if (bits & (rte_left_top | rte_left_bottom)) {
            const double kept = p.kept[lane];
            escape(lanes, lane, (bits & rte_left_top) != 0, r, p.exit_cos[lane], w * (1.0 - kept));
            if (!(kept > 0.0)) return true;
            w *= kept;
        }
        if (bits & rte_truncated) {
            absorb(lanes, lane, k, r, z, w);
            ++truncated;
            return true;
        }
        return false;
    }

    // White Monte Carlo (Alerstam et al. 2008, J. Biomed. Opt. 13:041304): free paths and scattering from mu_s
    // alone, so the path serves every absorption set; set s loses weight by Beer-Lambert along each segment,
    // w_s = (1 - R_sp) c exp(b_s - tau_s) with tau_s its optical depth, b_s its roulette boosts and c the
    // product of the weights kept at split boundaries. Absorption is deposited at the segment's end. Roulette (weight
    // below 1e-4, survival 0.1, energy-conserving) draws a number keyed by (photon, step) shared by every set, so a
    // set's numbers equal those of its own white run to rounding. True when the photon is finished.
    bool settle_white(std::size_t lane, Lanes& lanes) const {
        const auto& p = lanes.packet;
        const int bits = p.event_bits[lane];
        const auto k = static_cast<std::size_t>(p.segment_layer[lane]);
        const double r = p.r_cm[lane], z = p.z[lane];
        const double segment = p.segment_cm[lane];
        if (recording_) lanes.path_cm[lane * lanes.layers + k] += segment;
        const auto at = [&](std::size_t set) { return set * Lanes::count + lane; };
        const auto alive = [&](std::size_t set) { return lanes.limit[at(set)] != dead_limit; };
        const auto weight = [&](std::size_t set) { return std::exp(lanes.log_common[lane] + lanes.boost_log[at(set)] - lanes.tau[at(set)]); };
        const double* mu_a = &mu_a_per_cm_[k * sets_];
        for (std::size_t set = 0; set < sets_; ++set) {
            if (!alive(set) || mu_a[set] <= 0.0) continue;
            if (recording_) {
                lanes.tau[at(set)] += mu_a[set] * segment;  // the exit replay tallies no absorption: no weights to take
            } else {
                const double before = weight(set);
                lanes.tau[at(set)] += mu_a[set] * segment;
                absorb(lanes, lane, k, r, z, before - weight(set), set);
            }
            if (lanes.tau[at(set)] - lanes.boost_log[at(set)] - lanes.log_common[lane] <= lanes.limit[at(set)]) continue;
            const double w = weight(set);
            if (RandomStream::keyed_uniform(lanes.key[lane], p.steps[lane]) < roulette_survival) {
                lanes.boost_log[at(set)] -= std::log(roulette_survival);
                absorb(lanes, lane, k, r, z, w - weight(set), set);  // negative: the survivor's gain
            } else {
                absorb(lanes, lane, k, r, z, w, set);
                lanes.limit[at(set)] = dead_limit;
                --lanes.alive[lane];
            }
        }
        if (lanes.alive[lane] == 0) return true;
        if (bits & (rte_left_top | rte_left_bottom)) {
            const double kept = p.kept[lane];
            for (std::size_t set = 0; set < sets_; ++set) {
                if (!alive(set)) continue;
                const double w = weight(set) * (1.0 - kept);
                if (!recording_) {
                    escape(lanes, lane, (bits & rte_left_top) != 0, r, p.exit_cos[lane], w, set);
                } else if (w > 0.0) {
                    lanes.exits->add(std::span<const double>(&lanes.path_cm[lane * lanes.layers], lanes.layers), w, r, lanes.photon[lane],
                                     (bits & rte_left_top) != 0);
                }
            }
            if (!(kept > 0.0)) return true;
            lanes.log_common[lane] += std::log(kept);
        }
        if (bits & rte_truncated) {
            for (std::size_t set = 0; set < sets_; ++set) {
                if (!alive(set)) continue;
                absorb(lanes, lane, k, r, z, weight(set), set);
                if (!recording_) lanes.scores[lane].add(set * ch_.count + ch_.truncated, 1.0);
            }
            if (recording_) {
                for (std::size_t set = 0; set < tally_sets_; ++set) lanes.scores[lane].add(set * ch_.count + ch_.truncated, 1.0);
            }
            return true;
        }
        return false;
    }

    const RteRequest& request_;
    const RteStack& stack_;
    const Channels& ch_;
    std::size_t sets_;
    bool white_;
    bool recording_;          // the exit replay
    std::size_t tally_sets_;  // the sets the tally holds: sets_, or the exit replay's
    std::vector<double> mu_a_per_cm_;        // white mode: [layer * sets + set]
    std::vector<double> absorbed_fraction_;  // MCML's way: mu_a / mu_t per layer
    Direction entry_;
    double specular_ = 0.0;
    double inverse_dz_ = 0.0, inverse_dr_ = 0.0;  // 1/cm
    std::int64_t last_z_ = 0, last_r_ = 0;        // the last grid bins
    RtePacketModel model_;
};

// Photon by photon over a batch's exits (BatchExits: a photon's consecutive): single(e) for a photon that left once,
// group(first, last) for one that left several times (split boundaries).
template <class Single, class Group>
void by_photon(const BatchExits& exits, Single&& single, Group&& group) {
    const std::size_t n = exits.size();
    for (std::size_t e = 0; e < n;) {
        std::size_t end = e + 1;
        while (end < n && exits.photon[end] == exits.photon[e]) ++end;
        if (end == e + 1) {
            single(e);
        } else {
            group(e, end);
        }
        e = end;
    }
}

// Set `set`'s value of each exit of a batch: its weight at the floor times exp(-sum_k (mu_a,k - floor_k) L_k).
void exit_values(const BatchExits& exits, const std::vector<double>& mu_a_per_cm, std::vector<float>& scratch, std::vector<double>& values) {
    exits.paths.weights(mu_a_per_cm, scratch);
    values.resize(exits.size());
    for (std::size_t e = 0; e < exits.size(); ++e) values[e] = exits.weight[e] * static_cast<double>(scratch[e]);
}

// The exit replay's per-photon channels of one batch for every set: R, T and the within-radius channels, as sums and
// sums of squares of each photon's value. A photon that left once is worth its exit's value in each channel that holds
// its exit, so its squares are summed per radius band between two within radii and accumulated outwards.
void replay_exit_channels(const BatchExits& exits, const std::vector<std::vector<double>>& mu_a_sets, const std::vector<double>& within_cm,
                          const Channels& ch, RayTally& tally) {
    const std::size_t nw = within_cm.size();
    std::vector<std::size_t> band(exits.size());
    for (std::size_t e = 0; e < exits.size(); ++e) {
        band[e] = static_cast<std::size_t>(std::lower_bound(within_cm.begin(), within_cm.end(), static_cast<double>(exits.r_cm[e])) - within_cm.begin());
    }
    std::vector<float> scratch;
    std::vector<double> v;
    for (std::size_t set = 0; set < mu_a_sets.size(); ++set) {
        exit_values(exits, mu_a_sets[set], scratch, v);
        double side_sum[2] = {}, side_sq[2] = {};
        std::vector<double> band_sum(2 * (nw + 1)), band_sq(2 * (nw + 1)), within_sum(2 * nw), within_sq(2 * nw), value(2 * nw);
        by_photon(
            exits,
            [&](std::size_t e) {
                const std::size_t side = exits.top[e] ? 0 : 1;
                side_sum[side] += v[e];
                side_sq[side] += v[e] * v[e];
                band_sum[side * (nw + 1) + band[e]] += v[e];
                band_sq[side * (nw + 1) + band[e]] += v[e] * v[e];
            },
            [&](std::size_t first, std::size_t last) {
                double side_value[2] = {};
                std::fill(value.begin(), value.end(), 0.0);
                for (std::size_t e = first; e < last; ++e) {
                    const std::size_t side = exits.top[e] ? 0 : 1;
                    side_value[side] += v[e];
                    for (std::size_t k = band[e]; k < nw; ++k) value[side * nw + k] += v[e];
                }
                for (std::size_t side = 0; side < 2; ++side) {
                    side_sum[side] += side_value[side];
                    side_sq[side] += side_value[side] * side_value[side];
                }
                for (std::size_t i = 0; i < 2 * nw; ++i) {
                    within_sum[i] += value[i];
                    within_sq[i] += value[i] * value[i];
                }
            });
        const std::size_t o = set * ch.count;
        const auto n = static_cast<double>(exits.photons);
        tally.add_exits(o + ch.specular, n * exits.specular, n * exits.specular * exits.specular);
        tally.add_exits(o + ch.reflectance, side_sum[0], side_sq[0]);
        tally.add_exits(o + ch.transmittance, side_sum[1], side_sq[1]);
        for (std::size_t side = 0; side < 2; ++side) {
            double sum = 0.0, sq = 0.0;
            for (std::size_t k = 0; k < nw; ++k) {
                sum += band_sum[side * (nw + 1) + k];
                sq += band_sq[side * (nw + 1) + k];
                tally.add_exits(o + (side == 0 ? ch.r_within : ch.t_within) + k, sum + within_sum[side * nw + k], sq + within_sq[side * nw + k]);
            }
        }
    }
}

// The exit replay's rings for set `mu_a_per_cm` over every batch in order: R(r) and T(r) per ring of width dr (the last
// also collecting everything beyond, as MCML's), each per-photon mean and standard error in MCML's units (1/cm^2).
void replay_exit_rings(const std::vector<const BatchExits*>& batches, const std::vector<double>& mu_a_per_cm, const RteGrid& grid, std::uint64_t photons,
                       std::vector<Estimate>& reflectance_r, std::vector<Estimate>& transmittance_r) {
    const auto nr = static_cast<std::size_t>(grid.nr);
    std::vector<double> sum(2 * nr), sq(2 * nr);
    std::vector<float> scratch;
    std::vector<double> v;
    std::vector<std::pair<std::size_t, double>> photon_rings;  // a photon's (side * nr + ring, value) of a group
    for (const auto* exits : batches) {
        exit_values(*exits, mu_a_per_cm, scratch, v);
        by_photon(
            *exits,
            [&](std::size_t e) {
                const std::size_t i = exits->ring[e];
                sum[i] += v[e];
                sq[i] += v[e] * v[e];
            },
            [&](std::size_t first, std::size_t last) {
                photon_rings.clear();
                for (std::size_t e = first; e < last; ++e) {
                    const std::size_t i = exits->ring[e];
                    const auto at = std::find_if(photon_rings.begin(), photon_rings.end(), [&](const auto& pr) { return pr.first == i; });
                    if (at == photon_rings.end()) {
                        photon_rings.emplace_back(i, v[e]);
                    } else {
                        at->second += v[e];
                    }
                }
                for (const auto& [i, value] : photon_rings) {
                    sum[i] += value;
                    sq[i] += value * value;
                }
            });
    }
    const double n = static_cast<double>(photons);
    for (std::size_t i = 0; i < 2 * nr; ++i) {
        const double mean = sum[i] / n;
        const double variance = photons > 1 ? std::max(0.0, sq[i] / n - mean * mean) / (n - 1.0) : 0.0;
        const double area = 2.0 * pi * (static_cast<double>(i % nr) + 0.5) * grid.dr_cm * grid.dr_cm;  // MCML's ring area
        (i < nr ? reflectance_r : transmittance_r).push_back({mean / area, std::sqrt(variance) / area});
    }
}

std::vector<Estimate> scaled(const RayTally& t, std::size_t first, std::size_t n, const std::function<double(std::size_t)>& scale) {
    std::vector<Estimate> out;
    for (std::size_t i = 0; i < n; ++i) {
        const auto e = t.estimate(first + i);
        out.push_back({e.value * scale(i), e.stderr * scale(i)});
    }
    return out;
}

}  // namespace

namespace {

// Runs the walk (MCML's way without `mu_a_sets`, white with them) and returns one result per set.
// `exit_replay` (solve_rte_exit_sets): one white trace at the sets' floor, its exits recorded and replayed per set.
std::vector<RteResult> run_walk(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets, bool exit_replay = false) {
    validate(request.stack);
    check_incidence_deg(request.incidence_deg);
    if (request.photons < 1) throw InputError("photon count 0 is outside [1, inf)");
    if (request.max_steps_per_photon < 1 || request.max_steps_per_photon > 2147483647) {
        throw InputError("maximum steps per photon " + std::to_string(request.max_steps_per_photon) + " is outside [1, 2147483647]");
    }
    const auto& g = request.grid;
    if (g.nz < 0 || g.nr < 0 || g.na < 0 || ((g.nz > 0 || g.nr > 0) && !(g.dz_cm > 0.0 && g.dr_cm > 0.0))) {
        throw InputError("grid: bin counts must be >= 0 and dz, dr > 0");
    }
    for (const auto& set : mu_a_sets) {
        if (set.size() != request.stack.layers.size()) throw InputError("absorption set: one mu_a per layer is needed");
        for (const double mu : set) {
            if (!(std::isfinite(mu) && mu >= 0.0)) throw InputError("absorption set: mu_a [1/cm] = " + format_number(mu) + " is outside [0, inf)");
        }
    }
    const auto& within = request.within_radii_cm;
    for (std::size_t k = 0; k < within.size(); ++k) {
        if (!(std::isfinite(within[k]) && within[k] > 0.0) || (k > 0 && !(within[k] > within[k - 1]))) {
            throw InputError("within radii: " + format_number(within[k]) + " cm is not positive and above the one before");
        }
    }
    if (exit_replay && (g.nz > 0 || g.na > 0)) throw InputError("exit replay: only escapes are tallied (no absorption or angle grids)");
    // The exit replay's floor: per layer the least absorption of the sets; its tally holds no grids (rings are replayed
    // from the recorded exits after the walk).
    std::vector<double> floor;
    if (exit_replay) {
        floor = mu_a_sets.front();
        for (const auto& set : mu_a_sets) {
            for (std::size_t k = 0; k < floor.size(); ++k) floor[k] = std::min(floor[k], set[k]);
        }
    }
    const Channels channels(request.stack.layers.size(), exit_replay ? RteGrid{g.dz_cm, g.dr_cm, 0, 0, 0} : g, within.size());
    const std::size_t sets = std::max<std::size_t>(1, mu_a_sets.size());
    const Walk walk = exit_replay ? Walk(request, channels, {floor}, sets) : Walk(request, channels, mu_a_sets);
    std::mutex recorded_mutex;
    std::map<std::uint64_t, BatchExits> recorded;  // the exit replay's batches by index

    SpectralRequest driver;
    driver.wavelengths = WavelengthGrid::list({request.stream_key});
    driver.max_rays_per_wavelength = request.photons;
    driver.stderr_target = request.stderr_target;
    driver.seed = request.seed;
    // The grids' standard errors are batch means: at least 64 batches when the budget allows (batches of 64 to 4096).
    // With a target the rays are not known ahead: batches of 1024 give ~60 at the ~6e4 photons a 0.002 target takes.
    if (g.nz > 0 || g.nr > 0 || g.na > 0) {  // the exit replay's rings as the grid's, for photon counts alike
        driver.rays_per_batch = std::clamp<std::uint64_t>(request.stderr_target ? 1024 : request.photons / 64, 64, driver.rays_per_batch);
    }
    driver.on_progress = request.on_progress;
    driver.cancel = request.cancel;
    std::vector<std::size_t> targets{channels.reflectance, channels.transmittance};
    for (std::size_t k = 0; k < within.size(); ++k) targets.insert(targets.end(), {channels.r_within + k, channels.t_within + k});
    const auto trace = [&](std::size_t, std::uint64_t batch, RandomStream& random, std::uint64_t n, RayTally& tally) {
        if (!exit_replay) {
            walk.trace(random, n, tally);
            return;
        }
        BatchExits exits;
        walk.trace(random, n, tally, &exits);
        exits.paths.thinned_at_per_cm = floor;
        if (g.nr > 0) exits.rings_of(g.dr_cm, static_cast<std::size_t>(g.nr));
        replay_exit_channels(exits, mu_a_sets, within, channels, tally);
        const std::scoped_lock lock(recorded_mutex);
        recorded.emplace(batch, std::move(exits));
    };
    const auto outcome = run_batches(driver, channels.count * sets, targets, trace, sets);
    std::vector<const BatchExits*> batches;
    for (const auto& [batch, exits] : recorded) batches.push_back(&exits);

    std::vector<RteResult> results;
    const auto& t = outcome.tallies.front();
    // MCML 1.2 scaling (ScaleRdTt, ScaleA): per area of the ring, per solid angle 2 pi sin(a) da, per volume.
    const double dz = g.dz_cm, dr = g.dr_cm, da = g.na > 0 ? 0.5 * pi / g.na : 0.0;
    const auto ring = [&](std::size_t ir) { return 2.0 * pi * (ir + 0.5) * dr * dr; };
    const auto cone = [&](std::size_t ia) { return 2.0 * pi * std::sin((ia + 0.5) * da) * da; };
    const auto one = [](std::size_t) { return 1.0; };
    const auto ra_scale = [&](std::size_t i) {
        const std::size_t ir = i / std::max<std::size_t>(1, channels.na), ia = i % std::max<std::size_t>(1, channels.na);
        return 1.0 / (4.0 * pi * pi * dr * dr * std::sin(da / 2.0) * (ir + 0.5) * std::sin(2.0 * (ia + 0.5) * da));
    };
    for (std::size_t set = 0; set < sets; ++set) {
        const std::size_t o = set * channels.count;
        RteResult r;
        r.partial = outcome.cancelled;
        r.photons = t.rays();
        r.truncated_photons = mu_a_sets.empty() ? t.truncated() : static_cast<std::uint64_t>(std::llround(t.sum(o + channels.truncated)));
        if (r.photons > 0) {
            r.specular_reflectance = t.estimate(o + channels.specular);
            r.diffuse_reflectance = t.estimate(o + channels.reflectance);
            r.transmittance = t.estimate(o + channels.transmittance);
            r.absorption_layers = scaled(t, o + channels.first_layer, channels.layers, one);
            r.absorbed = t.estimate(o + channels.absorbed);
            r.absorption_z = scaled(t, o + channels.a_z, channels.nz, [&](std::size_t) { return 1.0 / dz; });
            r.reflectance_r = scaled(t, o + channels.r_r, channels.nr, [&](std::size_t ir) { return 1.0 / ring(ir); });
            r.transmittance_r = scaled(t, o + channels.t_r, channels.nr, [&](std::size_t ir) { return 1.0 / ring(ir); });
            r.reflectance_a = scaled(t, o + channels.r_a, channels.na, [&](std::size_t ia) { return 1.0 / cone(ia); });
            r.transmittance_a = scaled(t, o + channels.t_a, channels.na, [&](std::size_t ia) { return 1.0 / cone(ia); });
            r.absorption_rz = scaled(t, o + channels.a_rz, channels.nr * channels.nz,
                                     [&](std::size_t i) { return 1.0 / (ring(i / std::max<std::size_t>(1, channels.nz)) * dz); });
            r.reflectance_ra = scaled(t, o + channels.r_ra, channels.nr * channels.na, ra_scale);
            r.transmittance_ra = scaled(t, o + channels.t_ra, channels.nr * channels.na, ra_scale);
            r.reflectance_within = scaled(t, o + channels.r_within, channels.nw, one);
            r.transmittance_within = scaled(t, o + channels.t_within, channels.nw, one);
        }
        results.push_back(std::move(r));
    }
    // The exit replay's rings, set by set on the threads (each set's sums in batch order: the same for any thread count).
    if (exit_replay && g.nr > 0 && !outcome.cancelled && t.rays() > 0) {
        tbb::parallel_for(std::size_t{0}, sets, [&](std::size_t set) {
            replay_exit_rings(batches, mu_a_sets[set], g, results[set].photons, results[set].reflectance_r, results[set].transmittance_r);
        });
    }
    return results;
}

std::vector<double> own_absorption(const RteStack& stack) {
    std::vector<double> mu_a;
    for (const auto& l : stack.layers) mu_a.push_back(l.mu_a_per_cm);
    return mu_a;
}

}  // namespace

RteResult solve_rte(const RteRequest& request) {
    return run_walk(request, request.white ? std::vector<std::vector<double>>{own_absorption(request.stack)} : std::vector<std::vector<double>>{})
        .front();
}

std::vector<RteResult> solve_rte_sets(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets) {
    if (mu_a_sets.empty()) throw InputError("absorption replay: no absorption sets");
    return run_walk(request, mu_a_sets);
}

std::vector<RteResult> solve_rte_exit_sets(const RteRequest& request, const std::vector<std::vector<double>>& mu_a_sets) {
    if (mu_a_sets.empty()) throw InputError("exit replay: no absorption sets");
    return run_walk(request, mu_a_sets, true);
}

SpectralResult solve_rte_spectrum(const LayerStack& stack, const SpectralRequest& request, BoundaryMode boundaries) {
    return solve_rte_spectra({&stack}, request, boundaries, false).front();
}

namespace {

// A result's model, names and settings before its rows.
SpectralResult walk_result(const std::string& material, const std::vector<std::string>& layer_names, const SpectralRequest& request,
                           BoundaryMode boundaries, const std::string& bottom, bool replay, std::size_t sets) {
    SpectralResult o;
    o.model = "rte";
    o.material = material;
    o.quantities = Quantities{true, true, true, false};
    o.layer_names = layer_names;
    o.settings = {{"incidence_deg", request.incidence_deg},
                  {"seed", request.seed},
                  {"max_rays_per_wavelength", request.max_rays_per_wavelength},
                  {"boundaries", std::string(to_string(boundaries))},
                  {"bottom", bottom},
                  {"absorption", std::string(replay ? "white Monte Carlo (Beer-Lambert along mu_s paths)" : "MCML (albedo per interaction)")},
                  {"absorption_sets_traced_together", std::uint64_t{sets}},
                  {"roulette", std::string("weight < 1e-4, survival 0.1, energy-conserving")}};
    if (request.stderr_target) o.settings["stderr_target"] = *request.stderr_target;
    return o;
}

// The walk row by row (a wavelength or a band: `row_nm` is the row's wavelength, 0 for a band; `row_keys` keys its
// random streams), every result's medium at a row from `medium(row, result)`; the first result's medium is traced,
// the others replayed on its paths when `replay`. Rows stop at a cancellation, the results marked partial.
std::vector<SpectralResult> walk_rows(std::vector<SpectralResult> out, const SpectralRequest& request, BoundaryMode boundaries, bool replay,
                                      std::span<const double> row_nm, std::span<const double> row_keys,
                                      const std::function<RteStack(std::size_t, std::size_t)>& medium) {
    // One progress for the whole spectrum: rays and rows count on across the per-row runs.
    const std::size_t total = row_nm.size();
    std::uint64_t rays_before = 0;
    std::size_t index = 0;
    const auto progress = [&](const Progress& p) {
        if (!request.on_progress) return;
        // The rows to come are expected to take as many rays as this one (unknown while this one's is).
        const std::uint64_t expected = p.rays_expected > 0 ? rays_before + p.rays_expected * (total - index) : 0;
        request.on_progress(Progress{rays_before + p.rays_done, expected, index + p.wavelengths_done, total});
    };
    for (; index < total;) {
        RteRequest r;
        r.stack = medium(index, 0);
        r.photons = request.max_rays_per_wavelength;
        r.stderr_target = request.stderr_target;
        r.seed = request.seed;
        r.stream_key = row_keys[index];
        r.incidence_deg = request.incidence_deg;
        r.boundaries = boundaries;
        r.on_progress = progress;
        r.cancel = request.cancel;
        std::vector<RteResult> results;
        if (replay) {
            std::vector<std::vector<double>> sets;
            for (std::size_t s = 0; s < out.size(); ++s) sets.push_back(own_absorption(medium(index, s)));
            results = solve_rte_sets(r, sets);
        } else {
            results = {solve_rte(r)};
        }
        rays_before += results.front().photons;
        const double nm = row_nm[index];
        ++index;
        if (results.front().partial) {
            for (auto& o : out) o.partial = true;
            break;
        }
        for (std::size_t s = 0; s < out.size(); ++s) {
            const auto& res = results[s];
            WavelengthResult w;
            w.wavelength_nm = nm;
            // sce leaves out the first-surface reflection (the specular, taken deterministically at launch).
            const double specular = request.geometry == MeasurementGeometry::sce ? 0.0 : res.specular_reflectance.value;
            w.reflectance = {specular + res.diffuse_reflectance.value, res.diffuse_reflectance.stderr};
            w.specular_reflectance = res.specular_reflectance;
            w.transmittance = res.transmittance;
            w.absorptance_layers = res.absorption_layers;
            w.rays = res.photons;
            w.truncated_rays = res.truncated_photons;
            w.converged = !request.stderr_target || (res.diffuse_reflectance.stderr <= *request.stderr_target &&
                                                     res.transmittance.stderr <= *request.stderr_target);
            out[s].wavelengths.push_back(std::move(w));
        }
    }
    return out;
}

}  // namespace

std::vector<SpectralResult> solve_rte_spectra(const std::vector<const LayerStack*>& stacks, const SpectralRequest& request,
                                              BoundaryMode boundaries, bool white) {
    if (stacks.empty()) throw InputError("absorption replay: no stacks to simulate");
    const bool replay = stacks.size() > 1 || white;
    require_shared_paths(stacks, TracedPaths::volumetric);
    std::vector<SpectralResult> out;
    for (const auto* stack : stacks) {
        std::vector<std::string> layers;
        for (const auto& l : stack->layers) layers.push_back(l.name);
        out.push_back(walk_result(stack->name, layers, request, boundaries, std::string(to_string(stack->bottom)), replay, stacks.size()));
    }
    const auto nm = request.wavelengths.nm();
    return walk_rows(std::move(out), request, boundaries, replay, nm, nm,
                     [&](std::size_t row, std::size_t s) { return rte_stack_from(*stacks[s], nm[row]); });
}

RteStack rte_band_slab(const HomogeneousMaterial& material, std::size_t band) {
    const double reduced_per_mm = material.reduced_scattering_per_mm[band], absorption_per_mm = material.absorption_per_mm[band];
    const double transport_per_mm = reduced_per_mm + absorption_per_mm;
    // Deep enough that diffuse light reaching the bottom is below exp(-25) ~ 1e-11 of the incident: 25 / mu_eff, with
    // mu_eff = sqrt(3 mu_a (mu_a + mu_s')) (Farrell et al. 1992 Eq. 7); at least 200 and at most 1e4 mean free paths.
    const double effective_per_mm = std::sqrt(3.0 * absorption_per_mm * transport_per_mm);
    const double mean_free_paths = std::clamp(effective_per_mm > 0.0 ? 25.0 * transport_per_mm / effective_per_mm : band_slab_max_mean_free_paths,
                                              band_slab_min_mean_free_paths, band_slab_max_mean_free_paths);
    RteStack stack;
    stack.layers.push_back({material.relative_refractive_index, absorption_per_mm * 10.0, reduced_per_mm * 10.0,
                            mean_free_paths / transport_per_mm / 10.0, PhaseFunction::isotropic()});
    return stack;
}

SpectralResult solve_rte_bands(const HomogeneousMaterial& material, const SpectralRequest& request, BoundaryMode boundaries) {
    std::vector<SpectralResult> one;
    one.push_back(walk_result(material.name, {material.name}, request, boundaries,
                              "none: a slab deep enough to be semi-infinite to 1e-11 (200 to 1e4 transport mean free paths)", false, 1));
    one.front().bands = material.bands;
    std::vector<double> row_nm(material.bands.size(), 0.0), keys;
    for (std::size_t b = 0; b < material.bands.size(); ++b) keys.push_back(static_cast<double>(b + 1));
    auto result = walk_rows(std::move(one), request, boundaries, false, row_nm, keys,
                            [&](std::size_t row, std::size_t) { return rte_band_slab(material, row); })
                      .front();
    // A nearly non-absorbing band needs a deeper slab than the walk is given: say how much light left through it.
    for (std::size_t b = 0; b < result.wavelengths.size(); ++b) {
        const auto& t = result.wavelengths[b].transmittance;
        if (t.value > band_slab_transmittance_worth_a_warning) {
            result.warnings.push_back({"rte: the band's slab lets light through (R is below the semi-infinite medium's by about T)", material.name,
                                       "band " + material.bands[b], t.value});
        }
    }
    return result;
}

}  // namespace skinspec
