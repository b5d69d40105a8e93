#pragma once
// Many terms added to an exact sum (core/fixed_sum.hpp) in one pass, four at a time where the
// four-wide loops run (simd.hpp): the same bits as adding them one by one, which the energy log's
// per-particle work did at a cost of a fifth of its step (bench/results/design.md).
#include "core/fixed_sum.hpp"

namespace dem {

// s.add(x[k]) for each k in [0, n): the same sum, and the same term out of range where one is.
void add_all(FixedSum& s, const double* x, long n);

}  // namespace dem
