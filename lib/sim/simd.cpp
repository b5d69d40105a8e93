#include "sim/simd.hpp"

#include <atomic>

namespace dem {

namespace {
std::atomic<bool> simd_wanted{true};
}

bool simd_loops_available() {
#ifdef DEM_SIMD_LOOPS
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

bool simd_loops_on() { return simd_loops_available() && simd_wanted.load(std::memory_order_relaxed); }
void set_simd_loops(bool on) { simd_wanted.store(on, std::memory_order_relaxed); }

}  // namespace dem
