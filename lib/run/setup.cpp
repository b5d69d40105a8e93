#include "run/setup.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <string>
#include <unordered_map>
#include <cmath>
#include <numbers>
#include <iostream>
#include <sstream>

#include <omp.h>

#include "core/error.hpp"

namespace dem {

namespace {
bool threads_given = false;  // choose_threads
}  // namespace

void choose_threads(int threads) {
  if (threads > 0) omp_set_num_threads(threads), threads_given = true;
}

bool threads_chosen() { return threads_given || std::getenv("OMP_NUM_THREADS") != nullptr; }

SimParams params_from(const Scene& scene) {
  SimParams p;
  p.gravity = scene.simulation.gravity;
  p.alpha_r = scene.simulation.alpha_r;
  p.alpha_theta = scene.simulation.alpha_theta;
  p.skin = scene.simulation.skin;
  p.max_overlap = scene.simulation.max_overlap;
  p.max_energy_gain = scene.simulation.max_energy_gain;
  p.sort_every = scene.simulation.sort_every;
  // Small scenes step on one thread unless the user chose the thread count: below about 2,000
  // spheres two threads are slower than one (bench/results/scaling.md "Small scenes").
  p.parallel_min_particles = threads_chosen() ? 0 : kParallelMinParticles;
  return p;
}

Simulation simulation_from_scene(const Scene& scene) {
  Simulation sim;
  sim.materials = MaterialTable(scene.materials, scene.mixing, scene.pairs);
  for (const WallSpec& w : scene.walls) sim.walls.push_back(Wall{w.name, w.material, w.vertices, WallMotion{}});
  sim.params = params_from(scene);
  sim.periodic = scene.simulation.periodic;
  return sim;
}

void adopt_scene(Simulation& sim, const Scene& scene, WallPositions positions) {
  const MaterialTable old_materials = sim.materials;
  sim.materials = MaterialTable(scene.materials, scene.mixing, scene.pairs);
  std::vector<int> remap(old_materials.size(), -1);
  for (std::size_t k = 0; k < old_materials.size(); ++k) remap[k] = sim.materials.index_of(old_materials.materials()[k].name);
  Particles& p = sim.particles;
  for (std::size_t k = 0; k < p.size(); ++k) {
    int& m = p.material[k];
    if (remap[m] < 0)
      throw InputError(scene.path + ": the checkpoint's particles use material \"" + old_materials.materials()[m].name +
                       "\", which this scene does not define");
    m = remap[m];
    p.mass[k] = sphere_mass(scene.materials[m].density, p.radius[k]);
  }

  std::vector<Wall> walls;
  std::vector<int> wall_remap(sim.walls.size(), -1);
  std::unordered_map<std::string, std::size_t> by_name;  // meshes have many elements: no quadratic search
  for (std::size_t k = 0; k < sim.walls.size(); ++k) by_name.emplace(sim.walls[k].name, k);
  for (const WallSpec& spec : scene.walls) {
    Wall w{spec.name, spec.material, spec.vertices, WallMotion{}};
    if (const auto it = by_name.find(spec.name); it != by_name.end()) {
      if (positions == WallPositions::FromCheckpoint) w.base = sim.walls[it->second].vertices_at(sim.time);  // where the previous stage left it
      wall_remap[it->second] = static_cast<int>(walls.size());
    }
    walls.push_back(std::move(w));
  }
  sim.walls = std::move(walls);

  // Wall contact history follows the walls; contacts with walls that are gone are dropped.
  const ContactList& old = sim.wall_contacts();
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < old.size(); ++k) {
    const Index w = old.key_j[k];
    if (w >= 0 && w < static_cast<Index>(wall_remap.size()) && wall_remap[w] >= 0) order.push_back(k);
  }
  auto new_key = [&](std::size_t k) { return std::make_pair(old.key_i[k], static_cast<Index>(wall_remap[old.key_j[k]])); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return new_key(a) < new_key(b); });
  ContactList wc;
  for (std::size_t k : order) {
    wc.push_back_from(old, k);
    wc.key_j.back() = new_key(k).second;
  }
  sim.set_contacts(sim.pair_contacts(), std::move(wc));

  sim.params = params_from(scene);
  sim.set_periodic(scene.simulation.periodic);
}

