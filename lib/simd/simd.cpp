#include "simd/simd.hpp"

#include <atomic>
#include <cstdlib>
#include <string_view>

namespace dem {

namespace {
// DEM_SIMD=off in the environment runs the plain loops (the same bits, slower): to compare, or to
// rule the four-wide loops out when hunting a problem.
bool wanted_by_environment() {
  const char* v = std::getenv("DEM_SIMD");
  return !(v && std::string_view(v) == "off");
}
std::atomic<bool> simd_wanted{wanted_by_environment()};
}  // namespace

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
