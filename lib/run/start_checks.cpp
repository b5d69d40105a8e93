#include "run/start_checks.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

#include "forces/fluid.hpp"
#include "forces/void_fraction.hpp"
#include "walls/container.hpp"

namespace dem {

namespace {

std::string vec_text(const Vec3& v) {
  std::ostringstream s;
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string group_of(const std::string& wall) { return wall.substr(0, wall.find('.')); }

std::string percent(double share) {
  std::ostringstream s;
  s.precision(3);
  s << 100 * share << " %";
  return s.str();
}

// The walls that cross the inside of the generation box (shrunk by a hair, so that a floor on
// its face does not count): spheres are placed there without regard to walls. Returns the text of
// the finding, or "".
std::string walls_in_generation_box(const Simulation& sim, const GenerationSpec& g) {
  const Vec3 inset = 1e-6 * (g.box_max - g.box_min);
  const Vec3 lo = g.box_min + inset, hi = g.box_max - inset;
  std::vector<HalfSpace> sides;
  for (int d = 0; d < 3; ++d) {
    const Vec3 e = Vec3::Unit(d);
    sides.push_back(HalfSpace::through(lo, e));
    sides.push_back(HalfSpace::through(hi, -e));
  }
  std::map<std::string, std::size_t> crossing;  // wall group -> elements crossing
  std::string first;
  for (const Wall& w : sim.walls) {
    Polygon poly = w.vertices_at(sim.time);
    for (const HalfSpace& h : sides)
      if (!poly.empty()) poly = clip_polygon(poly, h, 0);
    if (poly.size() < 3 || !(polygon_area(poly) > 0)) continue;
    if (crossing.empty()) first = w.name;
    ++crossing[group_of(w.name)];
  }
  if (crossing.empty()) return "";
  std::ostringstream m;
  m << "the generation box " << vec_text(g.box_min) << " to " << vec_text(g.box_max) << " m is not inside the walls: ";
  std::size_t k = 0;
  for (const auto& [name, n] : crossing) m << (k++ ? ", " : "") << "wall \"" << name << "\"" << (n > 1 ? " (" + std::to_string(n) + " elements)" : "");
  m << (crossing.size() > 1 ? " cross" : " crosses") << " it (e.g. " << first
    << "), so spheres are placed across or outside the walls at step 0; put generation.box_min/box_max inside the walls (lengths in mm?)";
  return m.str();
}

struct Overlaps {
  double worst = 0;  // over the smaller radius
  std::size_t above = 0;
  std::string where;
};

// Particle-particle and particle-wall overlaps at step 0, from one force evaluation on a copy (as
// the force loop finds the contacts: linked cells, the walls' closest points).
void step0_overlaps(const Simulation& sim, double threshold, Overlaps& pairs, Overlaps& walls) {
  Simulation copy = sim;
  copy.params.max_overlap = std::numeric_limits<double>::infinity();  // measure, do not stop
  copy.params.keep_pair_results = true;
  copy.compute_forces();
  const Particles& p = copy.particles;
  const ContactList& pc = copy.pair_contacts();
  for (std::size_t k = 0; k < pc.size(); ++k) {
    const int i = pc.slot_i[k], j = pc.slot_j[k];
    if (i < 0 || j < 0) continue;
    const double r = std::min(p.radius[i], p.radius[j]);
    const double u = (p.radius[i] + p.radius[j] - copy.periodic.nearest(p.x[j] - p.x[i]).norm()) / r;
    if (u > threshold) ++pairs.above;
    if (u > pairs.worst) {
      pairs.worst = u;
      pairs.where = "particles " + std::to_string(p.id[i]) + " and " + std::to_string(p.id[j]);
    }
  }
  const ContactList& wc = copy.wall_contacts();
  const std::vector<WallGeometry>& geometry = copy.wall_geometry();
  for (std::size_t k = 0; k < wc.size(); ++k) {
    const int i = wc.slot_i[k], w = wc.slot_j[k];
    if (i < 0 || w < 0 || w >= static_cast<int>(geometry.size())) continue;
    const double u = (p.radius[i] - (closest_point(geometry[w], p.x[i]) - p.x[i]).norm()) / p.radius[i];
    if (u > threshold) ++walls.above;
    if (u > walls.worst) {
      walls.worst = u;
      walls.where = "particle " + std::to_string(p.id[i]) + " and wall " + copy.walls[w].name;
    }
  }
}

// A wall's peak speed and acceleration over its motion (upper bounds: the parts' peaks added),
// with what contributes most to them.
struct WallPace {
  double speed = 0, acceleration = 0;
  double vibration_speed = 0;  // A 2 pi f
  std::string how;
};

WallPace pace_of(const Wall& w, double t) {
  const WallMotion& m = w.motion;
  WallPace p;
  std::ostringstream how;
  if (m.velocity.norm() > 0) p.speed += m.velocity.norm(), how << "velocity " << m.velocity.norm() << " m/s; ";
  double table = 0;
  for (std::size_t k = 1; k < m.table_time.size(); ++k)
    table = std::max(table, (m.table_offset[k] - m.table_offset[k - 1]).norm() / (m.table_time[k] - m.table_time[k - 1]));
  if (table > 0) p.speed += table, how << "table up to " << table << " m/s; ";
  if (m.amplitude > 0 && m.frequency > 0) {
    const double omega = 2 * M_PI * m.frequency;
    p.vibration_speed = m.amplitude * omega;
    p.speed += p.vibration_speed;
    p.acceleration += m.amplitude * omega * omega;
    how << "vibration amplitude " << m.amplitude << " m x 2 pi x " << m.frequency << " Hz; ";
  }
  if (m.rotates()) {
    double reach = 0;  // the farthest vertex from the axis
    const Vec3 a = m.axis.normalized(), c = m.centre + m.offset(t);
    for (const Vec3& v : w.vertices_at(t)) {
      const Vec3 d = v - c;
      reach = std::max(reach, (d - d.dot(a) * a).norm());
    }
    const double omega = std::abs(m.angular_speed);
    p.speed += omega * reach;
    p.acceleration += omega * omega * reach;
    how << "rotation " << omega * 60 / (2 * M_PI) << " rpm at " << reach << " m from the axis; ";
  }
  p.how = how.str();
  if (p.how.size() >= 2) p.how.resize(p.how.size() - 2);
  return p;
}

}  // namespace

StartChecks::StartChecks(const Simulation& sim, const GenerationSpec* generation) {
  const Particles& p = sim.particles;
  if (p.size() == 0) return;
  double r_min = std::numeric_limits<double>::infinity();
  for (double r : p.radius) r_min = std::min(r_min, r);
  const double limit = sim.params.max_overlap;  // of the smaller radius
  const double threshold = kStartOverlapShare * limit;

  // Particles placed across walls, or overlapping each other, at step 0.
  Overlaps pairs, walls;
  step0_overlaps(sim, threshold, pairs, walls);
  const std::string box = generation ? walls_in_generation_box(sim, *generation) : "";
  std::ostringstream wm;
  if (walls.worst > threshold)
    wm << walls.above << " particles overlap walls at step 0 by more than " << percent(threshold) << " of their radius (the largest, "
       << percent(walls.worst) << ", " << walls.where << "; simulation.max_overlap = " << percent(limit)
       << "): particles placed across or outside the walls";
  if (!box.empty()) {
    // The cause first; the overlaps it leads to after it.
    suspects_.push_back({std::max(1.0, walls.worst / threshold) * 1.01, box + (wm.str().empty() ? "" : "; " + wm.str())});
  } else if (walls.worst > threshold) {
    wm << " (a wall's position or a checkpoint from another scene?)";
    suspects_.push_back({walls.worst / threshold, wm.str()});
  }

  // Walls that move faster than the particles can follow. A sphere of the smallest mass struck at
  // speed v by the stiffest contact overlaps by v sqrt(m_min / k_max) = v t_crit / sqrt(2) (t_crit of
  // eq. 2.48): at the speed v_absorb below that reaches simulation.max_overlap of the smallest radius.
  const double t_crit = sim.critical_time_step();
  const double v_absorb = std::isfinite(t_crit) && t_crit > 0 ? std::sqrt(2.0) * limit * r_min / t_crit : std::numeric_limits<double>::infinity();
  std::map<std::string, std::pair<WallPace, std::string>> fastest;  // per wall group: its fastest element
  for (const Wall& w : sim.walls) {
    if (!w.motion.moves()) continue;
    const WallPace pace = pace_of(w, sim.time);
    auto& f = fastest[group_of(w.name)];
    if (pace.speed > f.first.speed) f = {pace, w.name};
  }
  for (const auto& [group, fast] : fastest) {
    const WallPace& pace = fast.first;
    const double per_step = pace.speed * sim.dt / r_min;  // smallest radii per step
    const double score = std::max(per_step / kWallStepRadii, pace.speed / v_absorb);
    if (!(score > 1)) continue;
    std::ostringstream m;
    m << "wall \"" << group << "\" moves faster than the particles can follow: peak speed " << pace.speed << " m/s (" << pace.how << ")";
    if (pace.acceleration > 0) m << ", peak acceleration " << pace.acceleration / 9.81 << " g";
    m << "; it moves " << per_step << " of the smallest radius (" << r_min << " m) per step of " << sim.dt << " s (warning above "
      << kWallStepRadii << "), and a sphere it strikes overlaps it by about " << percent(pace.speed / v_absorb * limit)
      << " of its radius (simulation.max_overlap = " << percent(limit) << ")";
    if (pace.vibration_speed > 0.5 * pace.speed) m << ": vibration amplitude in mm? (m expected)";
    else m << ": lower its speed (units: m/s, m, rpm)";
    suspects_.push_back({score, m.str()});
  }

  // Bonds that hold far apart: the neighbour search lists every pair within the bonds' reach (the
  // margin of Simulation::find_contacts), so a strength far above the forces carried ("unbreakable"
  // bonds of 1e9 N reach metres) lists nearly every pair of the sample.
  const double reach = sim.materials.max_break_separation(), d_max = 2 * *std::max_element(p.radius.begin(), p.radius.end());
  if (sim.has_bonds() && reach > d_max) {
    std::ostringstream m;
    m << "bonds hold until their particles are " << reach << " m apart (a material's tensile_strength over kn, docs/physics.md eq. P11-P13), "
      << "more than the largest diameter (" << d_max << " m): the neighbour search lists every pair within that reach, which costs "
      << "time and memory; a bond meant not to break needs a tensile_strength only above the forces it carries";
    slow_.push_back(m.str());
  }

  // Particles overlapping each other at step 0.
  if (pairs.worst > threshold) {
    std::ostringstream m;
    m << "initial overlap between particles: " << pairs.above << " pairs overlap by more than " << percent(threshold)
      << " of the smaller radius at step 0, the largest " << percent(pairs.worst) << " (" << pairs.where << "; simulation.max_overlap = "
      << percent(limit) << "): the contacts push them apart violently (placed particles overlapping? copy.spacing too small?)";
    suspects_.push_back({pairs.worst / threshold, m.str()});
  }
  std::stable_sort(suspects_.begin(), suspects_.end(), [](const Suspect& a, const Suspect& b) { return a.score > b.score; });
}

void StartChecks::print(const std::string& tool) const {
  for (const Suspect& s : suspects_) std::cerr << tool << ": warning: " << s.text << "\n";
  for (const std::string& s : slow_) std::cerr << tool << ": warning: " << s << "\n";
}

void StartChecks::rethrow(const PhysicsError& e) const {
  if (suspects_.empty()) throw e;
  std::ostringstream m;
  m << (e.facts.empty() ? std::string(e.what()) : e.facts) << ". Likely causes, most likely first (checked at step 0): ";
  std::size_t k = 0;
  for (const Suspect& s : suspects_) m << "(" << ++k << ") " << s.text << "; ";
  m << "(" << ++k << ") otherwise the time step or the stiffness";
  if (e.advice.empty()) throw PhysicsError(m.str());
  throw PhysicsError(m.str(), e.advice);
}

DragRelaxation shortest_drag_relaxation(const Simulation& sim) {
  DragRelaxation out;
  const FluidParams& f = sim.params.fluid;
  const Particles& p = sim.particles;
  if (!f.on() || p.size() == 0) return out;
  std::vector<double> eps;
  VoidFractionScratch scratch;
  void_fractions(p, sim.periodic, f.void_cutoff, scratch, eps);
  const FluidField field(f);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.fixed[i]) continue;  // held: no motion to relax
    const double d = 2 * p.radius[i];
    const double w = (field.flow(field.grain(p.radius[i], eps[i]), field.pressure_gradient(p.x[i])) - p.v[i]).norm();
    // P76: the drag per unit volume D(w) w grows with w; its slope is the rate at which a change of
    // the grain's velocity along the slip is pulled back (the steepest direction), by a one-sided
    // difference of the law itself (P72).
    const double h = 1e-6 * w + 1e-12;
    const double slope = (drag_per_volume(eps[i], d, w + h, f.viscosity, f.density) * (w + h) -
                          drag_per_volume(eps[i], d, w, f.viscosity, f.density) * w) / h;
    const double tau = p.mass[i] / (4.0 / 3.0 * std::numbers::pi * p.radius[i] * p.radius[i] * p.radius[i] * slope);
    if (tau < out.tau) out = {tau, static_cast<long>(i), eps[i], w};
  }
  return out;
}

