#pragma once
// Pass 2 of the force loop: the law on the contacts pass 1 found (find_contacts.hpp), and what
// each contact leaves behind: its sum (force on i and n x f_t), which each of its particles adds in
// the order of its contacts' keys (forces/force_loop.hpp), its normal where kept, and its rolling
// couple where the model has one.
//
// The plain version is three loops in block_forces.hpp (any model); a model whose sub-models are all
// written over lanes (ContactModel::four_wide: every normal law, with either tangential law and
// any rolling law; contact/contact_law.hpp, simd/lanes.hpp) also runs eight contacts at a time,
// as two sets of four lanes, with AVX2 here: the same source, so the same bits. A template here,
// instantiated by block_forces.hpp for the models the force_loop_<law>.cpp units compile (so that the two lists cannot disagree).
#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

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
  std::vector<int>* broken = nullptr;  // the thread's: each candidate whose bond breaks is appended

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

// The bond flag of contact k as its law leaves it; where the bond broke, k joins a.broken.
inline void keep_bond(const PairLawArrays& a, long k, bool now) {
  if (a.bonded[k] && !now) a.broken->push_back(static_cast<int>(k));
  a.bonded[k] = now;
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
// What the laws read of the pair parameters of four lanes (L = Lanes4) or eight (Two<Lanes4>), by
// PairParams' names (contact/contact_law.hpp); a model's loop reads only its own (the rest are
// never loaded).
template <class L, class M>
struct LawParamsOf {
  L kn, kt, mu, damping_n, damping_t, cohesion;
  L tensile_strength, mendes_D, mendes_A, break_separation;
  L hertz_modulus, hertz_damping, mindlin_modulus, mindlin_damping, rolling_friction;
  M no_viscous_attraction, mendes_tension;
  // f(field, the same field of each of `from`) for every field: the one list of them.
  template <class F, class... From>
  DEM_AVX2_INLINE void each(F f, const From&... from) {
    f(kn, from.kn...), f(kt, from.kt...), f(mu, from.mu...), f(damping_n, from.damping_n...), f(damping_t, from.damping_t...);
    f(cohesion, from.cohesion...), f(tensile_strength, from.tensile_strength...), f(mendes_D, from.mendes_D...);
    f(mendes_A, from.mendes_A...), f(break_separation, from.break_separation...), f(hertz_modulus, from.hertz_modulus...);
    f(hertz_damping, from.hertz_damping...), f(mindlin_modulus, from.mindlin_modulus...), f(mindlin_damping, from.mindlin_damping...);
    f(rolling_friction, from.rolling_friction...), f(no_viscous_attraction, from.no_viscous_attraction...);
    f(mendes_tension, from.mendes_tension...);
  }
};
using LawParams = LawParamsOf<Lanes4, Mask4>;
using LawParamsTwo = LawParamsOf<lanes::Two<Lanes4>, lanes::Two<Mask4>>;
// Four lanes' parameters, from each lane's pair.
DEM_AVX2_INLINE LawParams law_params(const PairParams* const (&pp)[4]) {
  LawParams p;
  p.each([](auto& lanes, const auto& a, const auto& b, const auto& c, const auto& d) DEM_AVX2_LAMBDA {
    if constexpr (std::is_same_v<std::decay_t<decltype(a)>, bool>) lanes = lanes::mask4(a, b, c, d);
    else lanes = lanes::lanes4(a, b, c, d);
  }, *pp[0], *pp[1], *pp[2], *pp[3]);
  return p;
}
// Eight lanes' parameters: four and four.
DEM_AVX2_INLINE LawParamsTwo law_params(const LawParams& lo, const LawParams& hi) {
  LawParamsTwo p;
  p.each([](auto& lanes, const auto& a, const auto& b) DEM_AVX2_LAMBDA { lanes = {a, b}; }, lo, hi);
  return p;
}
// What the first `count` of four contacts (k) leave: keep_pair_result's, the dashpot's mark, with
// `bonds` the bond flags and, with Couples, the rolling couple, lane by lane; each vector written
// with one masked store of its three doubles (nothing written past it), all in one loop (one
// loop's overhead, not several).
template <bool Couples>
DEM_AVX2_INLINE void keep_results(const PairLawArrays& a, const int (&k)[4], int count, const V3& spring, const V3& n,
                                  const LaneForce<Lanes4>& force, const Lanes4& mark, const Mask4& bonded, bool bonds) {
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
    if constexpr (Couples) simd::store_xyz(a.rolling[k[l]].data(), m[l]);  // summed with the loads (block_forces.hpp)
    if (a.work) simd::store_xyz(a.work[k[l]].damping.data(), wd[l]), simd::store_xyz(a.work[k[l]].tangential.data(), wt[l]);
    if (bonds) a.bonded[k[l]] = bonded.v[l] != 0;
  }
}
// The lanes among the first `count` whose bond the law broke (bonded `before`, not `now`) join
// a.broken (rare: apart from the loop above, whose stores the list's could otherwise alias).
DEM_AVX2_INLINE void list_broken(const PairLawArrays& a, const int (&k)[4], int count, const Mask4& before, const Mask4& now) {
  if (const int broke = simd::bits(before) & ~simd::bits(now) & ((1 << count) - 1)) [[unlikely]]
    for (int l = 0; l < 4; ++l)
      if (broke >> l & 1) a.broken->push_back(k[l]);
}

