#pragma once
// Small vector types used for computing; storage is structure-of-arrays (see state/particles.hpp).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace dem {

using Vec3 = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Index = std::int64_t;  // stable particle id (never a storage slot)

}  // namespace dem
