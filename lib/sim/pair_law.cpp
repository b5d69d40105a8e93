#include "sim/pair_law.hpp"

#include "simd/simd.hpp"

namespace dem {

#ifdef DEM_SIMD_LOOPS
namespace {

using simd::gather;
// Four lanes of doubles; GCC's vector arithmetic (+ - * /) works on them lane by lane.
using V = __m256d;
struct V3 {
  V x, y, z;
};

#define AVX2 [[gnu::target("avx2")]] inline
AVX2 V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
AVX2 V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
AVX2 V3 operator*(V s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
AVX2 V3 operator*(const V3& a, V s) { return {a.x * s, a.y * s, a.z * s}; }
// Eigen's order for 3-vectors: (a0 b0 + a1 b1) + a2 b2, and the cross product's usual terms.
AVX2 V dot(const V3& a, const V3& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
AVX2 V3 cross(const V3& a, const V3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
AVX2 V root(V a) { return _mm256_sqrt_pd(a); }
AVX2 V less(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
AVX2 V less_or_equal(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
AVX2 V both(V a, V b) { return _mm256_and_pd(a, b); }
AVX2 V but_not(V a, V b) { return _mm256_andnot_pd(b, a); }  // a and not b
// where ? a : b, lane by lane (where: all bits set or none).
AVX2 V select(V where, V a, V b) { return _mm256_blendv_pd(b, a, where); }
// where ? a : +0 and where ? +0 : a: one instruction each (a blend is three on recent Intel cores).
AVX2 V only_where(V where, V a) { return _mm256_and_pd(where, a); }
AVX2 V zero_where(V where, V a) { return _mm256_andnot_pd(where, a); }
AVX2 V3 select(V where, const V3& a, const V3& b) { return {select(where, a.x, b.x), select(where, a.y, b.y), select(where, a.z, b.z)}; }
AVX2 V3 only_where(V where, const V3& a) { return {only_where(where, a.x), only_where(where, a.y), only_where(where, a.z)}; }
AVX2 V3 load_four(const Vec3* base, const int (&slot)[4]) {
  V3 out;
  simd::load_four(base, slot[0], slot[1], slot[2], slot[3], out.x, out.y, out.z);
  return out;
}
AVX2 V3 load3(const double* x, const double* y, const double* z) { return {_mm256_loadu_pd(x), _mm256_loadu_pd(y), _mm256_loadu_pd(z)}; }
// A lane mask from four flags.
AVX2 V flags(bool a, bool b, bool c, bool d) { return _mm256_castsi256_pd(_mm256_setr_epi64x(-long{a}, -long{b}, -long{c}, -long{d})); }
// One field of four lanes' pair parameters.
AVX2 V param(const PairParams* const (&pp)[4], double PairParams::*field) {
  return _mm256_setr_pd(pp[0]->*field, pp[1]->*field, pp[2]->*field, pp[3]->*field);
}
// What the Cundall law reads of four lanes' pair parameters.
struct LawParams {
  V kn, kt, mu, damping_n, damping_t, cohesion, no_attraction;
  AVX2 explicit LawParams(const PairParams* const (&pp)[4])
      : kn(param(pp, &PairParams::kn)), kt(param(pp, &PairParams::kt)), mu(param(pp, &PairParams::mu)),
        damping_n(param(pp, &PairParams::damping_n)), damping_t(param(pp, &PairParams::damping_t)),
        cohesion(param(pp, &PairParams::cohesion)),
        no_attraction(flags(pp[0]->no_viscous_attraction, pp[1]->no_viscous_attraction, pp[2]->no_viscous_attraction,
                            pp[3]->no_viscous_attraction)) {}
};
struct Lanes {
  alignas(32) double l[4];
};
AVX2 Lanes lanes(V a) {
  Lanes out;
  _mm256_store_pd(out.l, a);
  return out;
}
// Four lanes' vectors, one register each: [x y z 0] (a 4 x 4 transpose with a zero row).
AVX2 void per_lane(const V3& a, V (&out)[4]) {
  const V zero = _mm256_setzero_pd();
  const V xy_02 = _mm256_unpacklo_pd(a.x, a.y), xy_13 = _mm256_unpackhi_pd(a.x, a.y);  // x0 y0 x2 y2, x1 y1 x3 y3
  const V z_02 = _mm256_unpacklo_pd(a.z, zero), z_13 = _mm256_unpackhi_pd(a.z, zero);  // z0 0 z2 0, z1 0 z3 0
  out[0] = _mm256_permute2f128_pd(xy_02, z_02, 0x20);
  out[1] = _mm256_permute2f128_pd(xy_13, z_13, 0x20);
  out[2] = _mm256_permute2f128_pd(xy_02, z_02, 0x31);
  out[3] = _mm256_permute2f128_pd(xy_13, z_13, 0x31);
}
// s += a and s -= a on a padded load (its fourth double is never read).
AVX2 void add_to(LoadSum& s, V a) { _mm256_store_pd(s.v.data(), _mm256_load_pd(s.v.data()) + a); }
AVX2 void take_from(LoadSum& s, V a) { _mm256_store_pd(s.v.data(), _mm256_load_pd(s.v.data()) - a); }

// What the first `count` of four contacts (k, between slots i and j) leave, where all are summed
// here and only loads are kept: keep_pair_result's operations lane by lane, each vector added with
// one load, add and store (sim/load_sum.hpp; from lane arrays a double at a time, as
// keep_one_by_one, the chute took 6 % longer). The spring with a masked store: its three doubles,
// nothing written past it.
AVX2 void keep_loads(const PairLawArrays& a, const int (&k)[4], const int (&i)[4], const int (&j)[4], int count,
                     const V3& spring, const V3& on_i, const V3& moment_i, const V3& moment_j) {
  V s[4], f[4], t_i[4], t_j[4];
  per_lane(spring, s), per_lane(on_i, f), per_lane(moment_i, t_i), per_lane(moment_j, t_j);
  const __m256i xyz = _mm256_setr_epi64x(-1, -1, -1, 0);
  for (int l = 0; l < count; ++l) {
    _mm256_maskstore_pd(a.spring[k[l]].data(), xyz, s[l]);
    add_to(a.force[i[l]], f[l]);  // eq. 2.31-2.32
    take_from(a.force[j[l]], f[l]);
    add_to(a.torque[i[l]], t_i[l]);  // eq. 2.33-2.34: a n x f_t for i and j alike
    add_to(a.torque[j[l]], t_j[l]);
  }
}
// The same by keep_pair_result itself, from lane arrays: any contact.
AVX2 void keep_one_by_one(const PairLawArrays& a, const int (&k)[4], const int (&i)[4], const int (&j)[4], int count,
                          const V3& spring, const V3& n, const V3& on_i, const V3& moment, int reach_end) {
  const Lanes nx = lanes(n.x), ny = lanes(n.y), nz = lanes(n.z), fx = lanes(on_i.x), fy = lanes(on_i.y), fz = lanes(on_i.z);
  const Lanes mx = lanes(moment.x), my = lanes(moment.y), mz = lanes(moment.z);
  const Lanes sx = lanes(spring.x), sy = lanes(spring.y), sz = lanes(spring.z);
  for (int l = 0; l < count; ++l) {
    a.spring[k[l]] = Vec3(sx.l[l], sy.l[l], sz.l[l]);
    keep_pair_result(a, k[l], i[l], j[l], Vec3(nx.l[l], ny.l[l], nz.l[l]), Vec3(fx.l[l], fy.l[l], fz.l[l]),
                     Vec3(mx.l[l], my.l[l], mz.l[l]), reach_end);
  }
}

// contact/contact_law.hpp's in_tangent_plane and evaluate_in_plane with CundallNormal (and the
// kinematics of force_loop.cpp's pass 2), four contacts at a time: each step below is the scalar
// code's, in its order; branches become selections of both outcomes.
template <bool Fixed, bool Bonds>
[[gnu::target("avx2")]] double cundall_law_avx2(const PairLawArrays a, const MaterialTable& materials, double dt,
                                                const FoundInChunk found, int m, int reach_end) {
  if (m == 0) return 0;
  // Lanes past the last contact repeat it: computed, never kept.
  for (int q = m; q < m + 3; ++q)
    found.contact[q] = found.contact[m - 1], found.dx[q] = found.dx[m - 1], found.dy[q] = found.dy[m - 1], found.dz[q] = found.dz[m - 1];
  const V zero = _mm256_setzero_pd();
  // One material: the same parameters for every contact, set once.
  const PairParams* only[4] = {&materials.pair(0, 0), &materials.pair(0, 0), &materials.pair(0, 0), &materials.pair(0, 0)};
  LawParams law(only);
  double worst = 0;
  // Fetched into the cache ahead: the velocities of both particles of the contacts kAhead on (pass
  // 1 read only their positions). Settle of 10^4, one thread: 4 % off the step, where a random
  // packing's particles no longer fit the core's cache; i's alone or j's alone: nothing. Chute,
  // lattice of 10^5 and two threads: the same within the noise.
  constexpr int kAhead = 8;
  for (int e = 0; e < m; e += 4) {
    if (e + kAhead + 4 <= m)
      for (int l = 0; l < 4; ++l) {
        const long ahead = found.contact[e + kAhead + l];
        const int i_ahead = a.slot_i[ahead], j_ahead = a.slot_j[ahead];
        _mm_prefetch(reinterpret_cast<const char*>(a.v + i_ahead), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(a.w + i_ahead), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(a.v + j_ahead), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(a.w + j_ahead), _MM_HINT_T0);
      }
    const __m128i k = _mm_loadu_si128(reinterpret_cast<const __m128i*>(found.contact + e));
    const __m128i i = gather(a.slot_i, k), j = gather(a.slot_j, k);
    alignas(16) int kl[4], il[4], jl[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(kl), k);
    _mm_store_si128(reinterpret_cast<__m128i*>(il), i);
    _mm_store_si128(reinterpret_cast<__m128i*>(jl), j);

    // Kinematics (eq. 2.11-2.12).
    const V3 d = load3(found.dx + e, found.dy + e, found.dz + e);
    const V dist = root(dot(d, d));
    const V3 n = d * (1.0 / dist);
    const V ri = gather(a.radius, i), rj = gather(a.radius, j);
    const V overlap = (ri + rj) - dist;
    const V3 v_rel = load_four(a.v, jl) - load_four(a.v, il);
    const V3 w_arm = rj * load_four(a.w, jl) + ri * load_four(a.w, il);
    const V mi = gather(a.mass, i), mj = gather(a.mass, j);
    V m_eff = (mi * mj) / (mi + mj);
    if constexpr (Fixed) {  // effective_mass: against a held particle, the other's mass
      const std::uint8_t* held = a.fixed;
      m_eff = select(flags(held[il[0]], held[il[1]], held[il[2]], held[il[3]]), mj,
                     select(flags(held[jl[0]], held[jl[1]], held[jl[2]], held[jl[3]]), mi, m_eff));
    }

    // The spring turned into the tangent plane, keeping its magnitude.
    V3 s = load_four(a.spring, kl);
    const V s2 = dot(s, s);
    s = s - dot(s, n) * n;
    const V t2 = dot(s, s);
    s = select(both(less(zero, s2), less(zero, t2)), s * root(s2 / t2), s);

    // The law: damped linear normal force, tangential spring with Coulomb's (or, bonded,
    // Mohr-Coulomb's) radial return.
    if (materials.size() > 1) {
      const PairParams* pp[4];
      for (int l = 0; l < 4; ++l) pp[l] = &materials.pair(a.material[il[l]], a.material[jl[l]]);
      law = LawParams(pp);
    }
    const auto& [kn, kt, mu, damping_n, damping_t, cohesion, no_attraction] = law;
    // Without bonds (Bonds false: no contact of the scene holds one) every lane's flag is false.
    const V bonded = Bonds ? flags(a.bonded[kl[0]], a.bonded[kl[1]], a.bonded[kl[2]], a.bonded[kl[3]]) : zero;
    const V vn = dot(v_rel, n);
    const V f_el = only_where(less(zero, overlap), kn * overlap);
    const V sqrt_m = root(m_eff);
    V fn = f_el - (damping_n * sqrt_m) * vn;
    fn = zero_where(but_not(less_or_equal(overlap, zero), bonded), fn);
    fn = zero_where(both(but_not(no_attraction, bonded), less(fn, zero)), fn);
    const V3 vt = (v_rel - vn * n) - cross(w_arm, n);
    const V3 trial = s + (kt * dt) * vt;
    const V cohesive = cohesion + mu * fn;
    const V tau = select(bonded, only_where(less(zero, cohesive), cohesive), mu * zero_where(less(fn, zero), fn));
    const V trial2 = dot(trial, trial);
    const V stick = less_or_equal(trial2, tau * tau);
    // Where every lane sticks (most groups of a settled bed), the radial return's square root and
    // division are skipped: the settle of 10^4 on two threads 2 % faster, one thread the same.
    V3 spring = trial, ft = trial + (damping_t * sqrt_m) * vt;
    if (_mm256_movemask_pd(stick) != 0xf) {  // some lane slides: its radial return
      const V trial_norm = root(trial2);
      const V3 slid = only_where(less(zero, trial_norm), trial * (tau / trial_norm));
      spring = select(stick, spring, slid);
      ft = select(stick, ft, slid);
    }
    const V3 on_i = (-fn) * n + ft;
    const V3 moment = cross(n, ft);

    // Kept contact by contact, in order.
    const int count = std::min(4, m - e);
    const __m128i larger = _mm_max_epi32(i, j);
    if (!a.keep_results && _mm_movemask_epi8(_mm_cmplt_epi32(larger, _mm_set1_epi32(reach_end))) == 0xffff)
      keep_loads(a, kl, il, jl, count, spring, on_i, ri * moment, rj * moment);
    else
      keep_one_by_one(a, kl, il, jl, count, spring, n, on_i, moment, reach_end);
    // relative_overlap_if_larger's test on every lane with the group's first `worst`: where no lane
    // passes, none can with the larger values the loop below may reach (almost every group).
    const V bar = (_mm256_set1_pd(worst) * _mm256_min_pd(ri, rj)) * _mm256_set1_pd(1 - 1e-9);
    if (_mm256_movemask_pd(_mm256_cmp_pd(overlap, bar, _CMP_GE_OQ)) != 0) {
      const Lanes u = lanes(overlap);
      for (int l = 0; l < count; ++l)
        worst = std::max(worst, relative_overlap_if_larger(u.l[l], std::min(a.radius[il[l]], a.radius[jl[l]]), worst));
    }
  }
  return worst;
}
#undef AVX2

}  // namespace
#endif

template <bool Fixed>
double cundall_pair_law_simd(const PairLawArrays a, const MaterialTable& materials, double dt, const FoundInChunk found, int m,
                             int reach_end, bool any_bonds) {
#ifdef DEM_SIMD_LOOPS
  return any_bonds ? cundall_law_avx2<Fixed, true>(a, materials, dt, found, m, reach_end)
                   : cundall_law_avx2<Fixed, false>(a, materials, dt, found, m, reach_end);
#else
  (void)a, (void)materials, (void)dt, (void)found, (void)m, (void)reach_end, (void)any_bonds;
  return 0;  // never called: simd_loops_on() is false
#endif
}

template double cundall_pair_law_simd<false>(PairLawArrays, const MaterialTable&, double, FoundInChunk, int, int, bool);
template double cundall_pair_law_simd<true>(PairLawArrays, const MaterialTable&, double, FoundInChunk, int, int, bool);

}  // namespace dem
