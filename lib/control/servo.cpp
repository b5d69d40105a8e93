#include "control/servo.hpp"

#include <algorithm>
#include <cmath>

#include "contact/model_table.hpp"
#include "core/error.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

double ServoGroup::stress(const std::vector<WallLoad>& loads) const {
  double f = 0;
  for (std::size_t e : elements) f -= loads[e].force.dot(inward);
  return f / area;
}

double ServoGroup::speed(const std::vector<WallLoad>& loads, double dt, double k_max, double c_max) {
  int n = 0;
  for (std::size_t e : elements) n += loads[e].contacts;
  if (n == 0) return max_speed;
  const double error = (target - stress(loads)) * area;  // [N]
  const double u = error / (n * (k_max * dt + c_max));  // [m/s]
  const double v = gain * u + integral;
  const bool held = std::abs(v) > max_speed && (u > 0) == (v > 0);  // the limit holds it that way
  if (integral_time > 0 && !held) integral = std::clamp(integral + gain * u * dt / integral_time, -max_speed, max_speed);
  return std::clamp(v, -max_speed, max_speed);
}

Vec3 particle_centroid(const Simulation& sim) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& x : sim.particles.x) c += x;
  return c / std::max<double>(1, sim.particles.size());
}

ServoGroup servo_group(const std::vector<Wall>& walls, double t, const std::string& pattern, const Vec3& towards,
                       const Vec3* direction) {
  ServoGroup g;
  Vec3 normal = Vec3::Zero();
  for (std::size_t k = 0; k < walls.size(); ++k) {
    if (!wall_matches(walls[k].name, pattern)) continue;
    const std::vector<Vec3> v = walls[k].vertices_at(t);
    Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    if (n.dot(towards - v[0]) < 0) n = -n;  // facing the particles
    const double a = polygon_area(v);
    normal += a * n;
    g.area += a;
    g.elements.push_back(k);
  }
  if (!direction && !(normal.norm() > 0.5 * g.area))
    throw InputError("servo wall \"" + pattern + "\": its elements do not face one way; give the servo a direction");
  g.inward = direction ? direction->normalized() : normal.normalized();
  return g;
}

void servo_constants(const Simulation& sim, double& k_max, double& c_max) {
  k_max = sim.materials.max_stiffness(sim.contact_scale());
  double m_max = 0;
  for (double m : sim.particles.mass) m_max = std::max(m_max, m);
  c_max = 0;  // the largest normal dashpot against the heaviest particle (wall: m* = m_i)
  for (std::size_t a = 0; a < sim.materials.size(); ++a)
    for (std::size_t b = 0; b < sim.materials.size(); ++b) {
      const PairParams& p = sim.materials.pair(a, b);
      c_max = std::max(c_max, with_damping(p, [&](auto d) { return d.largest_normal(p, m_max, k_max); }));
    }
}

void update_areas(const Simulation& sim, std::vector<ServoGroup>& groups) {
  Container container(sim.walls, sim.time, sim.particles, sim.params.gravity);
  for (ServoGroup& g : groups) {
    g.area = 0;
    for (std::size_t e : g.elements) g.area += container.wall_area(e);
  }
}

void drive_servos(Simulation& sim, std::vector<ServoGroup>& groups, double k_max, double c_max) {
  update_areas(sim, groups);
  const std::vector<WallLoad> loads = sim.wall_loads();
  for (ServoGroup& g : groups) {
    WallMotion m;
    m.velocity = g.speed(loads, sim.dt, k_max, c_max) * g.inward;
    for (std::size_t e : g.elements) sim.walls[e].start_motion(m, sim.time);
  }
}

}  // namespace dem
