#pragma once
// Resident memory of this process from /proc/self/status, for memory per bond:
// VmRSS now and VmHWM, the peak since the start or the last reset_peak().
namespace pdmpm::perf {

struct MemoryStatus {
  double resident_bytes = 0.0;  // VmRSS
  double peak_bytes = 0.0;      // VmHWM
};

MemoryStatus memory_status();
// Sets VmHWM back to the current VmRSS (writes "5" to /proc/self/clear_refs,
// Linux ≥ 4.0); false if the kernel refused, in which case the peak also holds
// whatever came before.
bool reset_peak();

}  // namespace pdmpm::perf
