#pragma once
// SIGINT and SIGTERM during a run: the first one only raises a flag that the
// time loops read after each step (they then write a checkpoint and close their
// outputs); a second one ends the process at once, as the signal would have.
namespace pdmpm::sim {

// Installs the handlers (pdmpm run / resume do; the library alone does not).
void install_interrupt_handlers();
// The signal that asked the run to stop (SIGINT, SIGTERM), 0 if none.
int interrupt_requested();
// What a handler does, for tests and for RunOptions::interrupt_at_step.
void request_interrupt(int signal_number);
void clear_interrupt();

}  // namespace pdmpm::sim
