// gen-primary: Generate a random primary set of spheres in a box and settle it under gravity (scene [generation]).
#include "run/generate.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Generate a random primary set of spheres in a box and settle it under gravity (scene [generation]).", "gen-primary");
  dem::GenerateOptions o;
  int threads = 0;
  app.add_option("--scene", o.scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "output checkpoint (HDF5), written atomically")->required();
  app.add_flag("--quiet", o.quiet, "no progress output");
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::gen_primary(o); });
}
