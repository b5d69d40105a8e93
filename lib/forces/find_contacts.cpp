#include "forces/find_contacts.hpp"

#include <cstring>

#include "simd/lanes_avx2.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {

#ifdef DEM_SIMD_LOOPS
// Four candidates at a time: the positions gathered (x is 3 doubles per particle), the separation
// and the touch test in the plain loop's order of operations ((dx^2 + dy^2) + dz^2 < r^2), the
// contacts moved to the front of the lanes and stored; the last one to three by the plain loop.
template <bool Periodic>
DEM_AVX2 int find_contacts_avx2(const CandidateArrays a, const PeriodicBox& box, long first, long last, const FoundInChunk found) {
  using lanes::Lanes4;
  using simd::broadcast;
  int m = 0;
  long k = first;
  // Fetched into the cache ahead: the other particle of the candidates kAhead on, as gathers that
  // miss the cache stall the loop (bench/results/design.md). (The first particle's slots rise
  // along the storage: the processor fetches those ahead by itself.)
  constexpr long kAhead = 32;
  const long ahead_end = a.count - kAhead - 4;
  for (; k + 4 <= last; k += 4) {
    if (k <= ahead_end)
      for (int l = 0; l < 4; ++l) {
        const int j = a.slot_j[k + kAhead + l];
        simd::prefetch(a.x + j);
        simd::prefetch(a.radius + j);
      }
    const simd::Ints4 i = simd::load(a.slot_i + k), j = simd::load(a.slot_j + k);
    const lanes::Triple<Lanes4> pi = simd::load_four(a.x, a.slot_i[k], a.slot_i[k + 1], a.slot_i[k + 2], a.slot_i[k + 3]);
    const lanes::Triple<Lanes4> pj = simd::load_four(a.x, a.slot_j[k], a.slot_j[k + 1], a.slot_j[k + 2], a.slot_j[k + 3]);
    Lanes4 dx = pj.x - pi.x;
    Lanes4 dy = pj.y - pi.y;
    Lanes4 dz = pj.z - pi.z;
    if constexpr (Periodic) {
      if (box.axis[0]) dx = simd::nearest_image(dx, broadcast(box.length(0)), broadcast(0.5 * box.length(0)));
      if (box.axis[1]) dy = simd::nearest_image(dy, broadcast(box.length(1)), broadcast(0.5 * box.length(1)));
      if (box.axis[2]) dz = simd::nearest_image(dz, broadcast(box.length(2)), broadcast(0.5 * box.length(2)));
    }
    const Lanes4 r = simd::gather(a.radius, i) + simd::gather(a.radius, j);
    const Lanes4 d2 = (dx * dx + dy * dy) + dz * dz;
    int now = simd::bits(lanes::less(d2, r * r));
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
    if (const int lost = (a.work_unset ? 15 : lanes(active4)) & ~now)  // rare: a contact ends (or the work is unset)
      for (int l = 0; l < 4; ++l)
        if (lost >> l & 1) clear_no_contact(a, k + l, active4 >> 8 * l & 1);
    simd::store_compressed(found.dx + m, dx, now);
    simd::store_compressed(found.dy + m, dy, now);
    simd::store_compressed(found.dz + m, dz, now);
    simd::store_compressed_indices(found.contact + m, static_cast<int>(k), now);
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
