#pragma once
// Small vector types used for computing; storage is structure-of-arrays (see state/particles.hpp).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>

namespace dem {

using Vec3 = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Index = std::int64_t;  // stable particle id (never a storage slot)

// n vectors copied as one run of 3n doubles (a Vec3 is three doubles and nothing else): Eigen's
// copy, one vector at a time, took several times as long for a block's state.
static_assert(sizeof(Vec3) == 3 * sizeof(double));
inline void copy_vectors(const Vec3* from, long n, Vec3* to) {
  if (n > 0) std::memcpy(static_cast<void*>(to), static_cast<const void*>(from), static_cast<std::size_t>(n) * sizeof(Vec3));
}

}  // namespace dem
