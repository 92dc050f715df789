// The volumetric walk's per-segment step on SIMD packets (see rte_packet.hpp). Compiled once per instruction set by
// Highway's foreach_target and dispatched at run time; each formula is MCML's (Wang, Jacques & Zheng 1995) in
// lane-parallel form.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "transport/rte/rte_packet.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <limits>

#include "transport/lane_stream_seed.hpp"
#include "transport/rte/rte_packet.hpp"
#include "transport/simd_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace skinspec {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

std::uint64_t RteStepImpl(const RtePacketModel& model, RtePacket& p) {
    const DF df;
    const DI di;
    const std::size_t n = hn::Lanes(df);
    const VF zero = hn::Zero(df);
    const VF one = hn::Set(df, 1.0f);
    const VF infinity = hn::Set(df, std::numeric_limits<float>::infinity());
    const VI last = hn::Set(di, model.layers - 1);
    const MF none = hn::FirstN(df, 0);
    std::uint32_t* const rng[4] = {p.rng[0], p.rng[1], p.rng[2], p.rng[3]};
    const bool permute = static_cast<std::size_t>(model.layers) <= n;
    const PerLayer<DI> phases{model.phase.data(), permute}, table_offsets{model.table_offset.data(), permute},
        table_sizes{model.table_size.data(), permute};
    const PerLayer<DF> mus{model.mu_per_cm.data(), permute}, tops{model.top_cm.data(), permute}, bottoms{model.bottom_cm.data(), permute},
        gs{model.g.data(), permute}, g2s{model.g2.data(), permute}, first_weights{model.first_term_weight.data(), permute},
        eta_down{model.eta_down.data(), permute}, eta_up{model.eta_up.data(), permute}, inverse_eta_down{model.inverse_eta_down.data(), permute},
        inverse_eta_up{model.inverse_eta_up.data(), permute};
    const auto kind_is = [&](VI kind, PacketPhase phase) { return FromInt(kind == hn::Set(di, static_cast<int>(phase))); };
    std::uint64_t flags = 0;

    for (std::size_t base = 0; base < RtePacket::lanes; base += n) {
        const MF active = FromInt(hn::LoadU(di, p.active + base) != hn::Zero(di));
        if (hn::AllFalse(df, active)) continue;
        LaneRandom random = LaneRandom::load(rng, base);
        VF x = hn::LoadU(df, p.x + base);
        VF y = hn::LoadU(df, p.y + base);
        VF z = hn::LoadU(df, p.z + base);
        VF dx = hn::LoadU(df, p.dx + base);
        VF dy = hn::LoadU(df, p.dy + base);
        VF dz = hn::LoadU(df, p.dz + base);
        const VI k = hn::LoadU(di, p.layer + base);
        const VF mu = mus.at(k);
        const VF top = tops.at(k);
        const VF bottom = bottoms.at(k);

        // The free path: a new optical depth -ln(1 - u) (Eq. 3.7) once the last one is used up.
        const VF tau_before = hn::LoadU(df, p.tau_left + base);
        const MF draw = hn::And(active, tau_before <= zero);
        VF tau = tau_before;
        if (!hn::AllFalse(df, draw)) tau = hn::IfThenElse(draw, hn::Neg(hn::Log1p(df, hn::Neg(random.uniform(draw)))), tau);
        const MF scatters = mu > zero;
        const VF free_path = hn::IfThenElse(scatters, hn::Div(tau, hn::Max(mu, hn::Set(df, 1e-30f))), infinity);
        // Distance to the boundary ahead (MCML's HitBoundary, Sec. 3.5).
        const MF down = dz > zero;
        const MF up = dz < zero;
        const VF inverse_dz = hn::Div(one, hn::IfThenElse(hn::Or(down, up), dz, one));
        const VF to_boundary = hn::IfThenElse(down, hn::Mul(hn::Sub(bottom, z), inverse_dz),
                                              hn::IfThenElse(up, hn::Mul(hn::Sub(top, z), inverse_dz), infinity));
        const VF boundary_path = hn::Max(to_boundary, zero);
        const MF hits = hn::And(active, free_path >= boundary_path);
        const MF interacts = hn::AndNot(hits, active);
        const VF segment = hn::IfThenElseZero(active, hn::IfThenElse(hits, boundary_path, free_path));
        x = hn::MulAdd(segment, dx, x);
        y = hn::MulAdd(segment, dy, y);
        z = hn::IfThenElse(hits, hn::IfThenElse(down, bottom, top), hn::MulAdd(segment, dz, z));
        // The optical depth a boundary leaves for the next layer (MCML's sleft); an interaction uses it up.
        const VF tau_left = hn::IfThenElse(hits, hn::IfThenElse(scatters, hn::NegMulAdd(boundary_path, mu, tau), tau), zero);

        // An interaction: the layer's phase function (polar angle) and a uniform azimuth (MCML's Spin, Sec. 3.6).
        const VI kind = phases.at(k);
        const MF turns = hn::AndNot(kind_is(kind, PacketPhase::none), interacts);
        if (!hn::AllFalse(df, turns)) {
            const VF u = random.uniform(turns);
            VF g = gs.at(k);
            const MF two_term = hn::And(turns, kind_is(kind, PacketPhase::two_term_hg));
            if (!hn::AllFalse(df, two_term)) {
                // Two-term HG (Baranoski et al. 2005 Eq. 2; two_term_hg.hpp): the first term with its probability, then HG.
                const VF u_term = random.uniform(two_term);
                g = hn::IfThenElse(hn::And(two_term, u_term >= first_weights.at(k)), g2s.at(k), g);
            }
            VF c = HgCos(g, u);
            const MF rayleigh = hn::And(turns, kind_is(kind, PacketPhase::rayleigh));
            if (!hn::AllFalse(df, rayleigh)) c = hn::IfThenElse(rayleigh, RayleighCos(u), c);
            const MF tabulated = hn::And(turns, kind_is(kind, PacketPhase::tabulated));
            if (!hn::AllFalse(df, tabulated)) {
                // The inverse-CDF table's entry floor(u n) (InverseCdfTable::index); other lanes read entry 0.
                const VF size = hn::ConvertTo(df, table_sizes.at(k));
                const VI index = hn::Add(hn::ConvertTo(di, hn::Min(hn::Mul(u, size), hn::Sub(size, one))), table_offsets.at(k));
                c = hn::IfThenElse(tabulated, hn::GatherIndex(df, model.table_cos.data(), hn::IfThenElseZero(ToInt(tabulated), index)), c);
            }
            const VF s = hn::Sqrt(hn::Max(zero, hn::NegMulAdd(c, c, one)));
            VF cos_phi, sin_phi;
            Azimuth(random.uniform(turns), cos_phi, sin_phi);
            VF ox, oy, oz;
            Deflect(dx, dy, dz, c, s, cos_phi, sin_phi, ox, oy, oz);
            dx = hn::IfThenElse(turns, ox, dx);
            dy = hn::IfThenElse(turns, oy, dy);
            dz = hn::IfThenElse(turns, oz, dz);
        }

        // A boundary: the Lambertian reflector below the last layer, else Fresnel (MCML's CrossUpOrNot /
        // CrossDnOrNot, Sec. 3.7, with RFresnel, Eq. 3.31) and Snell.
        const MF at_last = FromInt(k == last);
        const MF at_first = FromInt(k == hn::Zero(di));
        MF bounce = model.reflector ? hn::And(hits, hn::And(down, at_last)) : none;
        // A reflector of reflectance below 1 keeps the photon with probability 1 - reflectance (it leaves the bottom).
        MF kept_below = none;
        if (model.reflector_reflectance < 1.0f && !hn::AllFalse(df, bounce)) {
            kept_below = hn::And(bounce, random.uniform(bounce) >= hn::Set(df, model.reflector_reflectance));
            bounce = hn::AndNot(kept_below, bounce);
        }
        if (!hn::AllFalse(df, bounce)) {
            const VF u_bounce = random.uniform(bounce);
            VF cos_phi, sin_phi;
            Azimuth(random.uniform(bounce), cos_phi, sin_phi);
            const VF sin_bounce = hn::Sqrt(u_bounce);
            dx = hn::IfThenElse(bounce, hn::Mul(sin_bounce, cos_phi), dx);
            dy = hn::IfThenElse(bounce, hn::Mul(sin_bounce, sin_phi), dy);
            dz = hn::IfThenElse(bounce, hn::Neg(hn::Sqrt(hn::Sub(one, u_bounce))), dz);
        }
        const MF fresnel = hn::AndNot(hn::Or(bounce, kept_below), hits);
        // Most steps of a scattering medium end in an interaction: a vector with no lane at an interface skips the
        // Fresnel work (it draws no random number either, so every path is unchanged).
        const auto imask = [&](MF mask) { return ToInt(mask); };
        VF cos_t = zero;
        VF kept = zero;
        MF split = none;
        MF escapes = none;
        VI next_k = k;
        if (!hn::AllFalse(df, fresnel)) {
            const VF eta = hn::IfThenElse(down, eta_down.at(k), eta_up.at(k));
            const VF m = hn::IfThenElse(down, inverse_eta_down.at(k), inverse_eta_up.at(k));
            MF total;
            const VF reflectance = FresnelReflectance(hn::Abs(dz), eta, m, cos_t, total);
            const MF outer = hn::And(fresnel, hn::Or(hn::And(down, at_last), hn::AndNot(down, at_first)));
            // Split outer boundaries: the transmitted part escapes and the reflected part goes on.
            split = model.split ? hn::AndNot(total, outer) : none;
            const MF test = hn::AndNot(hn::Or(total, split), hn::And(fresnel, reflectance > zero));
            MF reflected = hn::And(fresnel, total);
            if (!hn::AllFalse(df, test)) reflected = hn::Or(reflected, hn::And(test, random.uniform(test) < reflectance));
            const MF refracted = hn::AndNot(hn::Or(reflected, split), fresnel);
            escapes = hn::Or(split, hn::And(refracted, outer));
            const MF moves_on = hn::AndNot(outer, refracted);
            kept = hn::IfThenElseZero(split, reflectance);
            dx = hn::IfThenElse(moves_on, hn::Mul(eta, dx), dx);
            dy = hn::IfThenElse(moves_on, hn::Mul(eta, dy), dy);
            dz = hn::IfThenElse(hn::Or(reflected, split), hn::Neg(dz), hn::IfThenElse(moves_on, hn::CopySign(cos_t, dz), dz));
            next_k = hn::IfThenElse(imask(hn::And(moves_on, down)), hn::Add(k, hn::Set(di, 1)), k);
            next_k = hn::IfThenElse(imask(hn::AndNot(down, moves_on)), hn::Sub(k, hn::Set(di, 1)), next_k);
        }

        escapes = hn::Or(escapes, kept_below);
        const VI steps = hn::Add(hn::LoadU(di, reinterpret_cast<const std::int32_t*>(p.steps) + base), hn::IfThenElseZero(imask(active), hn::Set(di, 1)));
        const MF gone = hn::AndNot(split, escapes);
        const MF truncated = hn::AndNot(gone, hn::And(active, FromInt(steps > hn::Set(di, static_cast<int>(model.max_steps) - 1))));
        VI bits = hn::IfThenElseZero(imask(interacts), hn::Set(di, rte_interaction));
        bits = hn::Or(bits, hn::IfThenElseZero(imask(hn::AndNot(down, escapes)), hn::Set(di, rte_left_top)));
        bits = hn::Or(bits, hn::IfThenElseZero(imask(hn::And(down, escapes)), hn::Set(di, rte_left_bottom)));
        bits = hn::Or(bits, hn::IfThenElseZero(imask(truncated), hn::Set(di, rte_truncated)));

        hn::StoreU(x, df, p.x + base);
        hn::StoreU(y, df, p.y + base);
        hn::StoreU(z, df, p.z + base);
        if (model.radius) hn::StoreU(hn::Sqrt(hn::MulAdd(x, x, hn::Mul(y, y))), df, p.r_cm + base);
        hn::StoreU(dx, df, p.dx + base);
        hn::StoreU(dy, df, p.dy + base);
        hn::StoreU(dz, df, p.dz + base);
        hn::StoreU(tau_left, df, p.tau_left + base);
        hn::StoreU(segment, df, p.segment_cm + base);
        hn::StoreU(cos_t, df, p.exit_cos + base);
        hn::StoreU(kept, df, p.kept + base);
        hn::StoreU(k, di, p.segment_layer + base);
        hn::StoreU(next_k, di, p.layer + base);
        hn::StoreU(bits, di, p.event_bits + base);
        hn::StoreU(steps, di, reinterpret_cast<std::int32_t*>(p.steps) + base);
        random.store(rng, base);

        flags |= MaskBits(model.flag_every_segment ? active : FromInt(bits != hn::Zero(di)), base);
    }
    return flags;
}

