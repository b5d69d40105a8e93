#pragma once
// VTK XML output for ParaView: particles as an unstructured grid of vertices (.vtu), walls as
// polygons (.vtp), and .pvd collections that tie frames to simulation times. Every file is written
// atomically (temporary name, then rename), so a reader never sees a half-written frame and an
// interrupted run leaves the previous version in place.
#include <string>
#include <vector>

#include "core/types.hpp"
#include "forces/fibres.hpp"
#include "io/atomic_write.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

// ensure_parent_dir and write_atomically: io/atomic_write.hpp.

// A named data array: `components` values per point or cell, tuple after tuple (a 3x3 tensor is
// 9 components, row-major: xx, xy, xz, yx, ...; ParaView shows them as a tensor).
struct VtkArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

// One vertex per particle. Point data: id (int64), radius, velocity, angular_velocity,
// material (int32 index into `material_names`, which is stored as field data "material_names"),
// and, when `displacement` is given (one vector per particle, same order), displacement and
// displacement_magnitude, then the `extra` arrays (one tuple per particle, same order). Throws
// IoError when the file cannot be written.
void write_particles_vtu(const std::string& path, const Particles& p, const std::vector<std::string>& material_names,
                         const std::vector<Vec3>* displacement = nullptr, const std::vector<VtkArray>& extra = {});

// Image data (.vti): a regular grid of dims[0] x dims[1] x dims[2] points from `origin` in steps
// of `spacing`, point data `arrays` (x fastest, then y, then z). Throws IoError when the file
// cannot be written.
void write_image_vti(const std::string& path, const Vec3& origin, double spacing, const long dims[3],
                     const std::vector<VtkArray>& arrays);

// Polydata (.vtp) of line segments between `points` (lines[2k], lines[2k+1]), with point and cell
// data. Throws IoError when the file cannot be written.
void write_lines_vtp(const std::string& path, const std::vector<Vec3>& points, const std::vector<long>& lines,
                     const std::vector<VtkArray>& point_data, const std::vector<VtkArray>& cell_data);

// One polygon per wall at its position at `time`. Cell data: wall_index, material (int32);
// field data "wall_names". Throws IoError when the file cannot be written.
void write_walls_vtp(const std::string& path, const std::vector<Wall>& walls, double time);

// Fibres as polydata (.vtp): each segment one line between its two tie points (the second at the
// first's point plus the span, so that a segment across a periodic boundary is drawn whole).
// Cell data per segment: tension [N] (of the last force computation), broken (0/1), fibre (its
// fibre's index). Throws IoError when the file cannot be written.
void write_fibres_vtp(const std::string& path, const Particles& p, const PeriodicBox& box, const FibreSet& fibres);

struct PvdEntry {
  double time;       // [s]
  std::string file;  // relative to the .pvd file
};

// ParaView collection file listing the frames of a time series. Throws IoError when the file
// cannot be written.
void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries);

}  // namespace dem
