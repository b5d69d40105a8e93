#include "post/post_macro.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "io/vtk_output.hpp"
#include "post/displacement.hpp"

namespace dem {

void post_macro(const PostOptions& o) {
  Simulation ref, cur;
  CheckpointMeta mr, mc;
  read_checkpoint(o.reference, ref, mr);
  read_checkpoint(o.in, cur, mc);
  const DisplacementField d = displacement_by_id(ref.particles, cur.particles);
  if (!o.vtk.empty()) {
    std::vector<std::string> names;
    for (const Material& m : cur.materials.materials()) names.push_back(m.name);
    write_particles_vtu(o.vtk, cur.particles, names, &d.u);
  }
  if (!o.csv.empty()) {
    const std::vector<ProfileRow> rows = displacement_profile(cur.particles, d, o.axis, o.bins);
    const std::string tmp = o.csv + ".tmp";
    {
      ensure_parent_dir(o.csv);
      std::ofstream out(tmp);
      const char axis = static_cast<char>('x' + o.axis);
      out << "# displacement profile from " << o.reference << " (t = " << ref.time << " s) to " << o.in << " (t = " << cur.time
          << " s); lengths in m\n";
      out << axis << "_centre,count,mean_ux,mean_uy,mean_uz,mean_norm_u\n";
      out.precision(10);
      for (const ProfileRow& r : rows)
        out << r.centre << ',' << r.count << ',' << r.mean_u[0] << ',' << r.mean_u[1] << ',' << r.mean_u[2] << ',' << r.mean_norm << '\n';
      out.flush();
      if (!out) {
        std::remove(tmp.c_str());
        throw IoError(o.csv + ": cannot write the profile table");
      }
    }
    if (std::rename(tmp.c_str(), o.csv.c_str()) != 0) throw IoError(o.csv + ": cannot rename the finished table into place");
  }
  std::printf("post-macro: %zu particles matched by id, %zu removed since the reference, %zu new; t = %.6g s -> %.6g s\n", d.matched,
              d.removed, d.added, ref.time, cur.time);
}

}  // namespace dem
