#include "run/post_macro.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "io/output_paths.hpp"
#include "io/post_output.hpp"
#include "io/scene_parser.hpp"
#include "post/coarse_grain.hpp"
#include "post/contact_forces.hpp"
#include "post/displacement.hpp"
#include "post/fragments.hpp"
#include "post/kernel.hpp"
#include "run/setup.hpp"

namespace dem {

namespace {

constexpr double kMaxGridNodes = 1e8;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A checkpoint with the contact constants of the scene it was written with: the stored material
// rows lack the scene's [[pair]] entries (docs/checkpoint.md), so the stored scene text rebuilds
// them, as run-stage --restart does.
Simulation load_state(const std::string& path) {
  Simulation sim;
  CheckpointMeta meta;
  read_checkpoint(path, sim, meta);
  if (meta.scene_text.empty()) return sim;  // written by a program without a scene: stored materials
  Scene scene;
  try {
    scene = parse_scene(meta.scene_text, meta.scene_path);
  } catch (const InputError& e) {
    throw InputError(path + ": the scene stored in the checkpoint does not parse: " + e.what());
  }
  const std::vector<Material>& stored = sim.materials.materials();
  bool same = stored.size() == scene.materials.size();
  for (std::size_t k = 0; same && k < stored.size(); ++k) same = stored[k].name == scene.materials[k].name;
  if (!same) throw InputError(path + ": the materials stored in the checkpoint differ from those of its stored scene");
  sim.materials = MaterialTable(scene.materials, scene.mixing, scene.pairs);
  sim.params = params_from(scene);
  return sim;
}

std::string box_text(const Box& b) {
  std::ostringstream s;
  s.precision(6);
  s << "[" << b.lo[0] << " " << b.lo[1] << " " << b.lo[2] << "] to [" << b.hi[0] << " " << b.hi[1] << " " << b.hi[2] << "] m";
  return s.str();
}

}  // namespace

Box parse_region(const std::string& text) {
  const std::string prefix = "box:";
  if (text.rfind(prefix, 0) != 0) throw InputError("region \"" + text + "\": expected box:x0,y0,z0,x1,y1,z1 (metres)");
  std::vector<double> v;
  std::stringstream in(text.substr(prefix.size()));
  in.imbue(std::locale::classic());
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(x))
      throw InputError("region \"" + text + "\": \"" + item + "\" is not a finite number");
    v.push_back(x);
  }
  if (v.size() != 6) throw InputError("region \"" + text + "\": expected 6 numbers x0,y0,z0,x1,y1,z1, got " + std::to_string(v.size()));
  const Box b{Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])};
  for (int a = 0; a < 3; ++a)
    if (!(b.hi[a] > b.lo[a]))
      throw InputError("region \"" + text + "\": the upper corner must exceed the lower one along " + std::string(1, static_cast<char>('x' + a)));
  return b;
}

void check_post_options(const PostOptions& o) {
  if (o.in.empty()) throw InputError("--in is required");
  if (!o.csv.empty() && o.reference.empty()) throw InputError("--csv (displacement profile) needs --reference");
  if (!o.grid.empty() && !(o.cell > 0 && o.width > 0)) throw InputError("--grid needs --cell and --width, both positive");
  if (o.axis < 0 || o.axis > 2) throw InputError("--axis must be x, y or z");
  if (o.bins < 1) throw InputError("--bins must be at least 1");
  auto canonical = [](const std::string& f) {
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::weakly_canonical(f, ec);
    return ec ? std::filesystem::path(f) : p;
  };
  std::set<std::filesystem::path> seen;
  for (const std::string* f : {&o.reference, &o.in})
    if (!f->empty()) seen.insert(canonical(*f));
  for (const std::string* f : {&o.vtk, &o.csv, &o.stress_csv, &o.average_csv, &o.grid, &o.chains, &o.fragments}) {
    if (f->empty()) continue;
    if (!seen.insert(canonical(*f)).second)
      throw InputError("output " + *f + " is named twice, or is an input: give each output its own file");
  }
}

