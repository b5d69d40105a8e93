#pragma once
// VTK XML output for ParaView: particles as an unstructured grid of vertices (.vtu), walls as
// polygons (.vtp), and .pvd collections that tie frames to simulation times. Every file is written
// atomically (temporary name, then rename), so a reader never sees a half-written frame and an
// interrupted run leaves the previous version in place.
#include <string>
#include <vector>

#include "core/types.hpp"
#include "state/particles.hpp"
#include "walls/wall.hpp"

namespace dem {

// Creates the directories above `path` if missing; throws IoError naming `path` when it cannot.
void ensure_parent_dir(const std::string& path);

// One vertex per particle. Point data: id (int64), radius, velocity, angular_velocity,
// material (int32 index into `material_names`, which is stored as field data "material_names"),
// and, when `displacement` is given (one vector per particle, same order), displacement and
// displacement_magnitude. Throws IoError when the file cannot be written.
void write_particles_vtu(const std::string& path, const Particles& p, const std::vector<std::string>& material_names,
                         const std::vector<Vec3>* displacement = nullptr);

// One polygon per wall at its position at `time`. Cell data: wall_index, material (int32);
// field data "wall_names". Throws IoError when the file cannot be written.
void write_walls_vtp(const std::string& path, const std::vector<Wall>& walls, double time);

struct PvdEntry {
  double time;       // [s]
  std::string file;  // relative to the .pvd file
};

// ParaView collection file listing the frames of a time series. Throws IoError when the file
// cannot be written.
void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries);

}  // namespace dem
