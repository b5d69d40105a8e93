#include "run/wall_log.hpp"

namespace dem {

WallGroups wall_groups(const std::vector<Wall>& walls) {
  WallGroups out;
  std::vector<std::string>& names = out.names;
  for (const Wall& w : walls) {
    // Mesh elements NAME.0, NAME.1, ... make one wall NAME; box faces (box.zmax) are walls of their own.
    const std::size_t dot = w.name.rfind('.');
    const bool element = dot != std::string::npos && dot + 1 < w.name.size() &&
                         w.name.find_first_not_of("0123456789", dot + 1) == std::string::npos;
    const std::string name = element ? w.name.substr(0, dot) : w.name;
    std::size_t g = 0;
    while (g < names.size() && names[g] != name) ++g;
    if (g == names.size()) names.push_back(name);
    out.group_of.push_back(static_cast<int>(g));
  }
  return out;
}

WallLog::WallLog(const std::string& path, const std::vector<Wall>& walls, std::int64_t every, std::int64_t resume_step)
    : csv_(path, "step,time_s,wall,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm,contacts,cx_m,cy_m,cz_m\n", "wall force log", resume_step),
      every_(every > 0 ? every : 1), groups_(wall_groups(walls)) {}

void WallLog::record(const Simulation& sim, std::int64_t steps_done, bool last) {
  if (!csv_.active() || (steps_done % every_ != 0 && !last)) return;
  const std::vector<WallLoad> loads = sim.wall_loads(true);
  const std::vector<WallGeometry>& geometry = sim.wall_geometry();
  std::vector<WallLoad> sum(groups_.names.size());
  // The wall's position: the mean of its elements' vertices where the forces were computed (a
  // box face's centre), so that a sample's size follows from two opposite faces.
  std::vector<Vec3> vertex_sum(groups_.names.size(), Vec3::Zero());
  std::vector<int> vertex_count(groups_.names.size(), 0);
  for (std::size_t e = 0; e < loads.size(); ++e) {
    const int g = groups_.group_of[e];
    WallLoad& s = sum[g];
    s.force += loads[e].force;
    s.torque += loads[e].torque;
    s.contacts += loads[e].contacts;
    for (int v = 0; v < geometry[e].count; ++v) vertex_sum[g] += geometry[e].vertices[v];
    vertex_count[g] += geometry[e].count;
  }
  for (std::size_t g = 0; g < groups_.names.size(); ++g) {
    const WallLoad& s = sum[g];
    const Vec3 c = vertex_count[g] > 0 ? Vec3(vertex_sum[g] / vertex_count[g]) : Vec3::Zero();
    std::fprintf(csv_.file(), "%lld,%.12g,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%.12g,%.12g,%.12g\n", static_cast<long long>(sim.step),
                 sim.time, groups_.names[g].c_str(), s.force.x(), s.force.y(), s.force.z(), s.torque.x(), s.torque.y(), s.torque.z(),
                 s.contacts, c.x(), c.y(), c.z());
  }
  csv_.flush();
}

}  // namespace dem