void post_macro(const PostOptions& o) {
  check_post_options(o);
  // Every output is checked before the reading and computing, which take minutes on large files.
  check_output_file(o.vtk, "--vtk");
  check_output_file(o.csv, "--csv");
  check_output_file(o.stress_csv, "--stress-csv");
  check_output_file(o.average_csv, "--average-csv");
  check_output_file(o.grid, "--grid");
  check_output_file(o.chains, "--chains");
  check_output_file(o.fragments, "--fragments");
  const auto t0 = Clock::now();
  const Simulation cur = load_state(o.in);
  const Particles& p = cur.particles;
  if (p.size() == 0) throw InputError(o.in + ": the checkpoint holds no particles: nothing to post-process");
  const std::vector<Box> regions = o.regions.empty() ? std::vector<Box>{sphere_box(p)} : o.regions;
  const Box& main_box = regions.front();

  // Everything is computed before anything is written: a failure leaves no output behind.
  DisplacementField d;
  double ref_time = 0;
  if (!o.reference.empty()) {
    Simulation ref;
    CheckpointMeta meta;
    read_checkpoint(o.reference, ref, meta);
    d = displacement_by_id(ref.particles, p, ref.periodic, cur.periodic);
    ref_time = ref.time;
  }
  const std::vector<Vec3>* u = o.reference.empty() ? nullptr : &d.u;
  const double read_seconds = seconds_since(t0);

  GridSpec grid;
  if (!o.grid.empty()) {
    grid = grid_covering(main_box, o.cell);
    if (static_cast<double>(grid.n[0]) * grid.n[1] * grid.n[2] > kMaxGridNodes) {
      std::ostringstream m;
      m << "--grid: " << grid.n[0] << " x " << grid.n[1] << " x " << grid.n[2] << " nodes over " << box_text(main_box)
        << " is more than the limit of 1e8: give a larger --cell or a smaller --region";
      throw InputError(m.str());
    }
    if (o.cell > 2 * o.width)
      std::fprintf(stderr, "post-macro: warning: --cell %g m is more than twice --width %g m: the grid samples the fields too coarsely to "
                           "show everything the kernel resolves\n", o.cell, o.width);
  }

  // Fragments: when asked, and in the particles' file of a state that holds bonds.
  const bool fragments_wanted = !o.fragments.empty() || (!o.vtk.empty() && cur.has_bonds());
  const bool stress_wanted = !o.vtk.empty() || !o.stress_csv.empty() || !o.average_csv.empty() || !o.grid.empty() || !o.chains.empty() ||
                             o.csv.empty() || fragments_wanted;
  ContactForceSet forces;
  ParticleStress ps;
  auto t = Clock::now();
  if (stress_wanted) forces = contact_forces_at_state(cur);
  const double force_seconds = seconds_since(t);
  t = Clock::now();
  if (stress_wanted) ps = particle_stress(p, forces);
  FibreBranches fibre_part;  // the fibres' segments (eq. P64), their tensions at this state
  if (stress_wanted && !cur.fibres.empty()) {
    FibreSet fibres = cur.fibres;
    compute_fibre_tensions(fibres, p, cur.periodic);
    add_fibre_stress(p, cur.periodic, fibres, ps);
    fibre_part = fibre_branches(p, cur.periodic, fibres);
  }
  FragmentSet fragments;
  if (fragments_wanted) fragments = find_fragments(p, forces);
  const double stress_seconds = seconds_since(t);
  t = Clock::now();
  GridFields fields;
  if (!o.grid.empty()) fields = coarse_grain(p, forces, u, grid, o.width, fibre_part.size() > 0 ? &fibre_part : nullptr);
  const double grid_seconds = seconds_since(t);
  t = Clock::now();

  std::ostringstream when;
  when << o.in << " (t = " << cur.time << " s)";
  const std::string part = o.kinetic ? "contact + kinetic stress" : "contact stress (no kinetic part)";
  const std::string units = "Pa, tension positive (pressure = -trace/3 and q positive)";

  std::vector<std::string> names;
  for (const Material& m : cur.materials.materials()) names.push_back(m.name);
  if (!o.vtk.empty()) {
    const std::vector<Mat3> kin = o.kinetic ? particle_kinetic_stress(p) : std::vector<Mat3>{};
    write_particle_fields_vtu(o.vtk, p, names, particle_stress_tensors(p, ps), o.kinetic ? &kin : nullptr, ps.contacts, u,
                              fragments_wanted ? &fragments : nullptr);
  }
  if (!o.grid.empty()) write_grid_fields_vti(o.grid, fields, o.kinetic);
  if (!o.chains.empty()) write_force_chains_vtp(o.chains, p, forces);
  if (!o.average_csv.empty()) {
    std::vector<BoxAverage> rows;
    for (const Box& b : regions) rows.push_back(box_average(p, ps, b, u));
    write_average_csv(o.average_csv, "box averages of " + when.str() + ": " + part + " in " + units + "; lengths m, mass kg, velocity m/s",
                      rows, o.kinetic, u != nullptr);
  }
  if (!o.stress_csv.empty()) {
    const std::vector<BoxAverage> rows = stress_profile(p, ps, main_box, o.axis, o.bins, u);
    write_stress_profile_csv(o.stress_csv, "stress profile of " + when.str() + " over " + box_text(main_box) + ": " + part + " in " + units,
                             rows, o.axis, o.kinetic);
  }
  if (!o.fragments.empty())
    write_fragments_csv(o.fragments, "fragments of " + when.str() + ": groups of particles joined by intact bonds; mass kg, lengths m", fragments);
  if (!o.csv.empty()) {
    std::ostringstream title;
    title << "displacement profile from " << o.reference << " (t = " << ref_time << " s) to " << o.in << " (t = " << cur.time
          << " s); lengths in m";
    write_displacement_profile_csv(o.csv, title.str(), displacement_profile(p, d, o.axis, o.bins), o.axis);
  }

  const double write_seconds = seconds_since(t);
  if (o.quiet) return;  // warnings and errors (stderr) still come

  if (u != nullptr)
    std::printf("post-macro: %zu particles matched by id, %zu removed since the reference, %zu new; t = %.6g s -> %.6g s\n", d.matched,
                d.removed, d.added, ref_time, cur.time);
  if (stress_wanted) {
    const BoxAverage a = box_average(p, ps, main_box);
    const Mat3 s = o.kinetic ? Mat3(a.contact + a.kinetic) : a.contact;
    std::printf("post-macro: %zu particles, %zu particle contacts, %zu wall contacts; %s over %s: pressure %.6g Pa, q %.6g Pa, "
                "szz %.6g Pa\n",
                p.size(), forces.pairs(), forces.walls(), part.c_str(), box_text(main_box).c_str(), pressure_of(s) + 0.0, deviatoric_q(s),
                s(2, 2) + 0.0);  // + 0.0: no "-0"
  }
  if (fragments_wanted && !fragments.fragments.empty()) {
    const Fragment& big = fragments.fragments.front();
    double total = 0;
    for (const Fragment& f : fragments.fragments) total += f.mass;
    std::printf("post-macro: %zu fragments (%zu intact bonds); the largest holds %zu particles, %.4g %% of the mass\n",
                fragments.fragments.size(), fragments.intact_bonds, big.particles, 100 * big.mass / total);
  }
  if (!o.grid.empty())
    std::printf("post-macro: grid %ld x %ld x %ld nodes, cell %g m, kernel width %g m (Lucy, support radius %g m)\n", grid.n[0], grid.n[1],
                grid.n[2], o.cell, o.width, LucyKernel(o.width).cutoff());
  std::printf("post-macro: times [s]: reading %.2f, contact forces %.2f, particle stress %.2f, grid %.2f, writing %.2f; total %.2f\n",
              read_seconds, force_seconds, stress_seconds, grid_seconds, write_seconds, seconds_since(t0));
}

}  // namespace dem
