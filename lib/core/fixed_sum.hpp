#pragma once
// An exact sum of the energy ledger's terms (sim/energy_ledger.hpp), kept where they arise: the
// force loop adds each step's work (forces/step_work.hpp), the ledger's pass the rest.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.hpp"

namespace dem {

// A sum of doubles, exact in fixed point (2^-90 J, range ±2^37 J): the same bits in any order.
// Each term is truncated towards zero to a multiple of 2^-90 J. A term beyond ±2^36 J is not added
// but kept, and value() throws PhysicsError: add() never throws, so it may run in a parallel region.
class FixedSum {
 public:
  void add(double x) {
    if (!(std::abs(x) < 0x1p36)) [[unlikely]] {
      bad_ = x;
      return;
    }
    // trunc(x 2^90) in two exact steps of at most 63 bits: |x 2^90| < 2^126, and the rest after the
    // high part is a double that fits an int64 (a plain (__int128) cast is a libgcc call).
    const double y = x * 0x1p90;  // exact: a power of 2
    const std::int64_t high = static_cast<std::int64_t>(y * 0x1p-63);
    sum_ += static_cast<__int128>(high) * (__int128{1} << 63) + static_cast<std::int64_t>(y - static_cast<double>(high) * 0x1p63);
  }
  // Adds `whole` x 2^shift units, `whole` a whole number held exactly in a double with |whole| <
  // 2^63: the parts of many terms summed apart (simd/exact_sum.hpp). Modulo 2^128, as unsigned
  // integers: such a part may lie beyond the range that the whole sum keeps to.
  void add_whole_units(double whole, int shift) {
    using Bits = unsigned __int128;
    sum_ = static_cast<__int128>(static_cast<Bits>(sum_) + (static_cast<Bits>(static_cast<__int128>(static_cast<std::int64_t>(whole))) << shift));
  }
  void add(const FixedSum& s) {
    sum_ += s.sum_;
    if (s.bad_ != 0) bad_ = s.bad_;
  }
  // [J]; throws PhysicsError where a term was out of range.
  double value() const {
    if (bad_ != 0)
      throw PhysicsError("energy log: a term of " + std::to_string(bad_) + " J in one step, beyond the ledger's range of 6.9e10 J",
                         "the run has gone unstable (check the time step), or it is too large for the energy log");
    return static_cast<double>(sum_) * 0x1p-90;  // exact: a power of 2, and sum_ is 0 or at least 1
  }
  // The same sum to the last unit, and the same term out of range (tests).
  bool operator==(const FixedSum& o) const { return sum_ == o.sum_ && (bad_ == o.bad_ || (bad_ != bad_ && o.bad_ != o.bad_)); }

 private:
  __int128 sum_ = 0;
  double bad_ = 0;  // the last term out of range (NaN counts: NaN != 0)
};

}  // namespace dem
