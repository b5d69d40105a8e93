#pragma once
// Servo-controlled walls (SPEC §3): a group of wall elements translates along one direction so as
// to hold a target normal stress. Used by `compact` (one group per wall) and by `[[stage.servo]]`.
#include <cstddef>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "walls/container.hpp"
#include "walls/wall.hpp"

namespace dem {

class Simulation;
struct WallLoad;

struct ServoGroup {
  std::vector<std::size_t> elements;  // wall indices moved together
  Vec3 inward = Vec3::UnitZ();        // unit direction in which the group compresses the sample
  double area = 0;                    // the elements' area in contact with the sample [m^2]: their
                                      // polygons' area at first, then their area inside the container
                                      // now (update_areas)
  double target = 0;                  // target normal stress [Pa], compression positive
  double max_speed = 0;               // [m/s]
  double gain = 0.2;                  // fraction of the force error corrected per step
  double integral_time = 0;           // T_i of the integral action [s]; 0 = proportional only
  double integral = 0;                // the integral action's velocity now [m/s] (a periodic
                                      // checkpoint holds it: RunInfo::servo_integral)

  // Mean normal stress the particles exert on the group: -sum F . inward / area [Pa]
  // (`loads`: Simulation::wall_loads()).
  double stress(const std::vector<WallLoad>& loads) const;
  // Velocity along `inward` for the next step, and the integral action advanced by dt.
  // Proportional part: a velocity change dv changes the group's force at once by C dv (dashpots)
  // and by K v dt per step (springs), with K = n k_max and C = n c_max over its n contacts; with
  // u = force error / (K dt + C), the velocity that would close the whole error in one step,
  // `gain` u corrects about `gain` of the error per step (0.2 without chattering). Integral part
  // (PI, integral_time > 0): integral += gain u dt / T_i, so that a steady change of the sample
  // (a side wall pushing in, a bed compacting), which leaves the proportional servo an error
  // proportional to its rate / gain, is followed without one. The integral only grows while the
  // speed limit does not hold the output in the same direction, and stays within ±max_speed
  // (anti-windup). A group that touches nothing approaches at full speed, its integral unchanged.
  double speed(const std::vector<WallLoad>& loads, double dt, double k_max, double c_max);
};

// The walls whose names match `pattern` (a wall or group name), at time t, with their total area
// and the area-weighted normal, each element's normal turned towards `towards` (or `direction` if
// given). Throws InputError if the elements do not face one way.
ServoGroup servo_group(const std::vector<Wall>& walls, double t, const std::string& pattern, const Vec3& towards,
                       const Vec3* direction = nullptr);

// The centroid of the particles' centres (the side a servo wall pushes towards).
Vec3 particle_centroid(const Simulation& sim);

// The largest stiffness and the largest wall dashpot c = 2 gamma sqrt(m k) (eq. 2.27-2.28, wall:
// m* = m_i) of a simulation: the servo's estimate of a contact's response.
void servo_constants(const Simulation& sim, double& k_max, double& c_max);

// Sets each group's area to the sum of its elements' areas inside the container of the particles
// now (Container::wall_area): a lid between side walls that have moved in presses only on the
// cross-section between them, not on its whole quad. From the walls' and particles' current
// positions only, so a resumed run computes the same bits.
void update_areas(const Simulation& sim, std::vector<ServoGroup>& groups);

// Updates the groups' areas, then sets each group's elements to translate at its servo speed along
// `inward` from now.
void drive_servos(Simulation& sim, std::vector<ServoGroup>& groups, double k_max, double c_max);

}  // namespace dem
