#pragma once
// Operations on four lanes (lanes.hpp's Lanes4 and Mask4) that take AVX2 instructions of their
// own, so that only a four-wide loop (DEM_AVX2, simd.hpp) may call them; each lane gets what the
// plain loop's scalar operation gives, to the bit. Comparisons here are the quiet ones (no
// exception on a NaN): the same masks as lanes.hpp's.
#include "simd/lanes.hpp"
#include "simd/simd.hpp"

#ifdef DEM_SIMD_LOOPS
#include <immintrin.h>

namespace dem::simd {

using lanes::Lanes4;
using lanes::Mask4;

// a in every lane: one vbroadcastsd (lanes.hpp's Lanes4(a) gives the same bits with one
// vpbroadcastq, in the integer domain).
DEM_AVX2_INLINE Lanes4 broadcast(double a) { return _mm256_set1_pd(a); }

// One bit per lane, lane 0 lowest: to branch on, or to count.
DEM_AVX2_INLINE int bits(Mask4 where) { return _mm256_movemask_pd((__m256d)where.v); }
DEM_AVX2_INLINE Mask4 either(Mask4 a, Mask4 b) { return {(lanes::i64x4)_mm256_or_pd((__m256d)a.v, (__m256d)b.v)}; }
DEM_AVX2_INLINE Mask4 greater_or_equal(Lanes4 a, Lanes4 b) { return {(lanes::i64x4)_mm256_cmp_pd(a.v, b.v, _CMP_GE_OQ)}; }
// Not a <= b: a > b, or either is NaN.
DEM_AVX2_INLINE Mask4 not_less_or_equal(Lanes4 a, Lanes4 b) { return {(lanes::i64x4)_mm256_cmp_pd(a.v, b.v, _CMP_NLE_UQ)}; }

// Not a < b: a >= b, or either is NaN.
DEM_AVX2_INLINE Mask4 not_less(Lanes4 a, Lanes4 b) { return {(lanes::i64x4)_mm256_cmp_pd(a.v, b.v, _CMP_NLT_UQ)}; }

// Each lane rounded towards zero to a whole number (std::trunc's, exact): one vroundpd.
DEM_AVX2_INLINE Lanes4 truncated(Lanes4 a) { return _mm256_round_pd(a.v, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC); }

// vminpd and vmaxpd: a < b ? a : b and a > b ? a : b, lane by lane (b where either is NaN).
DEM_AVX2_INLINE Lanes4 min(Lanes4 a, Lanes4 b) { return _mm256_min_pd(a.v, b.v); }
DEM_AVX2_INLINE Lanes4 max(Lanes4 a, Lanes4 b) { return _mm256_max_pd(a.v, b.v); }
// |a|: the sign bit cleared.
DEM_AVX2_INLINE Lanes4 abs(Lanes4 a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v); }

// d - L s with s = +1 where d > L/2, -1 where d < -L/2, else 0, lane by lane: PeriodicBox::nearest's
// d - L or d + L or d, to the bit (L s is exactly +-L or 0). A lane with L = 0 and L/2 = infinity
// (an axis that is not periodic) keeps d.
DEM_AVX2_INLINE Lanes4 nearest_image(Lanes4 d, Lanes4 L, Lanes4 half_L) {
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d up = _mm256_and_pd(_mm256_cmp_pd(d.v, half_L.v, _CMP_GT_OQ), one);
  const __m256d down = _mm256_and_pd(_mm256_cmp_pd(d.v, -half_L.v, _CMP_LT_OQ), one);
  return d.v - L.v * (up - down);
}

}  // namespace dem::simd
#endif
