#include "sim/find_contacts.hpp"

#include <array>
#include <cstring>

#include "simd/simd.hpp"

namespace dem {

namespace {

#ifdef DEM_SIMD_LOOPS
using simd::gather;

// For each mask of four lanes, the 32-bit lanes that move the set lanes' doubles to the front in
// order (a compress, which AVX2 lacks): lane q takes double l_q, i.e. 32-bit lanes 2 l_q, 2 l_q + 1.
constexpr std::array<std::array<int, 8>, 16> compress_doubles() {
  std::array<std::array<int, 8>, 16> t{};
  for (int mask = 0; mask < 16; ++mask) {
    int q = 0;
    for (int l = 0; l < 4; ++l)
      if (mask >> l & 1) t[mask][2 * q] = 2 * l, t[mask][2 * q + 1] = 2 * l + 1, ++q;
  }
  return t;
}
// The same for four 32-bit lanes (the candidates' positions), in the low half.
constexpr std::array<std::array<int, 8>, 16> compress_ints() {
  std::array<std::array<int, 8>, 16> t{};
  for (int mask = 0; mask < 16; ++mask) {
    int q = 0;
    for (int l = 0; l < 4; ++l)
      if (mask >> l & 1) t[mask][q++] = l;
  }
  return t;
}
alignas(32) constexpr std::array<std::array<int, 8>, 16> kCompressDoubles = compress_doubles();
alignas(32) constexpr std::array<std::array<int, 8>, 16> kCompressInts = compress_ints();

// Four candidates at a time: the positions gathered (x is 3 doubles per particle), the separation
// and the touch test in the plain loop's order of operations ((dx^2 + dy^2) + dz^2 < r^2), the
// contacts moved to the front of the lanes and stored; the last one to three by the plain loop.
template <bool Periodic>
[[gnu::target("avx2")]] int find_contacts_avx2(const CandidateArrays a, const PeriodicBox& box, long first, long last,
                                               const FoundInChunk found) {
  int m = 0;
  long k = first;
  // Fetched into the cache ahead: the other particle of the candidates kAhead on. Gathers that
  // miss the cache stall the loop (the plain loop runs ahead instead); with 10^5 falling spheres
  // this loop took 50 % more perf samples than the plain one without it, about as many with it
  // (6,886 against 6,823); the chute's, 5 % fewer than without. (The first particle's slots rise
  // along the storage: the processor fetches those ahead by itself.)
  constexpr long kAhead = 32;
  const long ahead_end = a.count - kAhead - 4;
  for (; k + 4 <= last; k += 4) {
    if (k <= ahead_end)
      for (int l = 0; l < 4; ++l) {
        const int j = a.slot_j[k + kAhead + l];
        _mm_prefetch(reinterpret_cast<const char*>(a.x + j), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(a.radius + j), _MM_HINT_T0);
      }
    const __m128i i = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a.slot_i + k));
    const __m128i j = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a.slot_j + k));
    __m256d xi, yi, zi, xj, yj, zj;
    simd::load_four(a.x, a.slot_i[k], a.slot_i[k + 1], a.slot_i[k + 2], a.slot_i[k + 3], xi, yi, zi);
    simd::load_four(a.x, a.slot_j[k], a.slot_j[k + 1], a.slot_j[k + 2], a.slot_j[k + 3], xj, yj, zj);
    __m256d dx = _mm256_sub_pd(xj, xi);
    __m256d dy = _mm256_sub_pd(yj, yi);
    __m256d dz = _mm256_sub_pd(zj, zi);
    if constexpr (Periodic) {
      if (box.axis[0]) dx = simd::nearest_image(dx, _mm256_set1_pd(box.length(0)), _mm256_set1_pd(0.5 * box.length(0)));
      if (box.axis[1]) dy = simd::nearest_image(dy, _mm256_set1_pd(box.length(1)), _mm256_set1_pd(0.5 * box.length(1)));
      if (box.axis[2]) dz = simd::nearest_image(dz, _mm256_set1_pd(box.length(2)), _mm256_set1_pd(0.5 * box.length(2)));
    }
    const __m256d r = _mm256_add_pd(gather(a.radius, i), gather(a.radius, j));
    const __m256d d2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
    int now = _mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(r, r), _CMP_LT_OQ));
    std::uint32_t bonded4, active4;
    std::memcpy(&bonded4, a.bonded + k, 4);
    std::memcpy(&active4, a.active + k, 4);
    // One bit per lane from the four bytes (0 or 1 each).
    const auto lanes = [](std::uint32_t bytes) {
      return static_cast<int>((bytes & 1) | (bytes >> 7 & 2) | (bytes >> 14 & 4) | (bytes >> 21 & 8));
    };
    now |= lanes(bonded4);
    const std::uint32_t now4 = (now & 1) | (now & 2) << 7 | (now & 4) << 14 | (now & 8) << 21;
    std::memcpy(a.active + k, &now4, 4);
    if (const int lost = lanes(active4) & ~now)  // rare: a contact ends
      for (int l = 0; l < 4; ++l)
        if (lost >> l & 1) a.spring[k + l] = Vec3::Zero(), a.sum[k + l] = ContactSum();
    const __m256i to_front = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompressDoubles[now].data()));
    _mm256_storeu_pd(found.dx + m, _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(dx), to_front)));
    _mm256_storeu_pd(found.dy + m, _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(dy), to_front)));
    _mm256_storeu_pd(found.dz + m, _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(dz), to_front)));
    const __m256i positions = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(k)), _mm256_setr_epi32(0, 1, 2, 3, 0, 0, 0, 0));
    const __m256i ints_to_front = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompressInts[now].data()));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(found.contact + m),
                     _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(positions, ints_to_front)));
    m += __builtin_popcount(now);
  }
  return find_contacts_plain<Periodic>(a, box, k, last, found, m);
}
#endif

}  // namespace

template <bool Periodic>
int find_contacts(const CandidateArrays a, const PeriodicBox& box, long first, long last, const FoundInChunk found,
                  [[maybe_unused]] bool simd) {
#ifdef DEM_SIMD_LOOPS
  if (simd) return find_contacts_avx2<Periodic>(a, box, first, last, found);
#endif
  return find_contacts_plain<Periodic>(a, box, first, last, found, 0);
}

template int find_contacts<false>(CandidateArrays, const PeriodicBox&, long, long, FoundInChunk, bool);
template int find_contacts<true>(CandidateArrays, const PeriodicBox&, long, long, FoundInChunk, bool);

}  // namespace dem
