#pragma once
// Lane types, so that a law is written once and runs one contact at a time or four at a time:
// code written over a lane type L (double, or Lanes4: four doubles in an AVX2 register) with its
// mask type (bool, or Mask4) and selections in place of branches is the plain path with
// L = double and the four-wide path with L = Lanes4. Each operation rounds alike in a lane and in
// a scalar register (IEEE 754; no fused multiply-add is contracted), so both give the same bits.
//
// A four-wide caller is a [[gnu::target("avx2"), gnu::flatten]] function: flatten inlines the law
// (compiled for the default target) and the operations below into it, where AVX2 is allowed.
#include <cmath>

#include "core/types.hpp"
#include "simd/simd.hpp"

namespace dem::lanes {

// One lane: plain doubles, masks are bools. (Bitwise & on bools: no branch.)
inline bool less(double a, double b) { return a < b; }
inline bool less_or_equal(double a, double b) { return a <= b; }
inline bool both(bool a, bool b) { return a & b; }
inline bool but_not(bool a, bool b) { return a & !b; }  // a and not b
inline double select(bool where, double a, double b) { return where ? a : b; }
inline double only_where(bool where, double a) { return where ? a : 0.0; }  // where ? a : +0
inline double zero_where(bool where, double a) { return where ? 0.0 : a; }  // where ? +0 : a
inline double root(double a) { return std::sqrt(a); }
inline bool all(bool where) { return where; }

// A vector of three lanes each: x, y and z of one contact, or of four.
template <class L>
struct Triple {
  L x, y, z;
};
template <class L> inline Triple<L> operator+(const Triple<L>& a, const Triple<L>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class L> inline Triple<L> operator-(const Triple<L>& a, const Triple<L>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class L> inline Triple<L> operator*(const L& s, const Triple<L>& a) { return {s * a.x, s * a.y, s * a.z}; }
template <class L> inline Triple<L> operator*(const Triple<L>& a, const L& s) { return {a.x * s, a.y * s, a.z * s}; }
// Eigen's order for 3-vectors: (a0 b0 + a1 b1) + a2 b2, and the cross product's usual terms.
template <class L> inline L dot(const Triple<L>& a, const Triple<L>& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
template <class L> inline Triple<L> cross(const Triple<L>& a, const Triple<L>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class L, class M> inline Triple<L> select(const M& where, const Triple<L>& a, const Triple<L>& b) {
  return {select(where, a.x, b.x), select(where, a.y, b.y), select(where, a.z, b.z)};
}
template <class L, class M> inline Triple<L> only_where(const M& where, const Triple<L>& a) {
  return {only_where(where, a.x), only_where(where, a.y), only_where(where, a.z)};
}
inline Triple<double> triple(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 vec3(const Triple<double>& t) { return Vec3(t.x, t.y, t.z); }

#ifdef DEM_SIMD_LOOPS
#define DEM_AVX2 [[gnu::target("avx2")]] inline

// Four lanes of doubles, and a mask per lane (all bits set or none).
struct Lanes4 {
  __m256d v;
  Lanes4() = default;
  DEM_AVX2 Lanes4(__m256d a) : v(a) {}
  DEM_AVX2 Lanes4(double a) : v(_mm256_set1_pd(a)) {}  // the same value in every lane
};
struct Mask4 {
  __m256d v;
};
DEM_AVX2 Lanes4 operator+(Lanes4 a, Lanes4 b) { return _mm256_add_pd(a.v, b.v); }
DEM_AVX2 Lanes4 operator-(Lanes4 a, Lanes4 b) { return _mm256_sub_pd(a.v, b.v); }
DEM_AVX2 Lanes4 operator*(Lanes4 a, Lanes4 b) { return _mm256_mul_pd(a.v, b.v); }
DEM_AVX2 Lanes4 operator/(Lanes4 a, Lanes4 b) { return _mm256_div_pd(a.v, b.v); }
DEM_AVX2 Lanes4 operator-(Lanes4 a) { return _mm256_xor_pd(a.v, _mm256_set1_pd(-0.0)); }  // exact, as a scalar's -a
DEM_AVX2 Mask4 less(Lanes4 a, Lanes4 b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)}; }
DEM_AVX2 Mask4 less_or_equal(Lanes4 a, Lanes4 b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_LE_OQ)}; }
DEM_AVX2 Mask4 both(Mask4 a, Mask4 b) { return {_mm256_and_pd(a.v, b.v)}; }
DEM_AVX2 Mask4 but_not(Mask4 a, Mask4 b) { return {_mm256_andnot_pd(b.v, a.v)}; }
DEM_AVX2 Lanes4 select(Mask4 where, Lanes4 a, Lanes4 b) { return _mm256_blendv_pd(b.v, a.v, where.v); }
// One instruction each (a blend is three on recent Intel cores).
DEM_AVX2 Lanes4 only_where(Mask4 where, Lanes4 a) { return _mm256_and_pd(where.v, a.v); }
DEM_AVX2 Lanes4 zero_where(Mask4 where, Lanes4 a) { return _mm256_andnot_pd(where.v, a.v); }
DEM_AVX2 Lanes4 root(Lanes4 a) { return _mm256_sqrt_pd(a.v); }
DEM_AVX2 bool all(Mask4 where) { return _mm256_movemask_pd(where.v) == 0xf; }
DEM_AVX2 bool any(Mask4 where) { return _mm256_movemask_pd(where.v) != 0; }
// A mask from four flags.
DEM_AVX2 Mask4 mask4(bool a, bool b, bool c, bool d) {
  return {_mm256_castsi256_pd(_mm256_setr_epi64x(-long{a}, -long{b}, -long{c}, -long{d}))};
}
DEM_AVX2 Lanes4 lanes4(double a, double b, double c, double d) { return _mm256_setr_pd(a, b, c, d); }

#undef DEM_AVX2
#endif

}  // namespace dem::lanes
