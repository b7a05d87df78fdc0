#pragma once
// Small measurements and names every time loop reports (PD and MPM).
#include <chrono>

namespace pdmpm::sim {

// Peak resident memory of this process so far (bytes).
double peak_memory_bytes();
double seconds_since(std::chrono::steady_clock::time_point t0);
// "x", "y", "z" for history column names.
const char* axis_name(int a);

}  // namespace pdmpm::sim
