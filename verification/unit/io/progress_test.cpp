// Progress: plain lines at each 10 % (and during long silences) with an ETA
// from the injected clock; a single redrawn line on a terminal, rate-limited,
// with the newline only at finish.
#include "solver/io/progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace pdmpm::io {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) lines.push_back(line);
  return lines;
}

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// A clock the test moves by hand; counts how often Progress reads it.
struct FakeClock {
  double now = 0.0;
  long reads = 0;
  Progress::Clock function() {
    return [this] {
      ++reads;
      return now;
    };
  }
};

TEST(Progress, EngineeringFormat) {
  EXPECT_EQ(format_engineering(12.3e-6, "s"), "12.3 µs");
  EXPECT_EQ(format_engineering(1.5e-9, "s"), "1.50 ns");
  EXPECT_EQ(format_engineering(-2.5e-3, "s"), "-2.50 ms");
  EXPECT_EQ(format_engineering(0.0, "s"), "0 s");
  EXPECT_EQ(format_engineering(1.0, "s"), "1.00 s");
  EXPECT_EQ(format_engineering(123456.0, "Pa"), "123 kPa");
  EXPECT_EQ(format_engineering(999.96, "s"), "1.00 ks");     // rounding carries into the next prefix
  EXPECT_EQ(format_engineering(999.96e-9, "s"), "1.00 µs");
  EXPECT_EQ(format_engineering(1e-3, "s"), "1.00 ms");
  EXPECT_EQ(format_engineering(1e-7, "s"), "100 ns");        // 99.999... rounds to three digits, not "100.0"
  EXPECT_EQ(format_engineering(9.99999e-3, "s"), "10.0 ms");
  EXPECT_EQ(format_engineering(2.0e9, ""), "2.00G");
}

TEST(Progress, DurationFormat) {
  EXPECT_EQ(format_duration(4.3), "4.3 s");
  EXPECT_EQ(format_duration(59.9), "59.9 s");
  EXPECT_EQ(format_duration(60.0), "1:00");
  EXPECT_EQ(format_duration(187.0), "3:07");
  EXPECT_EQ(format_duration(3723.0), "1:02:03");
  EXPECT_EQ(format_duration(-1.0), "--");
}

// 1000 steps of 10 ms each: a line at every 10 % of the steps, then the final one.
TEST(Progress, NonInteractivePrintsAtEachTenPercentOfSteps) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, false, 1000, 0.0, "run", clock.function());
  for (std::int64_t step = 1; step <= 1000; ++step) {
    clock.now += 0.01;
    progress.update(step, 1e-9 * static_cast<double>(step), step / 100);
  }
  progress.finish(1000, 1e-6, 10);
  const auto lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 11u) << out.str();
  for (int k = 1; k <= 10; ++k) {
    const std::string& line = lines[static_cast<std::size_t>(k - 1)];
    EXPECT_TRUE(contains(line, std::to_string(10 * k) + ".0%")) << line;
    EXPECT_TRUE(contains(line, "step " + std::to_string(100 * k) + "/1000")) << line;
    EXPECT_TRUE(contains(line, "broken " + std::to_string(k))) << line;
    EXPECT_TRUE(line.rfind("run ", 0) == 0) << line;
  }
  EXPECT_TRUE(contains(lines[9], "t = 1.00 µs")) << lines[9];
  EXPECT_TRUE(contains(lines[10], "done: step 1000")) << lines[10];
  EXPECT_TRUE(contains(lines[10], "wall 10.0 s")) << lines[10];
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
}

// Progress by simulated time (adaptive steps): the marks follow time, not steps,
// and a jump over several marks prints one line.
TEST(Progress, NonInteractiveFollowsSimulatedTimeWhenEndTimeIsKnown) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, false, 0, 1e-3, "", clock.function());
  const double times[] = {0.5e-4, 0.99e-4, 1e-4, 1.5e-4, 4.2e-4, 4.3e-4, 1e-3};
  std::int64_t step = 0;
  for (double t : times) progress.update(++step, t, 0);
  const auto lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 3u) << out.str();
  EXPECT_TRUE(contains(lines[0], " 10.0% step 3 ")) << lines[0];
  EXPECT_TRUE(contains(lines[1], " 42.0% step 5 ")) << lines[1];
  EXPECT_TRUE(contains(lines[2], "100.0% step 7 ")) << lines[2];
}

