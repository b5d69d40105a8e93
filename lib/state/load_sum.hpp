#pragma once
// A particle's net force or torque as the force loop leaves it (forces/force_loop.hpp ForceBlocks),
// padded to four doubles and aligned to 32 bytes, so that the four-wide integration
// (integrate/motion.cpp) reads four particles' loads with aligned loads and blends. The fourth double is
// never read.
#include "core/types.hpp"

namespace dem {

struct alignas(32) LoadSum {
  Vec3 v = Vec3::Zero();
  double unused = 0;
};

}  // namespace dem
