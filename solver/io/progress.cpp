#include "solver/io/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace pdmpm::io {
namespace {

constexpr double kRedrawInterval = 0.1;      // s: ~10 redraws a second on a terminal
constexpr double kQuietLimit = 30.0;         // s: longest silence in a log
// Clock checks are spaced so that one happens every 2-20 ms: often enough for
// the intervals above, rare enough to cost nothing per step.
constexpr double kCheckTooSoon = 0.002, kCheckTooLate = 0.02;
constexpr std::int64_t kMaxStride = std::int64_t{1} << 20;
constexpr int kBarWidth = 24;

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Display columns of UTF-8 text (continuation bytes take no column).
std::size_t columns(const std::string& text) {
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

}  // namespace

std::string format_engineering(double value, std::string_view unit) {
  const std::string space = unit.empty() ? "" : " ";
  if (!std::isfinite(value)) return fmt::format("{}{}{}", value, space, unit);
  if (value == 0.0) return fmt::format("0{}{}", space, unit);
  static constexpr const char* prefixes[] = {"y", "z", "a", "f", "p", "n", "µ", "m", "", "k", "M", "G", "T", "P", "E", "Z", "Y"};
  constexpr int kUnitIndex = 8;
  const double magnitude = std::fabs(value);
  int group = static_cast<int>(std::floor(std::log10(magnitude) / 3.0));
  group = std::clamp(group, -kUnitIndex, 8);
  double mantissa = magnitude / std::pow(10.0, 3 * group);
  // Three significant digits. Rounding can add a digit (99.99 -> 100) or
  // carry into the next prefix (999.96 -> 1.00 k), so the decimals are chosen
  // again from the rounded value.
  auto decimals = [](double m) { return m < 10.0 ? 2 : (m < 100.0 ? 1 : 0); };
  auto rounded = [&](double m) {
    const double scale = std::pow(10.0, decimals(m));
    return std::round(m * scale) / scale;
  };
  mantissa = rounded(mantissa);
  if (mantissa >= 1000.0 && group < 8) {
    ++group;
    mantissa = rounded(mantissa / 1000.0);
  }
  const char* sign = value < 0 ? "-" : "";
  return fmt::format("{}{:.{}f}{}{}{}", sign, mantissa, decimals(mantissa), space, prefixes[group + kUnitIndex], unit);
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--";
  if (seconds < 59.95) return fmt::format("{:.1f} s", seconds);
  const auto total = static_cast<std::int64_t>(std::llround(seconds));
  const std::int64_t h = total / 3600, m = (total / 60) % 60, s = total % 60;
  if (h == 0) return fmt::format("{}:{:02d}", m, s);
  return fmt::format("{}:{:02d}:{:02d}", h, m, s);
}

Progress::Progress(std::ostream& out, bool interactive, std::int64_t total_steps, double end_time, std::string label,
                   Clock clock)
    : out_(out),
      interactive_(interactive),
      total_steps_(total_steps),
      end_time_(end_time),
      label_(std::move(label)),
      clock_(clock ? std::move(clock) : Clock(steady_seconds)),
      by_time_(end_time > 0.0) {
  start_ = last_check_ = last_output_ = clock_();
  if (!interactive_) arm_next_decile(0, 0.0);
}

bool Progress::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

double Progress::fraction(std::int64_t step, double time) const {
  if (by_time_) return std::clamp(time / end_time_, 0.0, 1.0);
  if (total_steps_ > 0) return std::clamp(static_cast<double>(step) / static_cast<double>(total_steps_), 0.0, 1.0);
  return -1.0;
}

// Next 10 % mark not yet passed; thresholds are computed the same way every
// time, so a mark is reported exactly once.
void Progress::arm_next_decile(std::int64_t step, double time) {
  next_report_time_ = std::numeric_limits<double>::infinity();
  next_report_step_ = std::numeric_limits<std::int64_t>::max();
  if (!by_time_ && total_steps_ <= 0) return;
  // Marks sit a hair (1e-9 relative) early so that a time accumulated from
  // many steps that should land on a mark is not missed by rounding.
  auto time_mark = [&](int k) { return end_time_ * k / 10.0 * (1.0 - 1e-9); };
  auto step_mark = [&](int k) { return (total_steps_ * k + 9) / 10; };
  while (next_decile_ <= 10 && (by_time_ ? time >= time_mark(next_decile_) : step >= step_mark(next_decile_)))
    ++next_decile_;
  if (next_decile_ > 10) return;
  if (by_time_)
    next_report_time_ = time_mark(next_decile_);
  else
    next_report_step_ = step_mark(next_decile_);
}

std::string Progress::status(std::int64_t step, double time, std::int64_t broken_bonds, double elapsed) const {
  const double f = fraction(step, time);
  std::string text;
  if (f >= 0) text += fmt::format("{:5.1f}% ", 100.0 * f);
  text += total_steps_ > 0 ? fmt::format("step {}/{}", step, total_steps_) : fmt::format("step {}", step);
  text += fmt::format("  t = {}", format_engineering(time, "s"));
  text += fmt::format("  elapsed {}", format_duration(elapsed));
  if (f > 0)
    text += fmt::format("  ETA {}", format_duration(elapsed * (1.0 - f) / f));
  else
    text += "  ETA --";
  text += fmt::format("  {} {}", counter_name_, broken_bonds);
  return text;
}

void Progress::draw(const std::string& line, bool final_line) {
  if (interactive_) {
    // Pad with spaces over what is left of a longer previous line.
    const std::size_t width = columns(line);
    const std::size_t pad = last_width_ > width ? last_width_ - width : 0;
    out_ << '\r' << line << std::string(pad, ' ');
    if (final_line) out_ << '\n';
    last_width_ = width;
  } else {
    out_ << line << '\n';
  }
  out_.flush();
  drawn_ = true;
}

void Progress::slow_update(std::int64_t step, double time, std::int64_t broken_bonds) {
  if (finished_) {
    countdown_ = kMaxStride;
    return;
  }
  const double now = clock_();
  const double since_check = now - last_check_;
  if (since_check < kCheckTooSoon && stride_ < kMaxStride)
    stride_ *= 2;
  else if (since_check > kCheckTooLate && stride_ > 1)
    stride_ /= 2;
  last_check_ = now;
  countdown_ = stride_;

  const double elapsed = now - start_;
  if (interactive_) {
    if (drawn_ && now - last_output_ < kRedrawInterval) return;
    const double f = fraction(step, time);
    std::string line = label_.empty() ? "" : label_ + " ";
    if (f >= 0) {
      const int filled = static_cast<int>(f * kBarWidth);
      line += '[';
      line.append(static_cast<std::size_t>(filled), '#');
      line.append(static_cast<std::size_t>(kBarWidth - filled), '-');
      line += "] ";
    }
    draw(line + status(step, time, broken_bonds, elapsed), false);
    last_output_ = now;
    return;
  }
  const bool at_mark = by_time_ ? time >= next_report_time_ : step >= next_report_step_;
  if (!at_mark && now - last_output_ < kQuietLimit) return;
  if (at_mark) arm_next_decile(step, time);
  draw((label_.empty() ? "" : label_ + " ") + status(step, time, broken_bonds, elapsed), false);
  last_output_ = now;
}

void Progress::finish(std::int64_t step, double time, std::int64_t broken_bonds) {
  if (finished_) return;
  finished_ = true;
  const double elapsed = clock_() - start_;
  std::string line = label_.empty() ? "" : label_ + " ";
  line += fmt::format("done: step {}  t = {}  wall {}  {} {}", step, format_engineering(time, "s"),
                      format_duration(elapsed), counter_name_, broken_bonds);
  draw(line, true);
  countdown_ = kMaxStride;
  next_report_time_ = std::numeric_limits<double>::infinity();
  next_report_step_ = std::numeric_limits<std::int64_t>::max();
}

}  // namespace pdmpm::io
