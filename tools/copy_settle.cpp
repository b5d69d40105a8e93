// copy-settle: Tile a settled set nx x ny x nz times and settle again (scene [copy]).
#include "run/generate.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Tile a settled set nx x ny x nz times and settle again (scene [copy]).", "copy-settle");
  dem::GenerateOptions o;
  int threads = 0;
  dem::add_generate_options(app, o, true);
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::copy_settle(o); });
}
