#pragma once
// The glass beads many tests place: 2500 kg/m³, kn = kt = 5e4 N/m, restitution 0.3.
#include "state/materials.hpp"

namespace dem {

inline MaterialTable glass_beads(double friction_angle_deg = 0) {
  Material m;
  m.name = "glass";
  m.density = 2500;
  m.kn = m.kt = 5e4;
  m.friction_angle = friction_angle_deg;
  m.restitution = 0.3;
  return MaterialTable({m}, {});
}

}  // namespace dem