namespace {

// The first closed box (all six faces NAME.xmin ... NAME.zmax among `walls`) whose faces some
// particle lies wholly beyond (its centre more than its radius outside the face's plane): the
// message says which box (`of` follows its name), face and particle, and how many; empty when none.
std::string outside_closed_boxes(const std::vector<Wall>& walls, double t, const PeriodicBox& periodic, const Particles& p,
                                 const std::string& of) {
  static const char* const kFaces[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  std::map<std::string, std::array<long, 6>> boxes;  // box name -> index of each face among the walls (-1: absent)
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const std::string& name = walls[k].name;
    const std::size_t dot = name.rfind('.');
    if (dot == std::string::npos) continue;
    for (int f = 0; f < 6; ++f)
      if (name.compare(dot + 1, std::string::npos, kFaces[f]) == 0)
        boxes.try_emplace(name.substr(0, dot), std::array<long, 6>{-1, -1, -1, -1, -1, -1}).first->second[f] = static_cast<long>(k);
  }
  for (const auto& [box, faces] : boxes) {
    if (std::find(faces.begin(), faces.end(), -1) != faces.end()) continue;  // open: particles may have left through the opening
    std::array<std::vector<Vec3>, 6> quads;
    std::array<Vec3, 6> middle;  // of each face
    for (int f = 0; f < 6; ++f) {
      quads[f] = walls[faces[f]].vertices_at(t);
      middle[f] = Vec3::Zero();
      for (const Vec3& v : quads[f]) middle[f] += v / static_cast<double>(quads[f].size());
    }
    for (int f = 0; f < 6; ++f) {
      if (periodic.axis[f / 2]) continue;  // positions are wrapped into the period along it
      const std::vector<Vec3>& q = quads[f];
      Vec3 n = (q[1] - q[0]).cross(q[2] - q[0]).normalized();
      if (n.dot(middle[f ^ 1] - q[0]) < 0) n = -n;  // into the box: towards the opposite face (a lid pressed down sits below the box's middle)
      std::size_t outside = 0, first = 0;
      for (std::size_t i = 0; i < p.size(); ++i)
        if (-n.dot(p.x[i] - q[0]) > p.radius[i] && outside++ == 0) first = i;
      if (outside == 0) continue;
      std::ostringstream m;
      const Vec3& x = p.x[first];
      m << outside << " of " << p.size() << " particles lie outside the closed box \"" << box << "\"" << of << ", beyond its face " << box
        << "." << kFaces[f] << " (e.g. particle id " << p.id[first] << " at [" << x.x() << ", " << x.y() << ", " << x.z()
        << "] m, its centre " << -n.dot(x - q[0]) << " m beyond the face)";
      return m.str();
    }
  }
  return "";
}

}  // namespace

void check_inside_walls(const Simulation& sim, const Scene& scene, const std::string& checkpoint) {
  const std::string now = outside_closed_boxes(sim.walls, sim.time, sim.periodic, sim.particles, " of " + scene.path);
  if (!now.empty())
    throw InputError(checkpoint + ": " + now + ": the checkpoint does not belong to this scene (another scene's checkpoint? Use the checkpoint of this "
                     "scene's previous step, or remove those particles with a stage action \"remove\")");
  std::vector<Wall> as_given;
  for (const WallSpec& w : scene.walls) as_given.push_back(Wall{w.name, w.material, w.vertices, {}});
  const std::string given = outside_closed_boxes(as_given, 0, sim.periodic, sim.particles, " as " + scene.path + " places it");
  if (!given.empty())
    std::cerr << "warning: " << checkpoint << ": " << given << "; the run keeps the box where the checkpoint left it, around the particles (moved by an earlier step, or "
                 "a checkpoint of another scene whose box has the same name?)\n";
}

double choose_time_step(const Simulation& sim, const SimulationSpec& spec) {
  const double critical = sim.critical_time_step();
  const double dashpot = sim.dashpot_time_step();
  if (spec.time_step == 0) {
    if (!std::isfinite(critical)) throw InputError("cannot compute the time step of docs/physics.md eq. P5: no particles or no stiffness");
    if (spec.frac * critical > dashpot) {  // only a forced FRAC above 0.5 with near-critical damping
      std::cerr << "warning: simulation.frac = " << spec.frac << " gives " << spec.frac * critical << " s, above the dashpot's limit "
                << dashpot << " s (2 m*/c_n of the lightest pair): using that\n";
      return dashpot;
    }
    return spec.frac * critical;
  }
  if (spec.time_step > critical && !spec.force_time_step) {
    std::ostringstream m;
    m << "simulation.time_step = " << spec.time_step << " s exceeds the critical time step " << critical
      << " s of docs/physics.md eq. P5 (2 sqrt(M_min / (2 K_max))); lower it, omit it for the automatic step, or set "
         "simulation.force_time_step = true";
    throw InputError(m.str());
  }
  if (spec.time_step > dashpot && !spec.force_time_step) {  // possible below eq. 2.48's step where gamma > 1/2
    std::ostringstream m;
    m << "simulation.time_step = " << spec.time_step << " s exceeds the dashpot's limit " << dashpot
      << " s (2 m*/c_n of the lightest pair: c_n dt / (2 m*) = " << spec.time_step / dashpot
      << " > 1, so a damped contact's relative velocity would flip sign every step instead of dying away; docs/contact-laws.md, "
         "\"The dashpot in time\"); lower it, omit it for the automatic step, or set simulation.force_time_step = true";
    throw InputError(m.str());
  }
  if (spec.time_step > dashpot)  // forced
    std::cerr << "warning: forced time step " << spec.time_step << " s exceeds the dashpot's limit " << dashpot
              << " s (2 m*/c_n of the lightest pair: c_n dt / (2 m*) = " << spec.time_step / dashpot
              << " > 1): a damped contact's relative velocity flips sign every step instead of dying away (docs/contact-laws.md, "
                 "\"The dashpot in time\")\n";
  if (spec.time_step > critical)
    std::cerr << "warning: forced time step " << spec.time_step << " s exceeds the critical step " << critical
              << " s of docs/physics.md eq. P5: expect an unstable run\n";
  else if (spec.time_step > 0.2 * critical)  // as frac > 0.2, which the parser refuses unless forced
    std::cerr << "warning: simulation.time_step = " << spec.time_step << " s is " << spec.time_step / critical
              << " of the critical step " << critical << " s of docs/physics.md eq. P5: above 0.2 a contact lasts fewer than 8 steps and the "
                 "results are wrong (README, \"Which FRAC buys which accuracy\")\n";
  return spec.time_step;
}

}  // namespace dem