// Four contacts as the law takes them: their slots, kinematics and histories.
struct FourContacts {
  int k[4], i[4], j[4];
  LaneKinematics<Lanes4> c;
  V3 spring, rolling;
  Lanes4 mark;
  Mask4 bonded;
  Lanes4 ri, rj;
};

// The histories of the four contacts g.k as the law takes them: bond flags, springs turned
// into the tangent plane of g.c.n, the rolling law's history, the dashpot's marks. Without bonds
// (Bonds false: no contact of the scene holds one) every lane's flag is false.
template <class Model, bool Bonds>
DEM_AVX2_INLINE void take_histories(const PairLawArrays& a, FourContacts& g) {
  using Tangential = typename Model::TangentialModel;
  g.bonded = Bonds ? lanes::mask4(a.bonded[g.k[0]], a.bonded[g.k[1]], a.bonded[g.k[2]], a.bonded[g.k[3]]) : Mask4{};
  g.spring = Tangential::in_tangent_plane(load_four(a.spring, g.k), g.c.n);
  g.rolling = V3{};
  if constexpr (Model::RollingModel::has_history) g.rolling = Tangential::in_tangent_plane(load_four(a.rolling, g.k), g.c.n);
  g.mark = simd::gather(a.dashpot, g.k);
}

// The law of Model on m contacts, eight at a time (two fours interleaved, L = Two<Lanes4>; the
// last four or fewer with L = Lanes4), lanes past the m-th repeating the last contact (computed,
// never kept). take(e, g, half) reads the four contacts from e on into g and, where their
// parameters differ from law[half]'s, sets law[half] and returns true; keep(g, count, f, spring,
// mark, bonded) stores what the first `count` of them leave. Shared by the pair contacts (below)
// and the wall contacts (wall_law.hpp).
template <class Model, class Take, class Keep>
DEM_AVX2_INLINE void eight_at_a_time(int m, double dt, LawParams (&law)[2], Take&& take, Keep&& keep) {
  using T = lanes::Two<Lanes4>;
  using lanes::high;
  using lanes::low;
  LawParamsTwo law_eight = law_params(law[0], law[1]);  // rebuilt only where either four's changes
  for (int e = 0; e < m;) {
    if (e + 4 < m) {  // eight: two fours, the second with at least one contact
      alignas(32) FourContacts g, h;
      const bool changed = take(e, g, 0);
      if (take(e + 4, h, 1) || changed) law_eight = law_params(law[0], law[1]);
      LaneKinematics<T> c;
      c.n = lanes::two(g.c.n, h.c.n), c.overlap = T(g.c.overlap, h.c.overlap), c.v_rel = lanes::two(g.c.v_rel, h.c.v_rel);
      c.w_arm = lanes::two(g.c.w_arm, h.c.w_arm), c.m_eff = T(g.c.m_eff, h.c.m_eff), c.r_eff = T(g.c.r_eff, h.c.r_eff);
      if constexpr (Model::has_rolling) c.w_rel = lanes::two(g.c.w_rel, h.c.w_rel);
      lanes::Triple<T> spring = lanes::two(g.spring, h.spring), rolling = lanes::two(g.rolling, h.rolling);
      lanes::Two<Mask4> bonded{g.bonded, h.bonded};
      T mark(g.mark, h.mark);
      const LaneForce<T> f = Model::evaluate_in_plane(law_eight, c, dt, spring, bonded, mark, rolling);
      const LaneForce<Lanes4> f_lo{low(f.on_i), low(f.tangential), low(f.couple), f.normal.lo, f.elastic.lo};
      const LaneForce<Lanes4> f_hi{high(f.on_i), high(f.tangential), high(f.couple), f.normal.hi, f.elastic.hi};
      keep(g, 4, f_lo, low(spring), mark.lo, bonded.lo);
      keep(h, std::min(4, m - e - 4), f_hi, high(spring), mark.hi, bonded.hi);
      e += 8;
    } else {
      alignas(32) FourContacts g;
      take(e, g, 0);
      Mask4 bonded = g.bonded;
      V3 spring = g.spring, rolling = g.rolling;
      Lanes4 mark = g.mark;
      const LaneForce<Lanes4> f = Model::evaluate_in_plane(law[0], g.c, dt, spring, bonded, mark, rolling);
      keep(g, std::min(4, m - e), f, spring, mark, bonded);
      e += 4;
    }
  }
}

