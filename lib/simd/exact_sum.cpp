#include "simd/exact_sum.hpp"

#include <algorithm>

#include "simd/lanes_avx2.hpp"
#include "simd/memory.hpp"

namespace dem {

namespace {

void add_one_by_one(FixedSum& s, const double* x, long n) {
  for (long k = 0; k < n; ++k) s.add(x[k]);
}

#ifdef DEM_SIMD_LOOPS
// Each term in units of 2^-90 J, truncated towards zero (FixedSum::add), is a whole number t with
// |t| < 2^126, which a double holds exactly. Cut at 2^84 and 2^42 units, each cut a truncation (so
// exact, every part of t's sign), t is three whole numbers of fewer than 2^42 of their units; a
// lane's sum of up to 2^11 of each stays below 2^53 units, so exact too; then the lanes' sums
// join FixedSum's integer. The same integer as adding the terms one by one, in any order.
constexpr long kPerLane = 2048;

// x[0, n), n a multiple of 4 and at most 4 kPerLane, added to s; false (s untouched) where a term
// is out of FixedSum's range or NaN, for the caller to add them one by one (which keeps it).
DEM_AVX2 bool add_four_at_a_time(FixedSum& s, const double* x, long n) {
  using simd::Lanes4;
  const Lanes4 limit = simd::broadcast(0x1p36);
  Lanes4 high = simd::broadcast(0.0), middle = high, low = high;
  lanes::Mask4 out_of_range;
  for (long k = 0; k < n; k += 4) {
    const Lanes4 v = simd::load(x + k);
    out_of_range = simd::either(out_of_range, simd::not_less(simd::abs(v), limit));
    const Lanes4 t = simd::truncated(v * Lanes4(0x1p90));  // exact: a power of 2
    const Lanes4 h = simd::truncated(t * Lanes4(0x1p-84)) * Lanes4(0x1p84);
    const Lanes4 rest = t - h;
    const Lanes4 m = simd::truncated(rest * Lanes4(0x1p-42)) * Lanes4(0x1p42);
    high = high + h, middle = middle + m, low = low + (rest - m);
  }
  if (simd::bits(out_of_range) != 0) return false;
  for (int l = 0; l < 4; ++l) {
    s.add_whole_units(high.v[l] * 0x1p-84, 84);
    s.add_whole_units(middle.v[l] * 0x1p-42, 42);
    s.add_whole_units(low.v[l], 0);
  }
  return true;
}
#endif

}  // namespace

void add_all(FixedSum& s, const double* x, long n) {
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on()) {
    const long four = n - n % 4;
    for (long first = 0; first < four; first += 4 * kPerLane) {
      const long count = std::min(four - first, 4 * kPerLane);
      if (!add_four_at_a_time(s, x + first, count)) add_one_by_one(s, x + first, count);
    }
    add_one_by_one(s, x + four, n - four);
    return;
  }
#endif
  add_one_by_one(s, x, n);
}

}  // namespace dem
