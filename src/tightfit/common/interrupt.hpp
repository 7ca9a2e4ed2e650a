#pragma once
/// Interruptions of long runs (Ctrl-C, `kill`): while an InterruptGuard lives, SIGINT and
/// SIGTERM do not kill the process but set a request that a long run polls between its
/// steps (the optimizer after each accepted iteration), so that the current step
/// finishes and the results so far are written. A second signal ends the process at
/// once (the default action). The guard restores the previous handlers.
namespace tightfit {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

/// The signal (SIGINT or SIGTERM) received while a guard lives, 0 if none.
int interrupt_signal();
/// interrupt_signal() != 0.
inline bool interrupt_requested() { return interrupt_signal() != 0; }
/// "SIGINT", "SIGTERM" or "signal N".
const char* signal_name(int signal);

/// Thrown by a command that stopped on request after writing its results; the CLI exits
/// with 128 + the signal number (130 for SIGINT, 143 for SIGTERM), the shell convention.
struct Interrupted {
  int signal = 0;
};

}  // namespace tightfit
