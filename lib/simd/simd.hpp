#pragma once
// The four-wide versions (AVX2, where the processor has it) of the force loop, the integration
// (sim/motion.cpp), the rebuild check (search/largest_move.cpp) and the search's distance pre-test
// (search/linked_cells.cpp): whether they run, and how they are marked. Each does per contact or
// particle the same operations in the same order as the plain loop it stands for, so both give
// the same bits (IEEE 754 rounds each operation alike in a vector lane and in a scalar register;
// no fused multiply-add is enabled, so none is contracted). Their operations are the layer's:
// lanes.hpp (lane types and arithmetic), lanes_avx2.hpp (what needs AVX2 instructions of its
// own), memory.hpp (loads, stores, gathers), layout.hpp (four vectors' layouts in registers).
// (AVX-512, eight lanes, was tried for the law: 15 % slower on an Intel Xeon, same bits.)

namespace dem {

bool simd_loops_available();  // the processor has AVX2 (always false off x86-64)
bool simd_loops_on();         // available, and not turned off
void set_simd_loops(bool on); // on unless DEM_SIMD=off; tests turn it off to compare bit for bit

}  // namespace dem

#if defined(__x86_64__)
#define DEM_SIMD_LOOPS 1
// A four-wide loop: compiled for AVX2 (the build stays generic x86-64), called only where
// simd_loops_on(); the layer's operations inline only into such a function.
#define DEM_AVX2 [[gnu::target("avx2")]]
// An operation of the layer: always inlined into its four-wide caller (a 32-byte vector passed by
// value to a function of another target would change the calling convention).
#define DEM_AVX2_INLINE [[gnu::target("avx2"), gnu::always_inline]] inline

#include <immintrin.h>

#include "core/types.hpp"

namespace dem::simd {

// base[index] for four 32-bit indices. (The masked forms: the plain ones start from an undefined
// register, which GCC 12 warns may be used uninitialized.)
[[gnu::target("avx2")]] inline __m256d gather(const double* base, __m128i index) {
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, index, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8);
}
[[gnu::target("avx2")]] inline __m128i gather(const int* base, __m128i index) {
  return _mm_mask_i32gather_epi32(_mm_setzero_si128(), base, index, _mm_set1_epi32(-1), 4);
}

// base[a], base[b], base[c], base[d] as three registers of x, y and z: each vector read with one
// masked load (its three doubles only: nothing read past it) and the four transposed, in place of
// three gathers (pass 1 took 15 % fewer perf samples on the chute so).
[[gnu::target("avx2")]] inline void load_four(const Vec3* base, int a, int b, int c, int d, __m256d& x, __m256d& y, __m256d& z) {
  const __m256i xyz = _mm256_setr_epi64x(-1, -1, -1, 0);
  const __m256d ra = _mm256_maskload_pd(base[a].data(), xyz), rb = _mm256_maskload_pd(base[b].data(), xyz);
  const __m256d rc = _mm256_maskload_pd(base[c].data(), xyz), rd = _mm256_maskload_pd(base[d].data(), xyz);
  const __m256d xz_ab = _mm256_unpacklo_pd(ra, rb), xz_cd = _mm256_unpacklo_pd(rc, rd);  // xa xb za zb, xc xd zc zd
  const __m256d y_ab = _mm256_unpackhi_pd(ra, rb), y_cd = _mm256_unpackhi_pd(rc, rd);    // ya yb 0 0, yc yd 0 0
  x = _mm256_permute2f128_pd(xz_ab, xz_cd, 0x20);
  y = _mm256_permute2f128_pd(y_ab, y_cd, 0x20);
  z = _mm256_permute2f128_pd(xz_ab, xz_cd, 0x31);
}

// d - L s with s = +1 where d > L/2, -1 where d < -L/2, else 0, lane by lane: PeriodicBox::nearest's
// d - L or d + L or d, to the bit (L s is exactly +-L or 0). A lane with L = 0 and L/2 = infinity
// (an axis that is not periodic) keeps d.
[[gnu::target("avx2")]] inline __m256d nearest_image(__m256d d, __m256d L, __m256d half_L) {
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d up = _mm256_and_pd(_mm256_cmp_pd(d, half_L, _CMP_GT_OQ), one);
  const __m256d down = _mm256_and_pd(_mm256_cmp_pd(d, -half_L, _CMP_LT_OQ), one);
  return d - L * (up - down);
}

// Four particles' vectors (Vec3) are twelve consecutive doubles: three registers [x0 y0 z0 x1],
// [y1 z1 x2 y2], [z2 x3 y3 z3]. A value per axis laid out alike: [ax ay az ax], [ay az ax ay],
// [az ax ay az].
[[gnu::target("avx2")]] inline void by_axis(const Vec3& a, __m256d out[3]) {
  out[0] = _mm256_setr_pd(a.x(), a.y(), a.z(), a.x());
  out[1] = _mm256_setr_pd(a.y(), a.z(), a.x(), a.y());
  out[2] = _mm256_setr_pd(a.z(), a.x(), a.y(), a.z());
}
// A value per particle (the four lanes of s) laid out alike: [s0 s0 s0 s1], [s1 s1 s2 s2], [s2 s3 s3 s3].
[[gnu::target("avx2")]] inline void by_particle(__m256d s, __m256d out[3]) {
  out[0] = _mm256_permute4x64_pd(s, 0b01000000);
  out[1] = _mm256_permute4x64_pd(s, 0b10100101);
  out[2] = _mm256_permute4x64_pd(s, 0b11111110);
}

}  // namespace dem::simd
#endif
