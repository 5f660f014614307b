#pragma once
// Ctrl-C during a long command. While an InterruptScope lives, the first SIGINT or SIGTERM only
// sets a flag: the command passes it to its calls (ClientOptions::cancel), the call in progress is
// cancelled (soiqd keeps nothing of an upload or import it had not finished receiving), and the
// command stops before its next step, says what it kept, and exits with kExitInterrupted. A second
// signal ends the process at once, as a user pressing Ctrl-C twice expects.
// Not reentrant: one scope at a time (a command is one process).

#include <atomic>

namespace soiq::cli {

// 128 + SIGINT, what shells report for a command Ctrl-C ended.
inline constexpr int kExitInterrupted = 130;

class InterruptScope {
 public:
  InterruptScope();   // clears the flag and installs the handlers
  ~InterruptScope();  // puts the previous handlers back
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  const std::atomic<bool>* flag() const;
  bool interrupted() const { return flag()->load(); }
};

// True once a signal arrived in the current (or last) scope: run_command's exit code then is
// kExitInterrupted whatever status the cancelled call returned.
bool interrupted();

}  // namespace soiq::cli
