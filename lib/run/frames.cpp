#include "run/frames.hpp"

#include <cstdio>

#include "io/vtk_output.hpp"

namespace dem {

namespace {
std::string frame_name(const std::string& stage, const char* what, std::size_t k, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06zu.%s", what, k, ext);
  return stage + "/" + buf;
}
}  // namespace

void FrameWriter::write(const Simulation& sim, const std::vector<double>& times) const {
  if (dir_.empty() || times.empty()) return;
  const std::size_t k = times.size() - 1;
  std::vector<std::string> names;
  for (const Material& m : sim.materials.materials()) names.push_back(m.name);
  // In id order (Particles::slots_by_id): a frame does not depend on the storage order.
  const std::vector<std::size_t> by_id = sim.particles.slots_by_id();
  Particles p = sim.particles;
  p.reorder(by_id);
  std::vector<Vec3> disp(by_id.size());
  for (std::size_t i = 0; i < disp.size(); ++i) disp[i] = sim.unwrapped_position(by_id[i]) - p.x_ref[i];
  write_particles_vtu(dir_ + "/" + frame_name(stage_, "particles", k, "vtu"), p, names, &disp);
  write_walls_vtp(dir_ + "/" + frame_name(stage_, "walls", k, "vtp"), sim.walls, sim.time);
  std::vector<PvdEntry> particles, walls;
  for (std::size_t f = 0; f < times.size(); ++f) {
    particles.push_back({times[f], frame_name(stage_, "particles", f, "vtu")});
    walls.push_back({times[f], frame_name(stage_, "walls", f, "vtp")});
  }
  write_pvd(dir_ + "/" + stage_ + "_particles.pvd", particles);
  write_pvd(dir_ + "/" + stage_ + "_walls.pvd", walls);
}

}  // namespace dem
