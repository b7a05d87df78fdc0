#pragma once
// Small measurements and names every time loop reports (PD and MPM).
#include <chrono>

namespace pdmpm::sim {

// Peak resident memory of this process so far (bytes).
double peak_memory_bytes();
double seconds_since(std::chrono::steady_clock::time_point t0);
// Other processes running on the machine now: the runnable tasks of /proc/loadavg minus
// this one, the median of five samples 10 ms apart (the one-minute load average lags: it
// still counts a build that ended half a minute ago). Negative when it cannot be read.
double other_running_processes();
// Whether other work keeps busy the cores a run of `threads` threads needs: fewer than
// `threads` of the machine's `cores` are left idle by `others` running processes. A run
// timed then can take many times its quiet-machine wall time — OpenMP threads spin while
// they wait for a descheduled partner (measured: `pdmpm check` 67× too high beside another
// 2-thread run on 2 cores).
bool cores_taken(double others, int cores, int threads);
// "x", "y", "z" for history column names.
const char* axis_name(int a);

}  // namespace pdmpm::sim
