// post-macro: stresses and displacement fields of a checkpoint, to VTK and CSV (docs/post.md).
#include <cmath>
#include <string>

#include "run/post_macro.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app(
      "Stress (Love-Weber per particle, box averages, profiles), coarse-grained grid fields and force chains of a checkpoint, and the "
      "displacement from a reference checkpoint matched by particle id: to VTK (.vtu, .vti, .vtp) and CSV. Fields, units and the sign "
      "convention (tension positive): docs/post.md.",
      "post-macro");
  dem::PostOptions o;
  int threads = 0;
  std::string axis = "z";
  std::vector<std::string> regions;
  const CLI::Validator region_check(
      [](std::string& s) {
        try {
          dem::parse_region(s);
          return std::string();
        } catch (const dem::InputError& e) {
          return std::string(e.what());
        }
      },
      "box:x0,y0,z0,x1,y1,z1");
  const CLI::Validator positive_length(
      [](std::string& s) {
        double x = 0;
        std::size_t used = 0;
        try {
          x = std::stod(s, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        return used == s.size() && std::isfinite(x) && x > 0 ? std::string() : "must be a positive length in metres, got " + s;
      },
      "METRES");
  app.add_option("--in", o.in, "checkpoint to post-process (HDF5)")->required()->check(CLI::ExistingFile);
  auto* ref = app.add_option("--reference", o.reference, "reference checkpoint for displacements, particles matched by id (HDF5)")
                  ->check(CLI::ExistingFile);
  app.add_option("--vtk", o.vtk, "particles with stress tensor, pressure, coordination (and displacement with --reference) (.vtu)");
  app.add_option("--csv", o.csv, "displacement profile along --axis (.csv); needs --reference")->needs(ref);
  app.add_option("--stress-csv", o.stress_csv, "stress profile along --axis in --bins slabs of the first region (.csv)");
  app.add_option("--average-csv", o.average_csv, "stress, solid fraction, velocity (and displacement) averaged over each region (.csv)");
  auto* grid = app.add_option("--grid", o.grid, "coarse-grained fields on a grid over the first region (.vti); needs --cell and --width");
  auto* cell = app.add_option("--cell", o.cell, "grid spacing [m]")->check(positive_length)->needs(grid);
  auto* width = app.add_option("--width", o.width, "kernel width w [m]: standard deviation of Lucy's kernel along each axis (support radius 3.46 w)")
                    ->check(positive_length)
                    ->needs(grid);
  grid->needs(cell)->needs(width);
  app.add_option("--chains", o.chains, "force chains: one line per contact with its force (.vtp)");
  app.add_option("--fragments", o.fragments,
                 "fragments: the groups of particles joined by intact bonds, one row each with its mass, equivalent diameter and "
                 "the mass passing (.csv)");
  app.add_option("--region", regions,
                 "averaging box box:x0,y0,z0,x1,y1,z1 [m], repeatable; the first also bounds the profile and the grid (default: the "
                 "bounding box of the spheres)")
      ->check(region_check)
      ->take_all();
  app.add_flag("--kinetic,!--no-kinetic", o.kinetic, "add the kinetic stress -sum m v'v' / V to the contact stress (default: contact only)");
  app.add_option("--axis", axis, "profile axis")->check(CLI::IsMember({"x", "y", "z"}));
  app.add_option("--bins", o.bins, "profile bins")->check(CLI::Range(1, 100000));
  app.add_flag("--quiet", o.quiet, "no summary on stdout (warnings and errors still go to stderr)");
  app.callback([&] {  // checks across options: a bad command line (exit 2), nothing read or written yet
    o.axis = axis[0] - 'x';
    try {
      for (const std::string& r : regions) o.regions.push_back(dem::parse_region(r));
      dem::check_post_options(o);
    } catch (const dem::InputError& e) {
      throw CLI::ValidationError(e.what());
    }
  });
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::post_macro(o); });
}
