#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a long run: the handler only records the signal (no work in
// a signal handler); the run checks it between steps, finishes the step, saves what it can and
// stops with exit code 130 (dem::Interrupted). A second signal stops the process at once (the
// handler is reset by the first), which an atomic checkpoint write survives.
#include <string>

namespace dem {

class StopOnSignal {
 public:
  // Installs the handlers; SIGINT only where it is not ignored (a script's background job ignores
  // it, so that Ctrl-C stops the script, not the jobs it left running).
  StopOnSignal();
  ~StopOnSignal();  // restores the handlers found
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  static int received();                // the signal received since construction, 0 if none
  static std::string name(int signal);  // "SIGINT", "SIGTERM"
};

}  // namespace dem
