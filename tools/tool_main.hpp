#pragma once
// What every tool shares: --version, --threads, and one place that turns exceptions into messages
// and exit codes (README "Exit codes").
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <functional>
#include <string>

#include "core/error.hpp"
#include "core/interval.hpp"
#include "core/version.hpp"
#include "run/setup.hpp"

namespace dem {

inline void add_common_options(CLI::App& app, int& threads) {
  app.set_version_flag("--version", std::string(app.get_name()) + " (dem) " + kVersion + " (commit " + kCommit + ")");
  app.add_option("--threads", threads, "OpenMP threads (0 = OMP_NUM_THREADS or all cores); results are identical for any count")
      ->check(CLI::NonNegativeNumber);
}

// An interval option (core/interval.hpp): a bare number counts steps, a number with s seconds
// ("0.01s"); 0 (off) only where `zero_ok`.
inline CLI::Option* add_interval_option(CLI::App& app, const std::string& name, Interval& target, const std::string& help,
                                        bool zero_ok = false) {
  return app
      .add_option_function<std::string>(
          name,
          [&target, name, zero_ok](const std::string& text) {
            std::string why;
            const std::optional<Interval> r = parse_interval(text, Interval::Unit::Steps, zero_ok, why);
            if (!r) throw CLI::ValidationError(name, why);
            target = *r;
          },
          help + "; a number of steps, or seconds with s (e.g. 0.01s)")
      ->type_name(zero_ok ? "STEPS|SECONDSs (0 = off)" : "STEPS|SECONDSs");
}

// The options gen-primary, copy-settle and compact share (`needs_input`: all but gen-primary).
template <class Options>
void add_generate_options(CLI::App& app, Options& o, bool needs_input) {
  app.add_option("--scene", o.scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  if (needs_input) app.add_option("--in", o.in, "input checkpoint (HDF5)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "output checkpoint (HDF5), written atomically")->required();
  app.add_flag("--quiet", o.quiet, "no progress output");
}

// The command line as a shell would take it back (arguments quoted where needed), for messages
// that tell the user what to run next.
inline std::string shell_command(int argc, char** argv) {
  std::string line;
  for (int k = 0; k < argc; ++k) {
    const std::string a = argv[k];
    const bool plain = !a.empty() && a.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-./=:,+@%") == std::string::npos;
    std::string q = "'";
    for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += (k ? " " : "") + (plain ? a : q + "'");
  }
  return line;
}

inline int run_tool(CLI::App& app, int argc, char** argv, int& threads, const std::function<void()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  choose_threads(threads);
  // Past a file-size limit (ulimit -f) a write should fail with an error we report, not kill us.
  std::signal(SIGXFSZ, SIG_IGN);
  const std::string name = app.get_name();
  try {
    body();
    return kExitOk;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
    return kExitInput;
  } catch (const IoError& e) {
    std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
    return kExitIo;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return kExitInterrupted;
  } catch (const PhysicsError& e) {
    std::fprintf(stderr, "%s: error: unstable simulation: %s\n", name.c_str(), e.what());
    return kExitPhysics;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", name.c_str(), e.what());
    return kExitInternal;
  }
}

}  // namespace dem
