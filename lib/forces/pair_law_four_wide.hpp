#pragma once
// Pass 2 of the force loop: the law on the contacts pass 1 found (find_contacts.hpp), and what
// each contact leaves behind: its sum (force on i and n x f_t), which each of its particles adds in
// the order of its contacts' keys (forces/force_loop.hpp), its normal where kept, and its rolling
// couple where the model has one.
//
// The plain version is three loops in force_loop.cpp (any model); a model whose sub-models are all
// written over lanes (ContactModel::four_wide: every normal law, with either tangential law and
// any rolling law; contact/contact_law.hpp, simd/lanes.hpp) also runs four contacts at a time with
// AVX2 here: the same source, so the same bits. A template here, instantiated by force_loop.cpp
// for the models it compiles (so that the two lists cannot disagree).
#include <algorithm>
#include <cstdint>

#include "contact/contact_law.hpp"
#include "contact/contact_list.hpp"
#include "core/types.hpp"
#include "forces/find_contacts.hpp"
#include "simd/lanes.hpp"
#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"

namespace dem {

// What pass 2 reads and writes, as bare arrays (see CandidateArrays).
struct PairLawArrays {
  const Vec3* v;
  const Vec3* w;
  const double* radius;
  const double* mass;
  const int* material;
  const std::uint8_t* fixed;
  const int* slot_i;
  const int* slot_j;
  std::uint8_t* bonded;
  Vec3* spring;
  Vec3* rolling;
  double* dashpot;
  Vec3* normal;
  ContactSum* sum;
  bool keep_normals;  // the normal of every contact (SimParams::keep_pair_results)
  ContactWork* work;  // per candidate, while the energy log is on (ForceLoopInput::work), else null

