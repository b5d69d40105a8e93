#pragma once
// Turning a scene into a Simulation, and fitting a checkpoint's state to a (possibly different)
// scene at the start of a stage.
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The size below which the tools step on one thread (SimParams::parallel_min_particles), unless
// the user chose the thread count: --threads (choose_threads) or OMP_NUM_THREADS.
constexpr long kParallelMinParticles = 2000;
void choose_threads(int threads);  // the tools' --threads N (0: not given), as given
bool threads_chosen();

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

// A checkpoint from another scene shows as particles outside the scene's walls. Checked where the
// inside is certain: closed boxes (all six faces NAME.xmin ... NAME.zmax; faces across a periodic
// axis skipped); open boxes (particles may leave through the opening), meshes (a cylinder may be a
// drum or a pillar) and polygons are not. A particle lies outside when its centre is more than its
// radius beyond a face. Outside a box as the walls stand now (as adopt_scene placed them): InputError
// naming `checkpoint`, the scene, the box, the face and a particle. Inside those but outside a box
// as the scene gives it (the checkpoint's box of the same name was kept): a warning on stderr.
void check_inside_walls(const Simulation& sim, const Scene& scene, const std::string& checkpoint);

// Time step from eq. 2.48 (FRAC x critical) or the scene's forced value; throws InputError when a
// given time step exceeds the critical one and is not forced.
double choose_time_step(const Simulation& sim, const SimulationSpec& spec);

}  // namespace dem
