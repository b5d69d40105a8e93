#include "io/post_output.hpp"

#include <algorithm>
#include <iomanip>

#include "io/atomic_write.hpp"
#include "io/vtk_output.hpp"

namespace dem {

namespace {

VtkArray scalars(const char* name, std::size_t n) { return {name, 1, std::vector<double>(n)}; }

template <class T>
void put(VtkArray& a, std::size_t k, const T& v) {  // a Vec3 or a row-major Mat3
  for (int r = 0; r < v.rows(); ++r)
    for (int c = 0; c < v.cols(); ++c) a.values[k * a.components + r * v.cols() + c] = v(r, c);
}

VtkArray tensors(const char* name, const std::vector<Mat3>& t) {
  VtkArray a{name, 9, std::vector<double>(9 * t.size())};
  for (std::size_t k = 0; k < t.size(); ++k) put(a, k, t[k]);
  return a;
}

VtkArray vectors(const char* name, const std::vector<Vec3>& v) {
  VtkArray a{name, 3, std::vector<double>(3 * v.size())};
  for (std::size_t k = 0; k < v.size(); ++k) put(a, k, v[k]);
  return a;
}

void stress_columns(std::ostream& out) {
  for (const char* c : {"sxx", "sxy", "sxz", "syx", "syy", "syz", "szx", "szy", "szz"}) out << ',' << c;
  out << ",pressure,q";
}

void stress_values(std::ostream& out, const BoxAverage& r, bool kinetic) {
  const Mat3 s = kinetic ? Mat3(r.contact + r.kinetic) : r.contact;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out << ',' << s(a, b);
  out << ',' << pressure_of(s) << ',' << deviatoric_q(s);
}

}  // namespace

void write_particle_fields_vtu(const std::string& path, const Particles& p, const std::vector<std::string>& material_names,
                               const std::vector<Mat3>& stress, const std::vector<Mat3>* kinetic, const std::vector<int>& coordination,
                               const std::vector<Vec3>* u, const FragmentSet* fragments) {
  const std::size_t n = p.size();
  std::vector<VtkArray> extra;
  std::vector<Mat3> total = stress;
  if (kinetic != nullptr)
    for (std::size_t k = 0; k < n; ++k) total[k] += (*kinetic)[k];
  extra.push_back(tensors("stress", total));
  VtkArray pr = scalars("pressure", n), coord = scalars("coordination", n);
  for (std::size_t k = 0; k < n; ++k) pr.values[k] = pressure_of(total[k]), coord.values[k] = coordination[k];
  extra.push_back(std::move(pr));
  if (kinetic != nullptr) extra.push_back(tensors("kinetic_stress", *kinetic));
  extra.push_back(std::move(coord));
  if (fragments != nullptr) {
    VtkArray rank = scalars("fragment", n), size = scalars("fragment_particles", n);
    for (std::size_t k = 0; k < n; ++k) {
      rank.values[k] = fragments->of_slot[k];
      size.values[k] = static_cast<double>(fragments->fragments[fragments->of_slot[k]].particles);
    }
    extra.push_back(std::move(rank));
    extra.push_back(std::move(size));
  }
  write_particles_vtu(path, p, material_names, u, extra);
}

void write_grid_fields_vti(const std::string& path, const GridFields& g, bool kinetic) {
  const std::size_t n = g.grid.nodes();
  std::vector<VtkArray> arrays;
  arrays.push_back({"density", 1, g.density});
  arrays.push_back({"solid_fraction", 1, g.solid_fraction});
  arrays.push_back(vectors("velocity", g.velocity));
  std::vector<Mat3> total = g.contact_stress;
  if (kinetic)
    for (std::size_t k = 0; k < n; ++k) total[k] += g.kinetic_stress[k];
  VtkArray pr = scalars("pressure", n);
  for (std::size_t k = 0; k < n; ++k) pr.values[k] = pressure_of(total[k]);
  arrays.push_back(tensors("stress", total));
  total.clear();
  total.shrink_to_fit();
  arrays.push_back(std::move(pr));
  if (kinetic) arrays.push_back(tensors("kinetic_stress", g.kinetic_stress));
  if (!g.displacement.empty()) {
    arrays.push_back(vectors("displacement", g.displacement));
    arrays.push_back(tensors("displacement_gradient", g.displacement_gradient));
    std::vector<Mat3> strain(n);
    VtkArray vol = scalars("volumetric_strain", n);
    for (std::size_t k = 0; k < n; ++k) {
      strain[k] = 0.5 * (g.displacement_gradient[k] + g.displacement_gradient[k].transpose());
      vol.values[k] = strain[k].trace();
    }
    arrays.push_back(tensors("strain", strain));
    arrays.push_back(std::move(vol));
  }
  write_image_vti(path, g.grid.origin, g.grid.cell, g.grid.n.data(), arrays);
}

void write_force_chains_vtp(const std::string& path, const Particles& p, const ContactForceSet& c) {
  const std::size_t np = c.pairs(), nw = c.walls(), nc = np + nw;
  std::vector<Vec3> points(p.x);
  points.insert(points.end(), c.wall_point.begin(), c.wall_point.end());
  std::vector<long> lines(2 * nc);
  VtkArray mag = scalars("force_magnitude", nc), fn = scalars("normal_force", nc), ft = scalars("tangential_force", nc),
           force{"force", 3, std::vector<double>(3 * nc)}, wall = scalars("wall", nc), bonded = scalars("bonded", nc);
  for (std::size_t k = 0; k < nc; ++k) {
    const bool pair = k < np;
    const std::size_t w = k - np;
    const Vec3& f = pair ? c.pair_force[k] : c.wall_force[w];
    const Vec3& n = pair ? c.pair_normal[k] : c.wall_normal[w];
    lines[2 * k] = pair ? c.pair_i[k] : c.wall_i[w];
    lines[2 * k + 1] = pair ? c.pair_j[k] : static_cast<long>(p.size() + w);
    if (pair && c.periodic.any()) {
      // Across a periodic boundary: to j's image next to i, not across the sample.
      const Vec3 image = p.x[c.pair_i[k]] + c.branch(p, k);
      if (image != p.x[c.pair_j[k]]) lines[2 * k + 1] = static_cast<long>(points.size()), points.push_back(image);
    }
    const double normal = -f.dot(n);  // the force on the first end is -f_n n for a push
    mag.values[k] = f.norm();
    fn.values[k] = normal;
    ft.values[k] = (f + normal * n).norm();
    put(force, k, f);
    wall.values[k] = pair ? -1 : c.wall_index[w];
    bonded.values[k] = pair ? c.pair_bonded[k] : c.wall_bonded[w];
  }
  write_lines_vtp(path, points, lines, {}, {mag, fn, ft, force, wall, bonded});
}

void write_average_csv(const std::string& path, const std::string& title, const std::vector<BoxAverage>& rows, bool kinetic,
                       bool displacement) {
  write_text_atomically(path, [&](std::ostream& out) {
    out << "# " << title << '\n';
    out << "region,x_lo,y_lo,z_lo,x_hi,y_hi,z_hi,volume,count,mass,solid_fraction,vx,vy,vz";
    stress_columns(out);
    if (displacement) out << ",displaced,mean_ux,mean_uy,mean_uz";
    out << '\n' << std::setprecision(10);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const BoxAverage& r = rows[k];
      out << k << ',' << r.box.lo[0] << ',' << r.box.lo[1] << ',' << r.box.lo[2] << ',' << r.box.hi[0] << ',' << r.box.hi[1] << ','
          << r.box.hi[2] << ',' << r.box.volume() << ',' << r.count << ',' << r.mass << ',' << r.solid_fraction << ','
          << r.mean_velocity[0] << ',' << r.mean_velocity[1] << ',' << r.mean_velocity[2];
      stress_values(out, r, kinetic);
      if (displacement)
        out << ',' << r.displaced << ',' << r.mean_displacement[0] << ',' << r.mean_displacement[1] << ',' << r.mean_displacement[2];
      out << '\n';
    }
  });
}

