// compact: Move boundary walls inward to a target stress or porosity (scene [compact]).
#include "run/generate.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Move boundary walls inward to a target stress or porosity (scene [compact]).", "compact");
  dem::GenerateOptions o;
  int threads = 0;
  dem::add_generate_options(app, o, true);
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::compact(o); });
}
