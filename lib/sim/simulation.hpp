#pragma once
// A Simulation only wires the components together: particles, materials, walls, contacts, the
// force loop and the integrator. Everything here is part of the checkpoint (io/checkpoint.hpp).
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "search/neighbour_list.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"
#include "walls/wall.hpp"

namespace dem {

struct SimParams {
  Vec3 gravity = Vec3(0, 0, -9.81);  // [m/s^2]
  double alpha_r = 0;                // global translational damping [1/s], eq. 2.36
  double alpha_theta = 0;            // global rotational damping [1/s], eq. 2.37
  double max_overlap = 0.5;          // stop when an overlap exceeds this fraction of the smaller radius
  double skin = 0;                   // neighbour-list skin [m]; 0 = 0.2 x mean radius. Speed only:
                                     // the contacts found do not depend on it
};

class Simulation {
 public:
  Particles particles;
  MaterialTable materials;
  std::vector<Wall> walls;
  SimParams params;
  ContactList pair_contacts;  // particle-particle
  ContactList wall_contacts;  // particle-wall (key_j = wall index)
  double time = 0;            // [s]
  double dt = 0;              // [s]
  std::int64_t step = 0;

  // One explicit step: contacts and forces at x^n with v^{n-1/2}, then eq. 2.38-2.47.
  void advance();

  // Stage action `bond`: Φ = 1 for every particle contact present now (and wall contacts if asked).
  // Returns how many contacts were bonded.
  std::size_t bond_present_contacts(bool walls_too);
  bool has_bonds() const { return has_bonds_; }
  // Call after replacing contact lists (checkpoint read): recounts bonds.
  void contacts_changed();

  // Critical time step of eq. 2.48 (without FRAC): 2 sqrt(M_min / (2 K_max)).
  double critical_time_step() const;

  double skin() const;  // the neighbour-list skin in use [m]
  std::int64_t neighbour_builds() const { return neighbours_.builds(); }

  double kinetic_energy() const;  // translational + rotational [J]
  std::vector<Vec3> wall_forces() const;  // force on each wall this step [N]
  const std::vector<WallGeometry>& wall_geometry() const { return wall_geometry_; }

 private:
  [[noreturn]] void report_overlap(double worst) const;
  void update_wall_geometry();
  void find_contacts();
  void sum_forces();
  void integrate();

  bool has_bonds_ = false;
  NeighbourList neighbours_;
  std::vector<FoundContact> found_;
  ContactList pair_scratch_, wall_scratch_;  // working storage of update_contacts
  std::vector<WallGeometry> wall_geometry_;
  std::vector<Vec3> force_, torque_;
  std::vector<int> csr_start_, csr_entry_, csr_fill_;  // per-particle contact lists, fixed order
};

}  // namespace dem
