// The BioSpec walk's per-event step on SIMD packets (see biospec_packet.hpp). Compiled once per instruction set by
// Highway's foreach_target and dispatched at run time; each formula is the one of the scalar specification
// (Krishnaswamy & Baranoski 2004; docs/BIOSPEC.md, "One ray"), in lane-parallel form.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "transport/biospec/biospec_packet.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "transport/biospec/biospec_packet.hpp"
#include "transport/lane_stream_seed.hpp"
#include "transport/simd_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skinspec {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

std::uint64_t StepImpl(const BiospecPacketModel& model, BiospecPacket& p) {
    const DF df;
    const DI di;
    std::uint32_t* const rng[4] = {p.rng[0], p.rng[1], p.rng[2], p.rng[3]};
    const std::size_t n = hn::Lanes(df);
    const VF zero = hn::Zero(df);
    const VF one = hn::Set(df, 1.0f);
    const VF tiny_cos = hn::Set(df, 1e-12f);
    const VI last = hn::Set(di, model.layers - 1);
    const MF none = hn::FirstN(df, 0);
    std::uint64_t flags = 0;
    const bool permute = static_cast<std::size_t>(model.layers) <= n;
    const PerLayer<DI> scattering{model.scattering.data(), permute}, redraw{model.redraw.data(), permute},
        table_offsets{model.table_offset.data(), permute}, table_offsets_upper{model.table_offset_upper.data(), permute},
        table_sizes{model.table_size.data(), permute};
    const PerLayer<DF> thicknesses{model.thickness_cm.data(), permute}, hg{model.hg_g.data(), permute},
        table_weights{model.table_upper_weight.data(), permute}, turn_mfp{model.turn_mean_free_path_cm.data(), permute},
        eta_down{model.eta_down.data(), permute}, eta_up{model.eta_up.data(), permute}, inverse_eta_down{model.inverse_eta_down.data(), permute},
        inverse_eta_up{model.inverse_eta_up.data(), permute};
    const PerLayer<DF> mu_a_first{model.mu_a_per_cm.data(), permute}, mu_a_bound{model.mu_a_bound_per_cm.data(), permute};

    for (std::size_t base = 0; base < BiospecPacket::lanes; base += n) {
        const MF active = FromInt(hn::LoadU(di, p.active + base) != hn::Zero(di));
        if (hn::AllFalse(df, active)) continue;
        LaneRandom random = LaneRandom::load(rng, base);
        const VF dx = hn::LoadU(df, p.dx + base);
        const VF dy = hn::LoadU(df, p.dy + base);
        const VF dz = hn::LoadU(df, p.dz + base);
        const VI k = hn::LoadU(di, p.layer + base);
        const VI event = hn::LoadU(di, reinterpret_cast<const std::int32_t*>(p.event) + base);
        const VI kind = scattering.at(k);
        const VF thickness = thicknesses.at(k);
        const MF was_down = dz > zero;
        const MF is_table = hn::And(active, FromInt(kind == hn::Set(di, static_cast<int>(PacketScattering::table))));
        const MF is_hg = hn::And(active, FromInt(kind == hn::Set(di, static_cast<int>(PacketScattering::henyey_greenstein))));
        const MF is_rayleigh = hn::And(active, FromInt(kind == hn::Set(di, static_cast<int>(PacketScattering::rayleigh_cosine))));
        const MF is_cosine = hn::And(active, FromInt(kind == hn::Set(di, static_cast<int>(PacketScattering::cosine))));
        const MF redraw_allowed = FromInt(redraw.at(k) != hn::Zero(di));
        const VI table_offset = table_offsets.at(k);
        const VI table_offset_upper = table_offsets_upper.at(k);
        const VF table_weight = table_weights.at(k);
        const bool mixed = !hn::AllFalse(df, table_weight > zero);
        const VF table_size = hn::ConvertTo(df, table_sizes.at(k));
        const VF hg_g = hg.at(k);

        // Steps 2-3: the crossing's direction change. The polar angle of a perturbing layer (table look-up, HG) ...
        const bool any_table = !hn::AllFalse(df, is_table);
        const bool any_hg = !hn::AllFalse(df, is_hg);
        const auto polar = [&](VF u, VF& c, VF& s) {
            c = one;
            s = zero;
            if (any_table) {
                // The mixture's table by the same u: u < w picks the upper table with u / w, else the lower with
                // (u - w) / (1 - w), each again uniform in [0, 1).
                VF v = u;
                VI offset = table_offset;
                if (mixed) {
                    const MF upper = u < table_weight;
                    v = hn::IfThenElse(upper, hn::Div(u, table_weight), hn::Div(hn::Sub(u, table_weight), hn::Sub(one, table_weight)));
                    offset = hn::IfThenElse(hn::RebindMask(di, upper), table_offset_upper, table_offset);
                }
                const VI index = hn::Add(hn::ConvertTo(di, hn::Min(hn::Mul(v, table_size), hn::Sub(table_size, one))), offset);
                c = hn::GatherIndex(df, model.table_cos, index);
                s = hn::GatherIndex(df, model.table_sin, index);
            }
            if (any_hg) {
                const VF hg = HgCos(hg_g, u);
                c = hn::IfThenElse(is_hg, hg, c);
                s = hn::IfThenElse(is_hg, hn::Sqrt(hn::Max(zero, hn::NegMulAdd(hg, hg, one))), s);
            }
        };
        const VF u = random.uniform();
        // ... the Rayleigh test of a downward crossing and its angle: a free path s = -ln(1 - u) / beta (beta the turn
        // coefficient, Rayleigh plus any Mie part) that ends inside the layer (s |cos_in| < d, probability
        // 1 - exp(-beta d / |cos_in|)) turns the ray ...
        const VF cos_in = hn::Max(hn::Abs(dz), tiny_cos);
        const MF rayleigh_test = hn::And(is_rayleigh, was_down);
        MF rayleigh_turn = none;
        VF free_path_cm = zero;
        if (!hn::AllFalse(df, rayleigh_test)) {
            free_path_cm = hn::Mul(hn::Neg(hn::Log1p(df, hn::Neg(u))), turn_mfp.at(k));
            rayleigh_turn = hn::And(rayleigh_test, hn::Mul(free_path_cm, cos_in) < thickness);
        }
        const VF u2 = random.uniform(is_rayleigh);
        VF c, s;
        polar(u, c, s);
        const bool any_turn = !hn::AllFalse(df, rayleigh_turn);
        if (any_turn) {
            const VF c_rayleigh = RayleighCos(u2);
            c = hn::IfThenElse(rayleigh_turn, c_rayleigh, c);
            s = hn::IfThenElse(rayleigh_turn, hn::Sqrt(hn::Max(zero, hn::NegMulAdd(c_rayleigh, c_rayleigh, one))), s);
        }
        VF cos_phi, sin_phi;
        Azimuth(random.uniform(), cos_phi, sin_phi);
        VF ox, oy, oz;
        Deflect(dx, dy, dz, c, s, cos_phi, sin_phi, ox, oy, oz);
        // ... or a cosine-distributed direction in the travel hemisphere (cos = sqrt(1 - u) > 0, never grazing).
        const MF cosine_now = hn::Or(is_cosine, hn::AndNot(rayleigh_turn, is_rayleigh));
        const VF u_cosine = hn::IfThenElse(is_cosine, u, u2);
        const VF sin_cosine = hn::Sqrt(u_cosine);
        ox = hn::IfThenElse(cosine_now, hn::Mul(sin_cosine, cos_phi), ox);
        oy = hn::IfThenElse(cosine_now, hn::Mul(sin_cosine, sin_phi), oy);
        oz = hn::IfThenElse(cosine_now, hn::CopySign(hn::Sqrt(hn::Sub(one, u_cosine)), dz), oz);

        // Same-hemisphere rule for the perturbing layers: re-draw a perturbation that reverses the travel sense (or
        // grazes); an SC that keeps reversals (authors' behaviour 4) reports them instead.
        const MF perturbing = hn::Or(is_table, is_hg);
        const MF grazing = oz == zero;
        const MF turned = hn::And(perturbing, hn::Or(hn::Xor(oz > zero, was_down), grazing));
        const MF reversed = hn::AndNot(grazing, hn::AndNot(redraw_allowed, turned));
        // A lane that re-draws does not loop here (that would hold the whole packet): it keeps its direction and layer
        // and draws again at the next step, with the other lanes' next events; after max_redraws attempts it keeps
        // the unperturbed direction.
        const MF redrawing = hn::And(turned, hn::Or(redraw_allowed, grazing));
        const VI attempts = hn::LoadU(di, p.attempts + base);
        const MF give_up = hn::And(redrawing, FromInt(attempts == hn::Set(di, max_redraws - 1)));
        const MF retry = hn::AndNot(give_up, redrawing);
        hn::StoreU(hn::IfThenElse(hn::RebindMask(di, retry), hn::Add(attempts, hn::Set(di, 1)), hn::Zero(di)), di, p.attempts + base);
        ox = hn::IfThenElse(redrawing, dx, ox);
        oy = hn::IfThenElse(redrawing, dy, oy);
        oz = hn::IfThenElse(redrawing, dz, oz);
        const MF crossed = hn::AndNot(retry, active);  // the lanes whose crossing is done this step

        // The path the crossing is charged: the whole layer along the new direction, or the Rayleigh turn rule.
        const VF cos_out = hn::Max(hn::Abs(oz), tiny_cos);
        const VF inverse_cos_out = Inverse(cos_out);
        const VF whole = hn::Mul(thickness, inverse_cos_out);
        VF turn_path = whole;
        if (any_turn && model.rayleigh_turn == RayleighTurn::sampled_depth) {
            // Shared spec 2026-12: the free path s that decided the turn, turn at depth s cos_in.
            const VF z_cm = hn::Min(hn::Mul(free_path_cm, cos_in), thickness);
            const VF rest = hn::IfThenElse(oz < zero, z_cm, hn::Sub(thickness, z_cm));
            turn_path = hn::MulAdd(rest, inverse_cos_out, free_path_cm);
        } else if (any_turn && model.rayleigh_turn == RayleighTurn::no_absorption) {
            turn_path = hn::IfThenElse(oz < zero, zero, whole);
        }
        VF path = hn::IfThenElse(rayleigh_turn, turn_path, whole);
        path = hn::IfThenElseZero(hn::AndNot(hn::Or(reversed, retry), crossed), path);
        const MF leaves_reversed = hn::And(reversed, was_down);  // leaves as reflectance, no Fresnel, no absorption

        // Step 4: absorption along the crossing. The path length in the layer, when kept (it serves every set at the
        // same cost: the caller turns it into each set's weight at exits and roulette, or records it). Weighted: the
        // bound on every set's optical depth (one set without layer paths: its depth); random: the per-crossing test.
        MF absorbed = none;
        MF over_limit = absorbed;
        for (std::int32_t layer = 0; model.layer_paths && layer < model.layers; ++layer) {
            float* slot = p.path_cm.data() + static_cast<std::size_t>(layer) * BiospecPacket::lanes + base;
            hn::StoreU(hn::Add(hn::LoadU(df, slot), hn::IfThenElseZero(FromInt(k == hn::Set(di, layer)), path)), df, slot);
        }
        if (model.weighted) {
            const VF bound = hn::MulAdd(mu_a_bound.at(k), path, hn::LoadU(df, p.depth_bound + base));
            hn::StoreU(bound, df, p.depth_bound + base);
            over_limit = bound > hn::LoadU(df, p.look_at + base);
        } else {
            const VF mu_a = mu_a_first.at(k);
            const MF testing = hn::AndNot(leaves_reversed, hn::And(crossed, mu_a > zero));
            const VF survive = hn::Exp(df, hn::Neg(hn::Mul(mu_a, path)));
            absorbed = hn::And(testing, random.uniform(testing) >= survive);
        }
        const VI every = hn::Set(di, static_cast<int>(model.roulette_every - 1));
        const MF look = FromInt(hn::And(event, every) == every);
        const MF roulette_due = model.weighted && model.roulette ? hn::AndNot(leaves_reversed, hn::And(crossed, hn::And(look, over_limit)))
                                                                 : none;

        // Steps 5-6: the interface the ray now meets.
        const MF going = hn::AndNot(hn::Or(leaves_reversed, absorbed), crossed);
        const MF down = oz > zero;
        const MF at_last = FromInt(k == last);
        const MF at_first = FromInt(k == hn::Zero(di));
        MF bounce = model.reflector ? hn::And(going, hn::And(down, at_last)) : none;
        // A reflector of reflectance below 1 keeps the ray with probability 1 - reflectance (it leaves the bottom).
        MF kept_below = none;
        if (model.reflector_reflectance < 1.0f && !hn::AllFalse(df, bounce)) {
            kept_below = hn::And(bounce, random.uniform(bounce) >= hn::Set(df, model.reflector_reflectance));
            bounce = hn::AndNot(kept_below, bounce);
        }
        if (!hn::AllFalse(df, bounce)) {  // the Lambertian reflector: a cosine-distributed upward direction
            const VF u_bounce = random.uniform(bounce);
            Azimuth(random.uniform(bounce), cos_phi, sin_phi);
            const VF sin_bounce = hn::Sqrt(u_bounce);
            ox = hn::IfThenElse(bounce, hn::Mul(sin_bounce, cos_phi), ox);
            oy = hn::IfThenElse(bounce, hn::Mul(sin_bounce, sin_phi), oy);
            oz = hn::IfThenElse(bounce, hn::Neg(hn::Sqrt(hn::Sub(one, u_bounce))), oz);
        }

        const MF bare_exit = hn::Or(kept_below, model.bottom_exit_fresnel ? none : hn::And(down, at_last));
        const MF at_interface = hn::AndNot(hn::Or(bounce, bare_exit), going);
        // The relative index n_from / n_to of the interface ahead (authors' behaviour 1, upward crossings with the
        // indices swapped, is in the model's eta_up) and m = n_to / n_from.
        const VF eta = hn::IfThenElse(down, eta_down.at(k), eta_up.at(k));
        const VF m = hn::IfThenElse(down, inverse_eta_down.at(k), inverse_eta_up.at(k));
        const MF same_index = eta == one;
        // Fresnel's reflectance and Snell's refraction.
        VF cos_t;
        MF total;
        const VF reflectance = FresnelReflectance(hn::Abs(oz), eta, m, cos_t, total);
        const MF fresnel = hn::AndNot(same_index, at_interface);
        const MF test = hn::AndNot(total, hn::And(fresnel, reflectance > zero));
        MF reflected = hn::And(fresnel, total);
        if (!hn::AllFalse(df, test)) reflected = hn::Or(reflected, hn::And(test, random.uniform(test) < reflectance));
        const MF refracted = hn::AndNot(reflected, fresnel);
        const MF moving = hn::AndNot(hn::Or(bounce, reflected), going);
        ox = hn::IfThenElse(refracted, hn::Mul(eta, ox), ox);
        oy = hn::IfThenElse(refracted, hn::Mul(eta, oy), oy);
        oz = hn::IfThenElse(reflected, hn::Neg(oz), hn::IfThenElse(refracted, hn::CopySign(cos_t, oz), oz));

        const MF leaves_bottom = hn::And(moving, hn::And(down, at_last));
        const MF leaves_top = hn::Or(leaves_reversed, hn::And(moving, hn::AndNot(down, at_first)));
        const auto dmask = [&](MF m) { return hn::RebindMask(di, m); };
        VI next_k = hn::IfThenElse(dmask(hn::AndNot(at_last, hn::And(moving, down))), hn::Add(k, hn::Set(di, 1)), k);
        next_k = hn::IfThenElse(dmask(hn::AndNot(at_first, hn::AndNot(down, moving))), hn::Sub(k, hn::Set(di, 1)), next_k);
        const VI next_event = hn::IfThenElse(dmask(crossed), hn::Add(event, hn::Set(di, 1)), event);

        VI status = hn::Zero(di);
        status = hn::IfThenElse(dmask(leaves_top), hn::Set(di, static_cast<int>(LaneStatus::left_top)), status);
        status = hn::IfThenElse(dmask(leaves_bottom), hn::Set(di, static_cast<int>(LaneStatus::left_bottom)), status);
        status = hn::IfThenElse(dmask(absorbed), hn::Set(di, static_cast<int>(LaneStatus::absorbed)), status);
        const MF walking = hn::And(crossed, FromInt(status == hn::Zero(di)));
        const MF truncated = hn::And(walking, FromInt(next_event > hn::Set(di, static_cast<int>(model.max_events) - 1)));
        status = hn::IfThenElse(dmask(truncated), hn::Set(di, static_cast<int>(LaneStatus::truncated)), status);
        const VF exit_cos = hn::IfThenElse(leaves_bottom, oz, hn::Neg(oz));

        hn::StoreU(ox, df, p.dx + base);
        hn::StoreU(oy, df, p.dy + base);
        hn::StoreU(oz, df, p.dz + base);
        hn::StoreU(exit_cos, df, p.exit_cos + base);
        hn::StoreU(next_k, di, p.layer + base);
        hn::StoreU(k, di, p.crossing_layer + base);
        hn::StoreU(status, di, p.status + base);
        hn::StoreU(hn::IfThenElseZero(dmask(roulette_due), hn::Set(di, 1)), di, p.roulette_due + base);
        hn::StoreU(next_event, di, reinterpret_cast<std::int32_t*>(p.event) + base);
        random.store(rng, base);

        const MF attention = model.flag_every_event
                                 ? crossed
                                 : hn::And(crossed, hn::Or(roulette_due, FromInt(status != hn::Zero(di))));
        flags |= MaskBits(attention, base);
    }
    return flags;
}

