#pragma once
// What the force loop adds up per particle (BlockLoads): a force or a torque, padded to four
// doubles and aligned to 32 bytes, so that the four-wide law (sim/pair_law.cpp) adds a contact's
// load to a particle with one vector load, add and store, never touching another particle's
// (which another thread may be writing). The fourth double is never read. Measured against three
// doubles (one and two threads, same bits): the chute and the lattice of 10^5 6-8 % faster, the
// settle of 10^4 the same on one thread and 4 % faster on two; the integration, which reads and
// zeroes the padded loads, takes about a fifth longer.
#include "core/types.hpp"

namespace dem {

struct alignas(32) LoadSum {
  Vec3 v = Vec3::Zero();
  double unused = 0;
};

}  // namespace dem
