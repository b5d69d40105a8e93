#include "run/frames.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <set>
#include <utility>

#include "core/error.hpp"
#include "io/vtk_output.hpp"

namespace fs = std::filesystem;

namespace dem {

namespace {
std::string frame_name(const std::string& stage, const char* what, std::size_t k, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06zu.%s", what, k, ext);
  return stage + "/" + buf;
}

// particles_NNNNNN.vtu, walls_NNNNNN.vtp or fibres_NNNNNN.vtp (6 digits or more), or its temporary (.tmp): the files
// of a series, the only ones commit() and discard() remove.
bool series_file(const std::string& name) {
  std::string n = name;
  if (n.size() > 4 && n.compare(n.size() - 4, 4, ".tmp") == 0) n.resize(n.size() - 4);
  for (const auto& [prefix, ext] : {std::pair<std::string, std::string>{"particles_", ".vtu"}, {"walls_", ".vtp"}, {"fibres_", ".vtp"}}) {
    if (n.size() < prefix.size() + 6 + ext.size() || n.compare(0, prefix.size(), prefix) != 0 ||
        n.compare(n.size() - ext.size(), ext.size(), ext) != 0)
      continue;
    bool digits = true;
    for (std::size_t k = prefix.size(); k < n.size() - ext.size(); ++k) digits = digits && std::isdigit(static_cast<unsigned char>(n[k]));
    if (digits) return true;
  }
  return false;
}

std::vector<fs::path> series_files(const fs::path& folder) {
  std::vector<fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return found;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file(ec) && series_file(e.path().filename().string())) found.push_back(e.path());
  return found;
}

void remove_file(const fs::path& p) {
  std::error_code ec;
  fs::remove(p, ec);
  if (ec) throw IoError(p.string() + ": cannot remove: " + ec.message());
}

void move_into_place(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw IoError(to.string() + ": cannot move the frame " + from.string() + " into place: " + ec.message());
}
}  // namespace

FrameWriter::FrameWriter(std::string dir, std::string stage)
    : dir_(std::move(dir)), stage_(std::move(stage)), staging_(dir_.empty() ? "" : dir_ + "/" + stage_ + ".partial") {}

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
  write_particles_vtu(staging_ + "/" + frame_name(stage_, "particles", k, "vtu"), p, names, &disp);
  write_walls_vtp(staging_ + "/" + frame_name(stage_, "walls", k, "vtp"), sim.walls, sim.time);
  std::vector<PvdEntry> particles, walls;
  for (std::size_t f = 0; f < times.size(); ++f) {
    particles.push_back({times[f], frame_name(stage_, "particles", f, "vtu")});
    walls.push_back({times[f], frame_name(stage_, "walls", f, "vtp")});
  }
  write_pvd(staging_ + "/" + stage_ + "_particles.pvd", particles);
  write_pvd(staging_ + "/" + stage_ + "_walls.pvd", walls);
  if (!sim.fibres.empty()) {  // placed at the stage start: every frame of the stage has them
    write_fibres_vtp(staging_ + "/" + frame_name(stage_, "fibres", k, "vtp"), sim.particles, sim.periodic, sim.fibres);
    std::vector<PvdEntry> fibres;
    for (std::size_t f = 0; f < times.size(); ++f) fibres.push_back({times[f], frame_name(stage_, "fibres", f, "vtp")});
    write_pvd(staging_ + "/" + stage_ + "_fibres.pvd", fibres);
  }
}

void FrameWriter::discard() const {
  if (dir_.empty()) return;
  const fs::path staging(staging_);
  for (const fs::path& f : series_files(staging / stage_)) remove_file(f);
  for (const char* pvd : {"_particles.pvd", "_walls.pvd", "_fibres.pvd", "_particles.pvd.tmp", "_walls.pvd.tmp", "_fibres.pvd.tmp"}) {
    std::error_code ec;
    fs::remove(staging / (stage_ + pvd), ec);
  }
  std::error_code ec;  // the folders go only if empty: never another file
  fs::remove(staging / stage_, ec);
  fs::remove(staging, ec);
}

void FrameWriter::commit(std::size_t frames) const {
  if (dir_.empty()) return;
  const fs::path dir(dir_), staging(staging_);
  std::error_code ec;
  fs::create_directories(dir / stage_, ec);
  if (ec) throw IoError((dir / stage_).string() + ": cannot create the folder for the frames: " + ec.message());
  // Frames first, then the stale ones, then the series files: a run killed in between leaves the
  // staged rest, which a restart completes and commits again.
  std::set<std::string> kept;
  for (std::size_t k = 0; k < frames; ++k)
    for (const auto& [what, ext] : {std::pair<const char*, const char*>{"particles", "vtu"}, {"walls", "vtp"}, {"fibres", "vtp"}}) {
      const std::string name = frame_name(stage_, what, k, ext);
      kept.insert(fs::path(name).filename().string());
      if (fs::exists(staging / name, ec)) move_into_place(staging / name, dir / name);
    }
  for (const fs::path& f : series_files(dir / stage_))
    if (!kept.count(f.filename().string())) remove_file(f);
  for (const char* pvd : {"_particles.pvd", "_walls.pvd", "_fibres.pvd"})
    if (fs::exists(staging / (stage_ + pvd), ec)) move_into_place(staging / (stage_ + pvd), dir / (stage_ + pvd));
  discard();  // what is left: temporaries of a killed run
}

}  // namespace dem
