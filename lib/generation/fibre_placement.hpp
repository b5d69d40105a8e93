#pragma once
// Fibres placed at random in a sample ([stage.fibres], docs/physics.md eq. P63): each a straight
// segment with a uniformly drawn centre in the particles' bounding box, a direction uniform on the
// sphere and a length uniform in [length_min, length_max], from one seeded generator. A fibre is
// tied to every particle its segment passes through (centre closer to the segment than the
// radius), at the segment's point nearest the centre, in order along it, skipping a tie closer to
// the last one kept than half the smaller of their radii; one left with fewer than two ties
// carries nothing and is drawn again. Fibres are added until `count` are tied or
// their volume (pi d^2/4 x length) reaches volume_fraction x the box's volume.
#include <cstddef>

#include "forces/fibres.hpp"
#include "scene/scene.hpp"
#include "state/particles.hpp"

namespace dem {

struct FibrePlacement {
  std::size_t placed = 0;     // fibres tied
  std::size_t redrawn = 0;    // drawn but meeting fewer than two particles
  std::size_t ties = 0;
  double volume = 0;          // of the fibres placed [m^3]
  double box_volume = 0;      // the particles' bounding box [m^3]
};

// Appends the fibres to `out`. Throws std::runtime_error when a thousand draws in a row tie no
// fibre (fibres too short for the particles' spacing).
FibrePlacement place_fibres(const Particles& p, const FibreSpec& spec, FibreSet& out);

}  // namespace dem
