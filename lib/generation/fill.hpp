#pragma once
// Model generation (SPEC §9, thesis §3.3): random primary sets and tiled copies.
#include <random>
#include <vector>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// Adds spec.placed (ids first, in order), then places spec.count non-overlapping spheres at pseudo-random positions inside spec's box (random
// sequential addition). Radii from spec.size (generation/size_distribution.hpp): uniform ones drawn
// at each attempt as always; others all drawn first, then placed largest first. Materials drawn by
// fraction. Throws InputError if the box cannot hold them. Same seed, same particles.
void fill_random(Simulation& sim, const GenerationSpec& spec, std::mt19937_64& rng);

// Tiles the particles nx x ny x nz times with the given period; ids are renumbered 0..N-1 in
// tile order; velocities are kept, contact history is dropped (the copies settle again).
void tile(Simulation& sim, int nx, int ny, int nz, const Vec3& period);

// Removes the particles whose centre is inside `region` (outside it when !inside), and their
// contacts (SPEC §9 step 4: other shapes come from a box by cutting). Returns how many it removed.
std::size_t remove_particles(Simulation& sim, const Region& region, bool inside);

// Which particles have their centre inside `region`, one byte per storage slot.
std::vector<char> centres_inside(const Particles& p, const Region& region);

// Removes the particles whose slot is marked (`gone`, one byte per slot) and their contacts.
// Returns how many it removed.
std::size_t remove_marked(Simulation& sim, const std::vector<char>& gone);

// Holds in place (fixed = true: velocity and spin set to zero) or releases the particles whose
// centre is inside `region` (outside it when !inside; every particle when region is null).
// Returns how many it selected.
std::size_t set_fixed(Simulation& sim, const Region* region, bool inside, bool fixed);

// Bounding box of the spheres (centres +- radii): min, max.
std::pair<Vec3, Vec3> sphere_bounds(const Particles& p);

}  // namespace dem
