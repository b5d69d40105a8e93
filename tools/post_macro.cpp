// post-macro: displacement fields between two checkpoints, to VTK and CSV.
#include "post/post_macro.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Displacement between two checkpoints, matched by particle id: per particle to VTK, profile to CSV.", "post-macro");
  dem::PostOptions o;
  int threads = 0;
  std::string axis = "z";
  app.add_option("--reference", o.reference, "reference checkpoint (HDF5)")->required()->check(CLI::ExistingFile);
  app.add_option("--in", o.in, "current checkpoint (HDF5)")->required()->check(CLI::ExistingFile);
  app.add_option("--vtk", o.vtk, "particles with displacement (.vtu)");
  app.add_option("--csv", o.csv, "displacement profile table (.csv)");
  app.add_option("--axis", axis, "profile axis")->check(CLI::IsMember({"x", "y", "z"}));
  app.add_option("--bins", o.bins, "profile bins")->check(CLI::Range(1, 100000));
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] {
    o.axis = axis[0] - 'x';
    dem::post_macro(o);
  });
}