  PairLawArrays(const Particles& p, ContactList& pc, bool keep, ContactWork* work_or_null)
      : v(p.v.data()), w(p.w.data()), radius(p.radius.data()), mass(p.mass.data()), material(p.material.data()),
        fixed(p.fixed.data()), slot_i(pc.slot_i.data()), slot_j(pc.slot_j.data()), bonded(pc.bonded.data()),
        spring(pc.spring.data()), rolling(pc.rolling.data()), dashpot(pc.dashpot.data()), normal(pc.normal.data()), sum(pc.sum.data()),
        keep_normals(keep), work(work_or_null) {}
};

// What the law of contact k leaves: its sum (the force on i and n x f_t), its normal where
// a.keep_normals, its ContactWork where a.work.
inline void keep_pair_result(const PairLawArrays& a, long k, const Vec3& n, const ContactForce& f) {
  if (a.keep_normals) a.normal[k] = n;
  a.sum[k] = {f.on_i, n.cross(f.tangential)};
  if (a.work) a.work[k] = {(f.normal - f.elastic) * n, f.tangential};
}

// overlap / radius where it may exceed `worst`, else 0: the division (one per contact) is done only
// near a new largest value. The margin keeps the result exact: whenever the quotient exceeds
// `worst`, the product test passes despite rounding, so the maximum is the same as dividing always.
inline double relative_overlap_if_larger(double overlap, double radius, double worst) {
  return overlap >= worst * radius * (1 - 1e-9) ? overlap / radius : 0.0;
}

#ifdef DEM_SIMD_LOOPS
namespace four_wide {

using lanes::Lanes4;
using lanes::Mask4;
using V3 = lanes::Triple<Lanes4>;

DEM_AVX2_INLINE V3 load3(const double* x, const double* y, const double* z) { return {simd::load(x), simd::load(y), simd::load(z)}; }
DEM_AVX2_INLINE V3 load_four(const Vec3* base, const int (&slot)[4]) { return simd::load_four(base, slot[0], slot[1], slot[2], slot[3]); }
// One field of four lanes' pair parameters.
DEM_AVX2_INLINE Lanes4 param(const PairParams* const (&pp)[4], double PairParams::*field) {
  return lanes::lanes4(pp[0]->*field, pp[1]->*field, pp[2]->*field, pp[3]->*field);
}
// One flag of four lanes' pair parameters.
DEM_AVX2_INLINE Mask4 flag(const PairParams* const (&pp)[4], bool PairParams::*field) {
  return lanes::mask4(pp[0]->*field, pp[1]->*field, pp[2]->*field, pp[3]->*field);
}
// What the laws read of four lanes' pair parameters, by PairParams' names (contact/contact_law.hpp);
// a model's loop reads only its own (the rest are never loaded).
struct LawParams {
  Lanes4 kn, kt, mu, damping_n, damping_t, cohesion;
  Lanes4 tensile_strength, mendes_D, mendes_A, break_separation;
  Lanes4 hertz_modulus, hertz_damping, mindlin_modulus, mindlin_damping, rolling_friction;
  Mask4 no_viscous_attraction, mendes_tension;
  DEM_AVX2_INLINE explicit LawParams(const PairParams* const (&pp)[4])
      : kn(param(pp, &PairParams::kn)), kt(param(pp, &PairParams::kt)), mu(param(pp, &PairParams::mu)),
        damping_n(param(pp, &PairParams::damping_n)), damping_t(param(pp, &PairParams::damping_t)),
        cohesion(param(pp, &PairParams::cohesion)), tensile_strength(param(pp, &PairParams::tensile_strength)),
        mendes_D(param(pp, &PairParams::mendes_D)), mendes_A(param(pp, &PairParams::mendes_A)),
        break_separation(param(pp, &PairParams::break_separation)), hertz_modulus(param(pp, &PairParams::hertz_modulus)),
        hertz_damping(param(pp, &PairParams::hertz_damping)), mindlin_modulus(param(pp, &PairParams::mindlin_modulus)),
        mindlin_damping(param(pp, &PairParams::mindlin_damping)), rolling_friction(param(pp, &PairParams::rolling_friction)),
        no_viscous_attraction(flag(pp, &PairParams::no_viscous_attraction)), mendes_tension(flag(pp, &PairParams::mendes_tension)) {}
};
// What the first `count` of four contacts (k) leave: keep_pair_result's, the dashpot's mark and,
// with Couples, the rolling couple, lane by lane; each vector written with one masked store of its
// three doubles (nothing written past it), all in one loop (one loop's overhead, not several).
template <bool Couples>
DEM_AVX2_INLINE void keep_results(const PairLawArrays& a, const int (&k)[4], int count, const V3& spring, const V3& n,
                                  const LaneForce<Lanes4>& force, const Lanes4& mark) {
  Lanes4 s[4], f[4], t[4], nl[4], m[4], wd[4], wt[4];
  simd::per_lane(spring, s), simd::per_lane(force.on_i, f), simd::per_lane(cross(n, force.tangential), t);
  if (a.keep_normals) simd::per_lane(n, nl);
  if constexpr (Couples) simd::per_lane(force.couple, m);
  if (a.work) simd::per_lane((force.normal - force.elastic) * n, wd), simd::per_lane(force.tangential, wt);
  alignas(32) double marks[4];
  simd::store_aligned(marks, mark);
  for (int l = 0; l < count; ++l) {
    a.dashpot[k[l]] = marks[l];
    simd::store_xyz(a.spring[k[l]].data(), s[l]);
    simd::store_xyz(a.sum[k[l]].force.data(), f[l]);
    simd::store_xyz(a.sum[k[l]].torque_per_radius.data(), t[l]);
    if (a.keep_normals) simd::store_xyz(a.normal[k[l]].data(), nl[l]);
    if constexpr (Couples) simd::store_xyz(a.rolling[k[l]].data(), m[l]);  // summed with the loads (force_loop.cpp)
    if (a.work) simd::store_xyz(a.work[k[l]].damping.data(), wd[l]), simd::store_xyz(a.work[k[l]].tangential.data(), wt[l]);
  }
}

// The kinematics of force_loop.cpp's plain pass 2 and the law of contact/contact_law.hpp with
// Model, four contacts at a time (L = Lanes4): the same operations in the same order. The law and
// the lane operations are always inlined here, where AVX2 is allowed.
template <class Model, bool Fixed, bool Bonds>
DEM_AVX2 double pair_law(const PairLawArrays a, const MaterialTable& materials, double dt, const FoundInChunk found, int m) {
  using Tangential = typename Model::TangentialModel;
  constexpr bool kRollingHistory = Model::RollingModel::has_history;
  if (m == 0) return 0;
  // Lanes past the last contact repeat it: computed, never kept.
  for (int q = m; q < m + 3; ++q)
    found.contact[q] = found.contact[m - 1], found.dx[q] = found.dx[m - 1], found.dy[q] = found.dy[m - 1], found.dz[q] = found.dz[m - 1];
  // One material: the same parameters for every contact, set once.
  const PairParams* only[4] = {&materials.pair(0, 0), &materials.pair(0, 0), &materials.pair(0, 0), &materials.pair(0, 0)};
  LawParams law(only);
  // The materials of i and j in each lane whose pair `law` holds: reread only where they change
  // (almost never: a scene of few materials has runs of contacts of one pair).
  const bool many_materials = materials.size() > 1;
  simd::Ints4 law_i{}, law_j{};
  double worst = 0;
  // Fetched into the cache ahead: the velocities of both particles of the contacts kAhead on (pass
  // 1 read only their positions), where a random packing's particles no longer fit the core's
  // cache (bench/results).
  constexpr int kAhead = 8;
  for (int e = 0; e < m; e += 4) {
    if (e + kAhead + 4 <= m)
      for (int l = 0; l < 4; ++l) {
        const long ahead = found.contact[e + kAhead + l];
        const int i_ahead = a.slot_i[ahead], j_ahead = a.slot_j[ahead];
        simd::prefetch(a.v + i_ahead);
        simd::prefetch(a.w + i_ahead);
        simd::prefetch(a.v + j_ahead);
        simd::prefetch(a.w + j_ahead);
      }
    const simd::Ints4 k = simd::load(found.contact + e);
    const simd::Ints4 i = simd::gather(a.slot_i, k), j = simd::gather(a.slot_j, k);
    alignas(16) int kl[4], il[4], jl[4];
    simd::store_aligned(kl, k), simd::store_aligned(il, i), simd::store_aligned(jl, j);

    // Kinematics (eq. 2.11-2.12).
    LaneKinematics<Lanes4> c;
    const V3 d = load3(found.dx + e, found.dy + e, found.dz + e);
    const Lanes4 dist = lanes::root(dot(d, d));
    c.n = d * (Lanes4(1.0) / dist);
    const Lanes4 ri = simd::gather(a.radius, i), rj = simd::gather(a.radius, j);
    c.overlap = (ri + rj) - dist;
    c.v_rel = load_four(a.v, jl) - load_four(a.v, il);
    const V3 wi = load_four(a.w, il), wj = load_four(a.w, jl);
    c.w_arm = rj * wj + ri * wi;
    if constexpr (Model::has_rolling) c.w_rel = wi - wj;
    const Lanes4 mi = simd::gather(a.mass, i), mj = simd::gather(a.mass, j);
    c.m_eff = (mi * mj) / (mi + mj);
    c.r_eff = (ri * rj) / (ri + rj);  // eq. H3 (a law that reads none: compiled away)
    if constexpr (Fixed) {  // effective_mass: against a fixed particle, the other's mass
      const std::uint8_t* fixed = a.fixed;
      c.m_eff = lanes::select(lanes::mask4(fixed[il[0]], fixed[il[1]], fixed[il[2]], fixed[il[3]]), mj,
                              lanes::select(lanes::mask4(fixed[jl[0]], fixed[jl[1]], fixed[jl[2]], fixed[jl[3]]), mi, c.m_eff));
    }
    if (many_materials) {
      const simd::Ints4 mat_i = simd::gather(a.material, i), mat_j = simd::gather(a.material, j);
      if (!(simd::same(mat_i, law_i) && simd::same(mat_j, law_j))) {
        alignas(16) int ml_i[4], ml_j[4];
        simd::store_aligned(ml_i, mat_i), simd::store_aligned(ml_j, mat_j);
        const PairParams* pp[4];
        for (int l = 0; l < 4; ++l) pp[l] = &materials.pair(ml_i[l], ml_j[l]);
        law = LawParams(pp), law_i = mat_i, law_j = mat_j;
      }
    }
    // Without bonds (Bonds false: no contact of the scene holds one) every lane's flag is false.
    Mask4 bonded = Bonds ? lanes::mask4(a.bonded[kl[0]], a.bonded[kl[1]], a.bonded[kl[2]], a.bonded[kl[3]]) : Mask4{};
    V3 spring = Tangential::in_tangent_plane(load_four(a.spring, kl), c.n);
    V3 rolling{};
    if constexpr (kRollingHistory) rolling = Tangential::in_tangent_plane(load_four(a.rolling, kl), c.n);
    Lanes4 mark = simd::gather(a.dashpot, k);
    const LaneForce<Lanes4> f = Model::evaluate_in_plane(law, c, dt, spring, bonded, mark, rolling);  // clears bonded where a bond breaks

    const int count = std::min(4, m - e);
    keep_results<Model::has_rolling>(a, kl, count, spring, c.n, f, mark);
    if constexpr (Bonds)
      for (int l = 0; l < count; ++l) a.bonded[kl[l]] = bonded.v[l] != 0;
    // relative_overlap_if_larger's test on every lane with the group's first `worst`: where no lane
    // passes, none can with the larger values the loop below may reach (almost every group).
    const Lanes4 bar = (simd::broadcast(worst) * simd::min(ri, rj)) * simd::broadcast(1 - 1e-9);
    if (simd::bits(simd::greater_or_equal(c.overlap, bar)) != 0) {
      alignas(32) double u[4];
      simd::store_aligned(u, c.overlap);
      for (int l = 0; l < count; ++l)
        worst = std::max(worst, relative_overlap_if_larger(u[l], std::min(a.radius[il[l]], a.radius[jl[l]]), worst));
    }
  }
  return worst;
}

}  // namespace four_wide
#endif

// The law of Model (ContactModel::four_wide) four contacts at a time on the m contacts `found`
// (whose arrays hold kFoundPadding entries more), as the plain loops would; returns the largest
// overlap relative to the smaller radius. Only where simd_loops_on(). (Arrays by value, as
// find_contacts.) any_bonds: some contact may be bonded (else every bonded flag is taken as 0,
// unread).
template <class Model, bool Fixed>
double pair_law_four_wide(const PairLawArrays a, const MaterialTable& materials, double dt, const FoundInChunk found, int m,
                          bool any_bonds) {
  static_assert(Model::four_wide, "a model with a sub-model not written over lanes runs the plain loops");
#ifdef DEM_SIMD_LOOPS
  return any_bonds ? four_wide::pair_law<Model, Fixed, true>(a, materials, dt, found, m)
                   : four_wide::pair_law<Model, Fixed, false>(a, materials, dt, found, m);
#else
  (void)a, (void)materials, (void)dt, (void)found, (void)m, (void)any_bonds;
  return 0;  // never called: simd_loops_on() is false
#endif
}

}  // namespace dem
