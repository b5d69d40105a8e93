// copy-settle: Tile a settled set nx x ny x nz times and settle again (scene [copy]).
#include "run/generate.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Tile a settled set nx x ny x nz times and settle again (scene [copy]).", "copy-settle");
  dem::GenerateOptions o;
  int threads = 0;
  app.add_option("--scene", o.scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  app.add_option("--in", o.in, "input checkpoint (HDF5)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "output checkpoint (HDF5), written atomically")->required();
  app.add_flag("--quiet", o.quiet, "no progress output");
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::copy_settle(o); });
}