void check_drag_step(const Simulation& sim, bool forced, const std::string& stage) {
  const DragRelaxation r = shortest_drag_relaxation(sim);
  if (!(sim.dt > 2 * r.tau)) return;
  const Particles& p = sim.particles;
  std::ostringstream m;
  m << "stage " << stage << ": the time step " << sim.dt << " s exceeds the fluid drag's stability limit " << 2 * r.tau
    << " s (twice the relaxation time tau = " << r.tau << " s, docs/physics.md eq. P76-P77) of particle id " << p.id[r.slot]
    << " (radius " << p.radius[r.slot] << " m, void fraction " << r.eps << ", slip " << r.slip
    << " m/s): the drag would reverse its velocity relative to the fluid by more than it was each step and the run blows up";
  if (forced) {
    std::cerr << "warning: " << m.str() << " (simulation.force_time_step = true: running all the same)\n";
    return;
  }
  m << "; lower simulation.time_step or frac to at most " << 2 * r.tau << " s, or raise the smallest grain's size or lower "
    << "[stage.fluid] viscosity, or set simulation.force_time_step = true";
  throw InputError(m.str());
}

void print_scene_warnings(const Scene& scene, const std::string& tool) {
  for (const std::string& w : scene.warnings) std::cerr << tool << ": warning: " << w << "\n";
}

}  // namespace dem
