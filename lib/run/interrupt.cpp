#include "run/interrupt.hpp"

#include <signal.h>

#include <csignal>

namespace dem {

namespace {

volatile std::sig_atomic_t g_received = 0;
struct sigaction g_old_int, g_old_term;
bool g_int_installed = false;

extern "C" void record_signal(int sig) { g_received = sig; }

}  // namespace

StopOnSignal::StopOnSignal() {
  g_received = 0;
  struct sigaction sa {};
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // the second signal takes the default action: stop at once
  sigaction(SIGINT, nullptr, &g_old_int);
  g_int_installed = g_old_int.sa_handler != SIG_IGN;
  if (g_int_installed) sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, &g_old_term);
}

StopOnSignal::~StopOnSignal() {
  if (g_int_installed) sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

int StopOnSignal::received() { return g_received; }

std::string StopOnSignal::name(int signal) {
  return signal == SIGINT ? "SIGINT (Ctrl-C)" : signal == SIGTERM ? "SIGTERM" : "signal " + std::to_string(signal);
}

}  // namespace dem
