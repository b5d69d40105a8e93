#pragma once
// Four lanes to and from memory, for the four-wide loops (DEM_AVX2, simd.hpp): loads and stores,
// a vector's three doubles with one masked load or store (nothing read or written past them),
// gathers, four particles' vectors at once, the lanes that passed a test stored at the front, and
// fetching into the cache.
#include <array>

#include "core/types.hpp"
#include "simd/lanes.hpp"
#include "simd/simd.hpp"

#ifdef DEM_SIMD_LOOPS
#include <immintrin.h>

namespace dem::simd {

using lanes::Lanes4;
using lanes::Triple;

// Four 32-bit indices (storage slots, places in a list): what a gather reads by.
struct Ints4 {
  __m128i v;
};

// Whether every lane of a equals b's.
DEM_AVX2_INLINE bool same(Ints4 a, Ints4 b) { return _mm_movemask_epi8(_mm_cmpeq_epi32(a.v, b.v)) == 0xffff; }

DEM_AVX2_INLINE Lanes4 load(const double* p) { return _mm256_loadu_pd(p); }
DEM_AVX2_INLINE Ints4 load(const int* p) { return {_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))}; }
DEM_AVX2_INLINE void store(double* p, Lanes4 a) { _mm256_storeu_pd(p, a.v); }
// p on a 32-byte boundary (16 bytes for ints).
DEM_AVX2_INLINE void store_aligned(double* p, Lanes4 a) { _mm256_store_pd(p, a.v); }
DEM_AVX2_INLINE void store_aligned(int* p, Ints4 a) { _mm_store_si128(reinterpret_cast<__m128i*>(p), a.v); }

// The first three lanes into p[0..2] (a Vec3's doubles): plain stores of two and one doubles, not
// a masked one, which AMD's cores run microcoded (bench/results/design.md).
DEM_AVX2_INLINE void store_xyz(double* p, Lanes4 a) {
  _mm_storeu_pd(p, _mm256_castpd256_pd128(a.v));
  _mm_store_sd(p + 2, _mm256_extractf128_pd(a.v, 1));
}

// base[k[0..3]]: four scalar loads, not a gather instruction, which AMD's cores run as many slow
// micro-operations (bench/results/design.md).
DEM_AVX2_INLINE Lanes4 gather(const double* base, const int (&k)[4]) { return _mm256_setr_pd(base[k[0]], base[k[1]], base[k[2]], base[k[3]]); }
DEM_AVX2_INLINE Ints4 gather(const int* base, const int (&k)[4]) { return {_mm_setr_epi32(base[k[0]], base[k[1]], base[k[2]], base[k[3]])}; }
// The same with the indices in a register (stored first: where they are already stored, pass those).
template <class T>
DEM_AVX2_INLINE auto gather(const T* base, Ints4 index) {
  alignas(16) int k[4];
  store_aligned(k, index);
  return gather(base, k);
}

// base[a], base[b], base[c], base[d] as x, y and z of the four: each vector's x and y read as a
// pair, its z alone, and the four transposed, in place of three gathers (bench/results/design.md). The
// slots by value: read through a pointer here, pass 1's loop kept one more pointer and spilled a
// register.
DEM_AVX2_INLINE Triple<Lanes4> load_four(const Vec3* base, int a, int b, int c, int d) {
  const double *pa = base[a].data(), *pb = base[b].data(), *pc = base[c].data(), *pd = base[d].data();
  const __m256d xy_ac = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(pa)), _mm_loadu_pd(pc), 1);  // xa ya xc yc
  const __m256d xy_bd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(pb)), _mm_loadu_pd(pd), 1);  // xb yb xd yd
  const __m128d z_ab = _mm_loadh_pd(_mm_load_sd(pa + 2), pb + 2), z_cd = _mm_loadh_pd(_mm_load_sd(pc + 2), pd + 2);
  return {_mm256_unpacklo_pd(xy_ac, xy_bd), _mm256_unpackhi_pd(xy_ac, xy_bd), _mm256_insertf128_pd(_mm256_castpd128_pd256(z_ab), z_cd, 1)};
}

// For each set of lanes (a bit each, as bits() gives), the 32-bit lanes that move those lanes'
// doubles to the front in order (a compress, which AVX2 lacks): lane q takes double l_q, i.e.
// 32-bit lanes 2 l_q and 2 l_q + 1.
constexpr std::array<std::array<int, 8>, 16> compress_doubles() {
  std::array<std::array<int, 8>, 16> t{};
  for (int mask = 0; mask < 16; ++mask) {
    int q = 0;
    for (int l = 0; l < 4; ++l)
      if (mask >> l & 1) t[mask][2 * q] = 2 * l, t[mask][2 * q + 1] = 2 * l + 1, ++q;
  }
  return t;
}
// The same for four 32-bit lanes, in the low half.
constexpr std::array<std::array<int, 8>, 16> compress_ints() {
  std::array<std::array<int, 8>, 16> t{};
  for (int mask = 0; mask < 16; ++mask) {
    int q = 0;
    for (int l = 0; l < 4; ++l)
      if (mask >> l & 1) t[mask][q++] = l;
  }
  return t;
}
// Internal linkage (constexpr): each file that uses them reads its own copy directly.
alignas(32) constexpr std::array<std::array<int, 8>, 16> kCompressDoubles = compress_doubles();
alignas(32) constexpr std::array<std::array<int, 8>, 16> kCompressInts = compress_ints();

// The lanes of a set in `keep` (bits), in order, stored from `to` on. Four doubles are written:
// those past the kept lanes hold others.
DEM_AVX2_INLINE void store_compressed(double* to, Lanes4 a, int keep) {
  const __m256i to_front = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompressDoubles[keep].data()));
  _mm256_storeu_pd(to, _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(a.v), to_front)));
}
// first + l for each lane l set in `keep` (bits), in order, stored from `to` on. Four ints are
// written: those past the kept lanes hold others.
DEM_AVX2_INLINE void store_compressed_indices(int* to, int first, int keep) {
  const __m256i indices = _mm256_add_epi32(_mm256_set1_epi32(first), _mm256_setr_epi32(0, 1, 2, 3, 0, 0, 0, 0));
  const __m256i to_front = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompressInts[keep].data()));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(to), _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(indices, to_front)));
}

// The cache line holding p fetched into every level ahead of its use.
DEM_AVX2_INLINE void prefetch(const void* p) { _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0); }

}  // namespace dem::simd
#endif
