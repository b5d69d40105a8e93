#pragma once
// Insertion over time (`[[stage.insert]]`, docs/scene.md): particles poured into a region during a
// stage at a count or mass rate, never overlapping a particle or a wall. Every draw of particle i of
// a group comes from (seed, i) and the step, so what is inserted depends only on the state, the step
// and the count inserted so far: a run resumed from a checkpoint that records the counts inserts
// the same particles, to the bit, as an uninterrupted one.
#include <cstdint>
#include <string>
#include <vector>

#include "generation/size_distribution.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// A region's bounding box, for drawing positions by rejection; false when it has none
// (half-space, cylinder of infinite length).
bool region_bounds(const Region& r, Vec3& lo, Vec3& hi);

// Whether a sphere of radius a at x lies in the region: wholly inside a box, sphere or cylinder;
// its centre inside a mesh.
bool sphere_in_region(const Region& r, const Vec3& x, double a);

class InsertGroup {
 public:
  // `count` particles inserted so far and `deferred` misses (from a checkpoint, or 0).
  InsertGroup(const InsertSpec& spec, const MaterialTable& materials, std::int64_t count = 0, std::int64_t deferred = 0);

  // Particle i's radius, material and mass: from (seed, i) alone.
  struct Draw {
    double radius = 0, mass = 0;
    int material = 0;
  };
  Draw draw(std::int64_t i) const;

  // How many of this group's particles are due at `stage_time` [s] (rate, window and total).
  // Particle i is due when amount(i) <= rate x (min(stage_time, end) - start) and amount(i) < total.
  bool due(std::int64_t i, double stage_time) const;

  const InsertSpec& spec() const { return spec_; }
  std::int64_t count() const { return count_; }        // inserted so far
  std::int64_t deferred() const { return deferred_; }   // particle-events that found no room
  double placed_amount() const { return amount_; }      // count or mass [kg] inserted so far
  void placed(const Draw& d);                           // particle count() was inserted
  void missed() { ++deferred_; }

 private:
  double amount_of(const Draw& d) const { return spec_.rate_kind == InsertSpec::Rate::Mass ? d.mass : 1.0; }

  InsertSpec spec_;
  RadiusSampler sizes_;
  std::vector<double> density_;
  std::int64_t count_ = 0, deferred_ = 0;
  double amount_ = 0;  // summed particle by particle in index order (the same bits after a restart)
};

// One insertion event of every group at the simulation's time and step, when
// (stage_step % spec.every) == 0: the particles due are drawn and placed in index order; a particle
// that finds no free position in spec.attempts tries is deferred with all after it to a later event.
// New ids continue from the largest present. Returns how many particles were inserted (0: the
// contact lists are untouched).
std::size_t insert_due(Simulation& sim, std::vector<InsertGroup>& groups, std::int64_t stage_step, double stage_time);

// What a stage's groups did: "insert[0]: 120 particles, 0.012 kg; 3 deferred; 0 due not inserted".
std::string insert_report(const std::vector<InsertGroup>& groups, double stage_time);

}  // namespace dem
