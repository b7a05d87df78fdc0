#include "solver/sim/interrupt.hpp"

#include <csignal>

namespace pdmpm::sim {
namespace {

volatile std::sig_atomic_t requested = 0;

extern "C" void on_signal(int signal_number) {
  requested = signal_number;
  std::signal(signal_number, SIG_DFL);  // a second signal is not caught
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

int interrupt_requested() { return requested; }
void request_interrupt(int signal_number) { requested = signal_number; }
void clear_interrupt() { requested = 0; }

}  // namespace pdmpm::sim