// The kinematics of block_forces.hpp's plain pass 2 and the law of contact/contact_law.hpp with
// Model, eight contacts at a time (eight_at_a_time): the same operations in the same order. The
// law and the lane operations are always inlined here, where AVX2 is allowed.
template <class Model, bool Fixed, bool Bonds>
DEM_AVX2 double pair_law(const PairLawArrays a, const MaterialTable& materials, double dt, const FoundInChunk found, int m) {
  if (m == 0) return 0;
  // Lanes past the last contact repeat it: computed, never kept.
  for (int q = m; q < m + 3; ++q)
    found.contact[q] = found.contact[m - 1], found.dx[q] = found.dx[m - 1], found.dy[q] = found.dy[m - 1], found.dz[q] = found.dz[m - 1];
  // One material: the same parameters for every contact, set once.
  const PairParams* only[4] = {&materials.pair(0, 0), &materials.pair(0, 0), &materials.pair(0, 0), &materials.pair(0, 0)};
  LawParams law[2] = {law_params(only), law_params(only)};
  // The materials of i and j in each lane whose pair law[half] holds: reread only where they change
  // (almost never: a scene of few materials has runs of contacts of one pair).
  const bool many_materials = materials.size() > 1;
  simd::Ints4 law_i[2] = {}, law_j[2] = {};
  double worst = 0;
  // Fetched into the cache ahead: the velocities of both particles of the contacts kAhead on (pass
  // 1 read only their positions), where a random packing's particles no longer fit the core's
  // cache (bench/results).
  constexpr int kAhead = 8;
  const auto take = [&](int e, FourContacts& g, int half) DEM_AVX2_LAMBDA {
    bool changed = false;
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
    simd::store_aligned(g.k, k), simd::store_aligned(g.i, i), simd::store_aligned(g.j, j);
    const Lanes4 ri = simd::gather(a.radius, g.i), rj = simd::gather(a.radius, g.j);
    g.ri = ri, g.rj = rj;
    pair_geometry(load3(found.dx + e, found.dy + e, found.dz + e), ri, rj, g.c);
    pair_motion<Model::has_rolling>(ri, rj, load_four(a.v, g.i), load_four(a.v, g.j), load_four(a.w, g.i), load_four(a.w, g.j), g.c);
    Mask4 held_i{}, held_j{};
    if constexpr (Fixed) {
      const std::uint8_t* fixed = a.fixed;
      held_i = lanes::mask4(fixed[g.i[0]], fixed[g.i[1]], fixed[g.i[2]], fixed[g.i[3]]);
      held_j = lanes::mask4(fixed[g.j[0]], fixed[g.j[1]], fixed[g.j[2]], fixed[g.j[3]]);
    }
    pair_inertia<Fixed>(ri, rj, simd::gather(a.mass, g.i), simd::gather(a.mass, g.j), held_i, held_j, g.c);
    if (many_materials) {
      const simd::Ints4 mat_i = simd::gather(a.material, g.i), mat_j = simd::gather(a.material, g.j);
      if (!(simd::same(mat_i, law_i[half]) && simd::same(mat_j, law_j[half]))) {
        alignas(16) int ml_i[4], ml_j[4];
        simd::store_aligned(ml_i, mat_i), simd::store_aligned(ml_j, mat_j);
        const PairParams* pp[4];
        for (int l = 0; l < 4; ++l) pp[l] = &materials.pair(ml_i[l], ml_j[l]);
        law[half] = law_params(pp), law_i[half] = mat_i, law_j[half] = mat_j, changed = true;
      }
    }
    take_histories<Model, Bonds>(a, g);
    return changed;
  };
  // What the first `count` of them leave.
  const auto keep = [&](const FourContacts& g, int count, const LaneForce<Lanes4>& f, const V3& spring, const Lanes4& mark,
                        const Mask4& bonded) DEM_AVX2_LAMBDA {
    if constexpr (Bonds) list_broken(a, g.k, count, g.bonded, bonded);
    keep_results<Model::has_rolling>(a, g.k, count, spring, g.c.n, f, mark, bonded, Bonds);
    // relative_overlap_if_larger's test on every lane with the four's first `worst`: where no lane
    // passes, none can with the larger values the loop below may reach (almost every four).
    const Lanes4 bar = (simd::broadcast(worst) * simd::min(g.ri, g.rj)) * simd::broadcast(1 - 1e-9);
    if (simd::bits(simd::greater_or_equal(g.c.overlap, bar)) != 0) {
      alignas(32) double u[4];
      simd::store_aligned(u, g.c.overlap);
      for (int l = 0; l < count; ++l)
        worst = std::max(worst, relative_overlap_if_larger(u[l], std::min(a.radius[g.i[l]], a.radius[g.j[l]]), worst));
    }
  };
  eight_at_a_time<Model>(m, dt, law, take, keep);
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
