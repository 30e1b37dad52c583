#pragma once
// SIGINT / SIGTERM as a request, not a kill: the first signal is recorded and the run loop ends
// after the step in progress (frame and metrics.json written, status "interrupted"); a second
// signal ends the process at once (every frame already written is a closed file). The same
// signal again within a second is the first delivered twice (`timeout`, batch systems: the
// process, then its group), which once ended a run before it wrote its metrics.

namespace duet {

/// Installs the handlers for SIGINT and SIGTERM (idempotent).
void install_interrupt_handlers();

/// The signal received since the handlers were installed, or 0.
int pending_interrupt();

/// The exit status for a run ended by `signal`: 128 + signal (130 for SIGINT, 143 for SIGTERM).
inline int interrupted_exit_status(int signal) {
  return 128 + signal;
}

}  // namespace duet
