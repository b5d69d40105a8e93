#pragma once
// Turning a scene into a Simulation, and fitting a checkpoint's state to a (possibly different)
// scene at the start of a stage.
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// Body forces, global damping, skin and overlap limit of a scene ([simulation]).
SimParams params_from(const Scene& scene);

// Materials, walls (at rest) and body forces from the scene; no particles.
Simulation simulation_from_scene(const Scene& scene);

// Continue from a checkpoint's state under `scene`: particle materials are matched by name and
// masses follow the scene's densities; with WallPositions::FromCheckpoint a wall keeps its
// checkpoint position when the scene has a wall of the same name (a compacted container stays
// compacted), otherwise walls are placed as the scene says. Wall contact history follows the walls
// by name.
enum class WallPositions { FromCheckpoint, FromScene };
void adopt_scene(Simulation& sim, const Scene& scene, WallPositions walls = WallPositions::FromCheckpoint);

// Time step from eq. 2.48 (FRAC x critical) or the scene's forced value; throws InputError when a
// given time step exceeds the critical one and is not forced.
double choose_time_step(const Simulation& sim, const SimulationSpec& spec);

}  // namespace dem
