// compact: Move boundary walls inward to a target stress or porosity (scene [compact]).
#include "run/generate.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Move boundary walls inward to a target stress or porosity (scene [compact]).", "compact");
  dem::GenerateOptions o;
  int threads = 0;
  app.add_option("--scene", o.scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  app.add_option("--in", o.in, "input checkpoint (HDF5)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "output checkpoint (HDF5), written atomically")->required();
  app.add_flag("--quiet", o.quiet, "no progress output");
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::compact(o); });
}