void write_stress_profile_csv(const std::string& path, const std::string& title, const std::vector<BoxAverage>& rows, int axis,
                              bool kinetic) {
  write_text_atomically(path, [&](std::ostream& out) {
    const char a = static_cast<char>('x' + axis);
    out << "# " << title << '\n';
    out << a << "_centre," << a << "_lo," << a << "_hi,count,solid_fraction";
    stress_columns(out);
    out << '\n' << std::setprecision(10);
    for (const BoxAverage& r : rows) {
      out << 0.5 * (r.box.lo[axis] + r.box.hi[axis]) << ',' << r.box.lo[axis] << ',' << r.box.hi[axis] << ',' << r.count << ','
          << r.solid_fraction;
      stress_values(out, r, kinetic);
      out << '\n';
    }
  });
}

void write_fragments_csv(const std::string& path, const std::string& title, const FragmentSet& f) {
  // mass_passing of each fragment: the masses summed in order of equivalent diameter, a tie taking
  // the sum at its last member (all of equal diameter pass together).
  const std::size_t n = f.fragments.size();
  std::vector<std::size_t> by_size(n);
  for (std::size_t k = 0; k < n; ++k) by_size[k] = k;
  std::stable_sort(by_size.begin(), by_size.end(), [&](std::size_t a, std::size_t b) {
    return f.fragments[a].equivalent_diameter() < f.fragments[b].equivalent_diameter();
  });
  double total = 0;
  for (const Fragment& x : f.fragments) total += x.mass;
  std::vector<double> passing(n);
  double sum = 0;
  for (std::size_t k = 0; k < n;) {
    std::size_t e = k;
    const double d = f.fragments[by_size[k]].equivalent_diameter();
    while (e < n && f.fragments[by_size[e]].equivalent_diameter() == d) sum += f.fragments[by_size[e++]].mass;
    for (; k < e; ++k) passing[by_size[k]] = sum / total;
  }
  write_text_atomically(path, [&](std::ostream& out) {
    out << "# " << title << '\n';
    out << "rank,first_id,particles,mass,equivalent_diameter,x,y,z,mass_passing\n" << std::setprecision(10);
    for (std::size_t k = 0; k < n; ++k) {
      const Fragment& x = f.fragments[k];
      out << k << ',' << x.first_id << ',' << x.particles << ',' << x.mass << ',' << x.equivalent_diameter() << ',' << x.centre[0] << ','
          << x.centre[1] << ',' << x.centre[2] << ',' << passing[k] << '\n';
    }
  });
}

void write_displacement_profile_csv(const std::string& path, const std::string& title, const std::vector<ProfileRow>& rows, int axis) {
  write_text_atomically(path, [&](std::ostream& out) {
    const char a = static_cast<char>('x' + axis);
    out << "# " << title << '\n';
    out << a << "_centre,count,mean_ux,mean_uy,mean_uz,mean_norm_u\n";
    out.precision(10);
    for (const ProfileRow& r : rows)
      out << r.centre << ',' << r.count << ',' << r.mean_u[0] << ',' << r.mean_u[1] << ',' << r.mean_u[2] << ',' << r.mean_norm << '\n';
  });
}

}  // namespace dem
