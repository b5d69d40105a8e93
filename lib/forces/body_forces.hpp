#pragma once
// Body forces: loads that act on each particle alone, from its own state and the scene's fields.
// The force loop starts a particle's net load from its weight (m g: its pair contacts are added to
// it, which saves a pass over the particles), and adds the other body forces after its contacts
// (forces/force_loop.hpp ForceBlocks), in the order of the members below, so that the order of
// every sum is fixed: the fluid's force (forces/fluid.hpp) is the first (docs/architecture.md).
#include <optional>

#include "core/types.hpp"
#include "forces/fluid.hpp"
#include "state/particles.hpp"

namespace dem {

struct BodyForces {
  BodyForces() = default;
  BodyForces(const Vec3& g, const FluidParams* f, const FluidGrains* grains = nullptr) : gravity(g), fluid_grains(grains) {
    if (f) fluid.emplace(*f);
  }
  Vec3 gravity = Vec3::Zero();  // [m/s^2] (SimParams::gravity)
  // The stage's fluid, or none (a run without one pays a test per block of particles).
  std::optional<FluidField> fluid;
  // Per particle slot, its FluidField::grain at the last void-fraction update (Simulation's).
  const FluidGrains* fluid_grains = nullptr;

  // Adds the fluid's force on particle slots [lo, hi) (fluid_grains filled) [N], four at a time
  // where simd (the same bits).
  void add_fluid(const Particles& p, long lo, long hi, LoadSum* force, bool simd) const {
    fluid->add_forces(*fluid_grains, p, gravity, lo, hi, force, simd);
  }
};

}  // namespace dem
