// gen-primary: Generate a random primary set of spheres in a box and settle it under gravity (scene [generation]).
#include "run/generate.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Generate a random primary set of spheres in a box and settle it under gravity (scene [generation]).", "gen-primary");
  dem::GenerateOptions o;
  int threads = 0;
  dem::add_generate_options(app, o, false);
  app.add_option("--sizes", o.sizes, "CSV of the size distribution asked against the radii drawn (docs/scene.md)");
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::gen_primary(o); });
}