// One second per step, 100 steps: at 10 % 10 s have passed, so 90 s remain.
TEST(Progress, EtaComesFromTheInjectedClock) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, false, 100, 0.0, "eta", clock.function());
  for (std::int64_t step = 1; step <= 50; ++step) {
    clock.now += 1.0;
    progress.update(step, 0.0, 0);
  }
  const auto lines = lines_of(out.str());
  // A line at each 10 % mark (10 s apart, so the 30 s rule adds none).
  ASSERT_EQ(lines.size(), 5u) << out.str();
  EXPECT_TRUE(contains(lines[0], "elapsed 10.0 s  ETA 1:30")) << lines[0];
  EXPECT_TRUE(contains(lines[4], "elapsed 50.0 s  ETA 50.0 s")) << lines[4];
}

// One second per step with the 10 % marks 100 steps apart: a line every 30 s.
TEST(Progress, NonInteractivePrintsAtLeastEveryThirtySeconds) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, false, 1000, 0.0, "slow", clock.function());
  for (std::int64_t step = 1; step <= 100; ++step) {
    clock.now += 1.0;
    progress.update(step, 0.0, 0);
  }
  const auto lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 4u) << out.str();
  EXPECT_TRUE(contains(lines[0], "step 30/1000")) << lines[0];
  EXPECT_TRUE(contains(lines[1], "step 60/1000")) << lines[1];
  EXPECT_TRUE(contains(lines[2], "step 90/1000")) << lines[2];
  EXPECT_TRUE(contains(lines[3], " 10.0% step 100/1000")) << lines[3];
}

TEST(Progress, InteractiveRedrawsOneLineAndEndsItAtFinish) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, true, 200, 2e-6, "sim", clock.function());
  for (std::int64_t step = 1; step <= 200; ++step) {
    clock.now += 0.04;  // 25 steps a second, 8 s in all
    progress.update(step, 1e-8 * static_cast<double>(step), 0);
  }
  const std::string before = out.str();
  EXPECT_NE(before.find('\r'), std::string::npos);
  EXPECT_EQ(before.find('\n'), std::string::npos);
  const auto redraws = std::count(before.begin(), before.end(), '\r');
  // At most 10 redraws per second over 8 s (+1 for the first); at least one
  // every 0.12 s (3 steps), as a 0.1 s limit allows.
  EXPECT_LE(redraws, 81);
  EXPECT_GE(redraws, 66);
  EXPECT_TRUE(contains(before, "sim [")) << before;
  EXPECT_TRUE(contains(before, " 99.5% step 199/200")) << before;

  progress.finish(200, 2e-6, 3);
  const std::string after = out.str();
  EXPECT_EQ(std::count(after.begin(), after.end(), '\n'), 1);
  EXPECT_EQ(after.back(), '\n');
  const std::string last = after.substr(after.rfind('\r') + 1);
  EXPECT_TRUE(contains(last, "sim done: step 200  t = 2.00 µs  wall 8.0 s  broken 3")) << last;
  progress.finish(200, 2e-6, 3);  // idempotent
  progress.update(201, 2.1e-6, 3);
  EXPECT_EQ(out.str(), after);
}

// While the clock stands still no redraw happens however often update() is
// called; once 0.1 s has passed the next clock check redraws.
TEST(Progress, InteractiveRedrawsAtMostTenTimesPerSecond) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, true, 0, 0.0, "", clock.function());
  auto redraws = [&] {
    const std::string text = out.str();
    return std::count(text.begin(), text.end(), '\r');
  };
  for (int k = 0; k < 100000; ++k) progress.update(k, 0.0, 0);
  EXPECT_EQ(redraws(), 1);
  clock.now = 0.05;
  for (int k = 0; k < 100000; ++k) progress.update(k, 0.0, 0);
  EXPECT_EQ(redraws(), 1);
  clock.now = 0.15;
  for (int k = 0; k < 3000000; ++k) progress.update(k, 0.0, 0);
  EXPECT_EQ(redraws(), 2);
}

// update() reads the clock only now and then: with fast steps the distance
// between reads grows until reads are milliseconds apart.
TEST(Progress, UpdateRarelyReadsTheClock) {
  std::ostringstream out;
  FakeClock clock;
  Progress progress(out, true, 10000000, 0.0, "", clock.function());
  const long reads_at_start = clock.reads;
  for (std::int64_t step = 1; step <= 10000000; ++step) {
    clock.now += 1e-8;  // 10 ns per step
    progress.update(step, 0.0, 0);
  }
  const long reads = clock.reads - reads_at_start;
  // 0.1 s of fake time with reads at least ~2 ms apart once the stride has
  // grown: of order 100 reads (bound 1000 leaves room for the ramp-up) for 10^7 calls.
  EXPECT_LT(reads, 1000);
  EXPECT_GT(reads, 10);  // but it still looks: redraws need the clock
}

}  // namespace
}  // namespace pdmpm::io
