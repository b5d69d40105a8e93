#pragma once
// A Simulation only wires the components together: particles, materials, walls, contacts, the
// force loop and the integrator. Everything here is part of the checkpoint (io/checkpoint.hpp).
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "search/linked_cells.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"
#include "walls/wall.hpp"

namespace dem {

struct SimParams {
  Vec3 gravity = Vec3(0, 0, -9.81);  // [m/s^2]
  double alpha_r = 0;                // global translational damping [1/s], eq. 2.36
  double alpha_theta = 0;            // global rotational damping [1/s], eq. 2.37
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

  // Critical time step of eq. 2.48 (without FRAC): 2 sqrt(M_min / (2 K_max)).
  double critical_time_step() const;

  double kinetic_energy() const;  // translational + rotational [J]
  std::vector<Vec3> wall_forces() const;  // force on each wall this step [N]

 private:
  void find_contacts();
  void compute_forces();
  void integrate();

  LinkedCells cells_;
  std::vector<FoundContact> found_;
  std::vector<Vec3> force_, torque_;
  std::vector<int> csr_start_, csr_entry_;  // per-particle contact lists, fixed order
};

}  // namespace dem
