#pragma once
// How four particles' vectors lie in registers, for the four-wide loops (DEM_AVX2, simd.hpp), and
// the moves between layouts. Packed: as storage holds them (Vec3), twelve consecutive doubles,
// three registers [x0 y0 z0 x1], [y1 z1 x2 y2], [z2 x3 y3 z3]. By axis: a Triple, x, y and z of
// the four. Per lane: one register [x y z 0] each.
#include "core/types.hpp"
#include "simd/lanes.hpp"
#include "simd/simd.hpp"

#ifdef DEM_SIMD_LOOPS
#include <immintrin.h>

namespace dem::simd {

using lanes::Lanes4;
using lanes::Triple;

// A value per axis laid out as packed vectors: [ax ay az ax], [ay az ax ay], [az ax ay az].
DEM_AVX2_INLINE void by_axis(const Vec3& a, Lanes4 (&out)[3]) {
  out[0] = _mm256_setr_pd(a.x(), a.y(), a.z(), a.x());
  out[1] = _mm256_setr_pd(a.y(), a.z(), a.x(), a.y());
  out[2] = _mm256_setr_pd(a.z(), a.x(), a.y(), a.z());
}
// A value per particle (the four lanes of s) laid out alike: [s0 s0 s0 s1], [s1 s1 s2 s2], [s2 s3 s3 s3].
DEM_AVX2_INLINE void by_particle(Lanes4 s, Lanes4 (&out)[3]) {
  out[0] = _mm256_permute4x64_pd(s.v, 0b01000000);
  out[1] = _mm256_permute4x64_pd(s.v, 0b10100101);
  out[2] = _mm256_permute4x64_pd(s.v, 0b11111110);
}

// Packed vectors to x, y and z of the four (blends and one permutation each).
DEM_AVX2_INLINE Triple<Lanes4> unpack(const Lanes4 (&packed)[3]) {
  const __m256d a = packed[0].v, b = packed[1].v, c = packed[2].v;
  return {_mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b0100), c, 0b0010), 0b01101100),
          _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b1001), c, 0b0100), 0b10110001),
          _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b0010), c, 0b1001), 0b11000110)};
}

// Four vectors padded to four doubles each ([x y z -], 16 doubles from f, 32-byte aligned), packed.
// From loads, broadcasts and blends only (no shuffle across the register's halves: those have one
// port, which the integration keeps busy already).
DEM_AVX2_INLINE void pack_padded(const double* f, Lanes4 (&out)[3]) {
  out[0] = _mm256_blend_pd(_mm256_load_pd(f), _mm256_broadcast_sd(f + 4), 0b1000);  // [x0 y0 z0 -] with x1
  out[1] = _mm256_blend_pd(_mm256_loadu_pd(f + 5), _mm256_broadcast_pd(reinterpret_cast<const __m128d*>(f + 8)), 0b1100);  // [y1 z1 - x2] with x2 y2
  out[2] = _mm256_blend_pd(_mm256_loadu_pd(f + 11), _mm256_broadcast_sd(f + 10), 0b0001);  // [- x3 y3 z3] with z2
}

// By axis to per lane: [x y z 0] of each of the four (a 4 x 4 transpose with a zero row).
DEM_AVX2_INLINE void per_lane(const Triple<Lanes4>& a, Lanes4 (&out)[4]) {
  const __m256d zero = _mm256_setzero_pd();
  const __m256d xy_02 = _mm256_unpacklo_pd(a.x.v, a.y.v), xy_13 = _mm256_unpackhi_pd(a.x.v, a.y.v);  // x0 y0 x2 y2, x1 y1 x3 y3
  const __m256d z_02 = _mm256_unpacklo_pd(a.z.v, zero), z_13 = _mm256_unpackhi_pd(a.z.v, zero);  // z0 0 z2 0, z1 0 z3 0
  out[0] = _mm256_permute2f128_pd(xy_02, z_02, 0x20);
  out[1] = _mm256_permute2f128_pd(xy_13, z_13, 0x20);
  out[2] = _mm256_permute2f128_pd(xy_02, z_02, 0x31);
  out[3] = _mm256_permute2f128_pd(xy_13, z_13, 0x31);
}

}  // namespace dem::simd
#endif
