#pragma once
// Many terms added to an exact sum (core/fixed_sum.hpp) in one pass, four at a time where the
// four-wide loops run (simd.hpp): the same bits as adding them one by one, with additions and
// roundings of doubles in place of a 128-bit add per term (bench/results/design.md).
#include "core/fixed_sum.hpp"

namespace dem {

// s.add(x[k]) for each k in [0, n): the same sum, and the same term out of range where one is.
void add_all(FixedSum& s, const double* x, long n);

// How many terms a loop gathers before each add_all: its arrays stay on the stack and in cache.
constexpr long kTermRun = 256;

}  // namespace dem
