#pragma once
// Progress of a long run on stderr. On a terminal: one line redrawn in place
// (\r) at most ~10 times a second. Otherwise (log files, CI): a plain line at
// every 10 % of the run and at least every 30 s. Both show step, simulated
// time, percentage, elapsed and remaining wall time and broken bonds.
//
// update() is meant to be called every step: it only counts down to the next
// clock check, and the distance between checks adapts so that the clock is
// read every few milliseconds whatever the cost of a step.
#include <cstdint>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <string_view>

namespace pdmpm::io {

// 12.3 µs, 4.56 ms, 0 s: three significant digits with an SI prefix.
std::string format_engineering(double value, std::string_view unit);
// 4.2 s, 3:07, 1:02:03 (seconds; h:mm:ss beyond an hour).
std::string format_duration(double seconds);

class Progress {
 public:
  // Seconds on a monotonic clock; injectable for tests.
  using Clock = std::function<double()>;

  // Progress is measured by simulated time when end_time > 0, otherwise by
  // step / total_steps (total_steps <= 0: unknown, no percentage or ETA).
  Progress(std::ostream& out, bool interactive, std::int64_t total_steps, double end_time, std::string label,
           Clock clock = {});

  void update(std::int64_t step, double time, std::int64_t broken_bonds) {
    if (--countdown_ > 0 && !(by_time_ ? time >= next_report_time_ : step >= next_report_step_)) return;
    slow_update(step, time, broken_bonds);
  }
  // Final line with the total wall time; later calls and updates do nothing.
  void finish(std::int64_t step, double time, std::int64_t broken_bonds);

  static bool stderr_is_terminal();
  // What the count in each line is called ("broken" bonds for PD, "failed" particles for MPM).
  void set_counter_name(std::string name) { counter_name_ = std::move(name); }

 private:
  void slow_update(std::int64_t step, double time, std::int64_t broken_bonds);
  double fraction(std::int64_t step, double time) const;  // < 0 when unknown
  std::string status(std::int64_t step, double time, std::int64_t broken_bonds, double elapsed) const;
  void draw(const std::string& line, bool final_line);
  void arm_next_decile(std::int64_t step, double time);

  std::ostream& out_;
  bool interactive_;
  std::int64_t total_steps_;
  double end_time_;
  std::string label_;
  std::string counter_name_ = "broken";
  Clock clock_;
  bool by_time_;

  double start_ = 0.0, last_check_ = 0.0, last_output_ = 0.0;
  bool drawn_ = false, finished_ = false;
  std::int64_t stride_ = 1, countdown_ = 1;
  int next_decile_ = 1;
  double next_report_time_ = std::numeric_limits<double>::infinity();
  std::int64_t next_report_step_ = std::numeric_limits<std::int64_t>::max();
  std::size_t last_width_ = 0;
};

}  // namespace pdmpm::io
