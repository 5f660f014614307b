#include "client/cli/interrupt.h"

#include <signal.h>  // sigaction (POSIX)

namespace soiq::cli {

namespace {

std::atomic<bool> g_interrupted{false};
struct sigaction g_previous_int, g_previous_term;

extern "C" void on_signal(int) { g_interrupted.store(true); }

void install(int signo, struct sigaction* previous) {
  struct sigaction a = {};
  a.sa_handler = on_signal;
  sigemptyset(&a.sa_mask);
  a.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process at once
  sigaction(signo, &a, previous);
}

}  // namespace

InterruptScope::InterruptScope() {
  g_interrupted.store(false);
  install(SIGINT, &g_previous_int);
  install(SIGTERM, &g_previous_term);
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

const std::atomic<bool>* InterruptScope::flag() const { return &g_interrupted; }

bool interrupted() { return g_interrupted.load(); }

}  // namespace soiq::cli
