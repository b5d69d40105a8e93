#pragma once
// The force loop's four-wide versions (AVX2, where the processor has it): whether they run, and
// the gathers they share. Each does per contact the same operations in the same order as the
// plain loop it stands for, so both give the same bits (IEEE 754 rounds each operation alike in a
// vector lane and in a scalar register; no fused multiply-add is enabled, so none is contracted).

namespace dem {

bool simd_loops_available();  // the processor has AVX2 (always false off x86-64)
bool simd_loops_on();         // available, and not turned off
void set_simd_loops(bool on); // on unless DEM_SIMD=off; tests turn it off to compare bit for bit

}  // namespace dem

#if defined(__x86_64__)
#include <immintrin.h>
#define DEM_SIMD_LOOPS 1

namespace dem::simd {

// base[index] for four 32-bit indices. (The masked forms: the plain ones start from an undefined
// register, which GCC 12 warns may be used uninitialized.)
[[gnu::target("avx2")]] inline __m256d gather(const double* base, __m128i index) {
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, index, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8);
}
[[gnu::target("avx2")]] inline __m128i gather(const int* base, __m128i index) {
  return _mm_mask_i32gather_epi32(_mm_setzero_si128(), base, index, _mm_set1_epi32(-1), 4);
}
[[gnu::target("avx2")]] inline __m128i times3(__m128i index) { return _mm_add_epi32(index, _mm_add_epi32(index, index)); }

}  // namespace dem::simd
#endif
