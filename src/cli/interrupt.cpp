#include "cli/interrupt.hpp"

#include <csignal>
#include <stdexcept>

namespace holoray::cli {

namespace {

// The only state a signal handler may touch: a lock-free flag.
volatile std::sig_atomic_t g_signal = 0;
bool g_installed = false;
struct sigaction g_previous_int, g_previous_term;

extern "C" void record_signal(int sig) { g_signal = sig; }

}  // namespace

StopOnSignal::StopOnSignal() {
  if (g_installed) throw std::logic_error("StopOnSignal: one at a time");
  g_installed = true;
  g_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second signal takes the default action: stop now
  sigaction(SIGINT, &sa, &g_previous_int);
  sigaction(SIGTERM, &sa, &g_previous_term);
}

StopOnSignal::~StopOnSignal() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  g_installed = false;
}

int StopOnSignal::signal() const { return g_signal; }

}  // namespace holoray::cli
