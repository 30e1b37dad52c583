#include "common/interrupt.hpp"

#include <signal.h>

#include <csignal>
#include <ctime>

namespace duet {

namespace {

volatile std::sig_atomic_t received = 0;
timespec first_at{};  // when the first signal came (CLOCK_MONOTONIC)

double seconds_since(const timespec& t0) {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe (POSIX)
  return static_cast<double>(now.tv_sec - t0.tv_sec) +
         1e-9 * static_cast<double>(now.tv_nsec - t0.tv_nsec);
}

void on_signal(int signal) {
  if (received == 0) {
    clock_gettime(CLOCK_MONOTONIC, &first_at);
    received = signal;
    return;
  }
  // A second signal: the user wants out now; the default action ends the process. The same
  // signal again within a second is the same request delivered twice (`timeout` and batch
  // systems signal the process and then its process group, and a fast handler sees both).
  if (signal == received && seconds_since(first_at) < 1.0) return;
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int pending_interrupt() {
  return static_cast<int>(received);
}

}  // namespace duet
