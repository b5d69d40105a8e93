#pragma once
// A random vector for the test scenes, its three draws in a fixed order. In
// Vec3(u(rng), u(rng), u(rng)) the compiler picks the order (GCC draws z first, clang x), so such
// a scene differs between compilers; the scenes that need their contacts were tuned with GCC's.
#include "core/types.hpp"

namespace dem {

template <class Draw, class Rng>
Vec3 draw_vec(Draw& u, Rng& rng) {
  const double z = u(rng), y = u(rng), x = u(rng);
  return Vec3(x, y, z);
}

}  // namespace dem
