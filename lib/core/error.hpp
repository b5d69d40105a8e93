#pragma once
// The library throws this small hierarchy; each tool's main catches once and maps the kind to an
// exit code (see README "Exit codes").
#include <stdexcept>
#include <string>

namespace dem {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Bad user input: scene file, command-line option, a checkpoint that does not fit the scene.
struct InputError : Error {
  using Error::Error;
};
// A file that cannot be read or written: missing, truncated, corrupted, foreign, disk full.
struct IoError : Error {
  using Error::Error;
};
// The simulation became unphysical (NaN/Inf, runaway overlap). With two parts, what() is
// "facts: advice": the advice is the generic remedy (time step, stiffness), which the run layer
// lists after the causes its start checks found likelier (run/start_checks.hpp).
struct PhysicsError : Error {
  using Error::Error;
  PhysicsError(const std::string& facts_, const std::string& advice_) : Error(facts_ + ": " + advice_), facts(facts_), advice(advice_) {}
  std::string facts, advice;  // empty when built from one message
};

// The run was stopped by a signal (Ctrl-C, SIGTERM) between steps; the message says what was saved
// and how to resume.
struct Interrupted : Error {
  using Error::Error;
};

// Exit codes shared by all tools (130: as a shell reports a process stopped by Ctrl-C).
enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 2,
  kExitInput = 3,
  kExitIo = 4,
  kExitPhysics = 5,
  kExitInternal = 70,
  kExitInterrupted = 130
};

}  // namespace dem