const char* TargetImpl() { return hwy::TargetName(HWY_TARGET); }

void SetsImpl(const SetArrays& a) {
    const hn::ScalableTag<double> dd;
    if (a.due) std::fill_n(a.due, (a.set_stride + 63) / 64, std::uint64_t{0});
    for (std::size_t s = 0; s < a.sets; s += hn::Lanes(dd)) {
        auto tau = hn::Zero(dd);
        for (std::size_t k = 0; k < a.layers; ++k) tau = hn::MulAdd(hn::LoadU(dd, a.mu_a_per_cm + k * a.set_stride + s), hn::Set(dd, a.path_cm[k]), tau);
        hn::StoreU(tau, dd, a.depth + s);
        if (a.due) {
            std::uint8_t bits[8] = {};
            hn::StoreMaskBits(dd, tau > hn::LoadU(dd, a.limit + s), bits);
            a.due[s / 64] |= static_cast<std::uint64_t>(bits[0]) << (s % 64);
        }
        if (a.weight) hn::StoreU(hn::Exp(dd, hn::Sub(hn::LoadU(dd, a.boost_log + s), tau)), dd, a.weight + s);
    }
}

double SetMarginImpl(std::size_t set_stride, const double* limit, const double* depth) {
    const hn::ScalableTag<double> dd;
    auto margin = hn::Set(dd, HUGE_VAL);
    for (std::size_t s = 0; s < set_stride; s += hn::Lanes(dd)) margin = hn::Min(margin, hn::Sub(hn::LoadU(dd, limit + s), hn::LoadU(dd, depth + s)));
    return hn::GetLane(hn::MinOfLanes(dd, margin));
}

}  // namespace HWY_NAMESPACE
}  // namespace skinspec
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skinspec {

HWY_EXPORT(StepImpl);
HWY_EXPORT(TargetImpl);
HWY_EXPORT(SetsImpl);
HWY_EXPORT(SetMarginImpl);

std::uint64_t step_biospec_packet(const BiospecPacketModel& model, BiospecPacket& packet) {
    return HWY_DYNAMIC_DISPATCH(StepImpl)(model, packet);
}

const char* biospec_packet_target() { return HWY_DYNAMIC_DISPATCH(TargetImpl)(); }

void biospec_sets(const SetArrays& a) { HWY_DYNAMIC_DISPATCH(SetsImpl)(a); }

double biospec_set_margin(std::size_t set_stride, const double* limit, const double* depth) {
    return HWY_DYNAMIC_DISPATCH(SetMarginImpl)(set_stride, limit, depth);
}

void BiospecPacketModel::pad() {
    layer_stride = (static_cast<std::size_t>(layers) + widest_vector - 1) / widest_vector * widest_vector;
    for (auto* v : {&scattering, &redraw, &table_offset, &table_offset_upper, &table_size}) v->resize(layer_stride, 0);
    for (auto* v : {&thickness_cm, &eta_down, &eta_up, &inverse_eta_down, &inverse_eta_up, &turn_mean_free_path_cm, &hg_g, &table_upper_weight,
                    &mu_a_per_cm, &mu_a_bound_per_cm}) {
        v->resize(layer_stride, 0.0f);
    }
}

void BiospecPacket::seed_lane(std::size_t lane, std::uint64_t key) { seed_lane_stream(rng, lane, key); }

}  // namespace skinspec
#endif
