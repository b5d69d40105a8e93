#include "forces/cundall_four_wide.hpp"

#include "contact/contact_law.hpp"
#include "simd/lanes.hpp"
#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

#ifdef DEM_SIMD_LOOPS
namespace {

using lanes::Lanes4;
using lanes::Mask4;
using lanes::Triple;
using V3 = Triple<Lanes4>;
using Model = ContactModel<CundallNormal>;  // the model of every scene without bonds

DEM_AVX2_INLINE V3 load3(const double* x, const double* y, const double* z) { return {simd::load(x), simd::load(y), simd::load(z)}; }
DEM_AVX2_INLINE V3 load_four(const Vec3* base, const int (&slot)[4]) { return simd::load_four(base, slot[0], slot[1], slot[2], slot[3]); }
// One field of four lanes' pair parameters.
DEM_AVX2_INLINE Lanes4 param(const PairParams* const (&pp)[4], double PairParams::*field) {
  return lanes::lanes4(pp[0]->*field, pp[1]->*field, pp[2]->*field, pp[3]->*field);
}
// What the law reads of four lanes' pair parameters, by PairParams' names (contact/contact_law.hpp).
struct LawParams {
  Lanes4 kn, kt, mu, damping_n, damping_t, cohesion;
  Mask4 no_viscous_attraction;
  DEM_AVX2_INLINE explicit LawParams(const PairParams* const (&pp)[4])
      : kn(param(pp, &PairParams::kn)), kt(param(pp, &PairParams::kt)), mu(param(pp, &PairParams::mu)),
        damping_n(param(pp, &PairParams::damping_n)), damping_t(param(pp, &PairParams::damping_t)),
        cohesion(param(pp, &PairParams::cohesion)),
        no_viscous_attraction(lanes::mask4(pp[0]->no_viscous_attraction, pp[1]->no_viscous_attraction,
                                           pp[2]->no_viscous_attraction, pp[3]->no_viscous_attraction)) {}
};
// What the first `count` of four contacts (k) leave: keep_pair_result's and the dashpot's mark,
// lane by lane; each vector written with one masked store of its three doubles (nothing written
// past it), the marks in the same loop (one loop's overhead, not two).
DEM_AVX2_INLINE void keep_results(const PairLawArrays& a, const int (&k)[4], int count, const V3& spring, const V3& n,
                                  const V3& on_i, const V3& torque_per_radius, const Lanes4& mark) {
  Lanes4 s[4], f[4], t[4], nl[4];
  simd::per_lane(spring, s), simd::per_lane(on_i, f), simd::per_lane(torque_per_radius, t);
  if (a.keep_normals) simd::per_lane(n, nl);
  alignas(32) double marks[4];
  simd::store_aligned(marks, mark);
  for (int l = 0; l < count; ++l) {
    a.dashpot[k[l]] = marks[l];
    simd::store_xyz(a.spring[k[l]].data(), s[l]);
    simd::store_xyz(a.sum[k[l]].force.data(), f[l]);
    simd::store_xyz(a.sum[k[l]].torque_per_radius.data(), t[l]);
    if (a.keep_normals) simd::store_xyz(a.normal[k[l]].data(), nl[l]);
  }
}

// The kinematics of force_loop.cpp's plain pass 2 and the law of contact/contact_law.hpp with
// CundallNormal, four contacts at a time (L = Lanes4): the same operations in the same order.
// The law and the lane operations are always inlined here, where AVX2 is allowed.
template <bool Fixed, bool Bonds>
DEM_AVX2 double cundall_law_avx2(const PairLawArrays a, const MaterialTable& materials, double dt, const FoundInChunk found, int m) {
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
    c.w_arm = rj * load_four(a.w, jl) + ri * load_four(a.w, il);
    const Lanes4 mi = simd::gather(a.mass, i), mj = simd::gather(a.mass, j);
    c.m_eff = (mi * mj) / (mi + mj);
    c.r_eff = (ri * rj) / (ri + rj);  // eq. H3 (the Cundall law reads none: compiled away)
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
    V3 spring = Model::TangentialModel::in_tangent_plane(load_four(a.spring, kl), c.n);
    Lanes4 mark = simd::gather(a.dashpot, k);
    const LaneForce<Lanes4> f = Model::evaluate_in_plane(law, c, dt, spring, bonded, mark);  // clears bonded where a bond breaks
    const V3 torque_per_radius = cross(c.n, f.tangential);

    const int count = std::min(4, m - e);
    keep_results(a, kl, count, spring, c.n, f.on_i, torque_per_radius, mark);
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

}  // namespace
#endif

template <bool Fixed>
double cundall_pair_law_simd(const PairLawArrays a, const MaterialTable& materials, double dt, const FoundInChunk found, int m,
                             bool any_bonds) {
#ifdef DEM_SIMD_LOOPS
  return any_bonds ? cundall_law_avx2<Fixed, true>(a, materials, dt, found, m)
                   : cundall_law_avx2<Fixed, false>(a, materials, dt, found, m);
#else
  (void)a, (void)materials, (void)dt, (void)found, (void)m, (void)any_bonds;
  return 0;  // never called: simd_loops_on() is false
#endif
}

template double cundall_pair_law_simd<false>(PairLawArrays, const MaterialTable&, double, FoundInChunk, int, bool);
template double cundall_pair_law_simd<true>(PairLawArrays, const MaterialTable&, double, FoundInChunk, int, bool);

}  // namespace dem