const char* RteTargetImpl() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace skinspec
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skinspec {

HWY_EXPORT(RteStepImpl);
HWY_EXPORT(RteTargetImpl);

std::uint64_t step_rte_packet(const RtePacketModel& model, RtePacket& packet) { return HWY_DYNAMIC_DISPATCH(RteStepImpl)(model, packet); }

const char* rte_packet_target() { return HWY_DYNAMIC_DISPATCH(RteTargetImpl)(); }

void RtePacketModel::pad() {
    layer_stride = (static_cast<std::size_t>(layers) + widest_vector - 1) / widest_vector * widest_vector;
    for (auto* v : {&phase, &table_offset, &table_size}) v->resize(layer_stride, 0);
    for (auto* v : {&mu_per_cm, &top_cm, &bottom_cm, &g, &g2, &first_term_weight, &eta_down, &eta_up, &inverse_eta_down, &inverse_eta_up}) {
        v->resize(layer_stride, 0.0f);
    }
    if (table_cos.empty()) table_cos.push_back(1.0f);  // the gathers of lanes without a tabulated phase read entry 0
}

void RtePacket::launch(std::size_t lane, std::uint64_t key, float dir_x, float dir_y, float dir_z) {
    x[lane] = y[lane] = z[lane] = 0.0f;
    dx[lane] = dir_x;
    dy[lane] = dir_y;
    dz[lane] = dir_z;
    tau_left[lane] = 0.0f;
    layer[lane] = 0;
    steps[lane] = 0;
    active[lane] = 1;
    seed_lane_stream(rng, lane, key);
}

}  // namespace skinspec
#endif
