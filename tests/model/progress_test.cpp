// The progress meter (model/base/progress.hpp) on an injected clock and stream: what the line says
// (done/total, share, rate, time left), how often it is redrawn, how it ends.
#include <unistd.h>

#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "model/base/progress.hpp"

namespace tessim {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct FakeClock {
  double now = 100.0;
  ProgressMeter::Clock clock() {
    return [this] { return now; };
  }
};

TEST(ProgressMeter, LineShowsDoneTotalRateAndTimeLeft) {
  FakeClock t;
  std::ostringstream out;
  ProgressMeter meter("sim", "vertices", 1000000, out, t.clock());
  t.now += 4.0;
  meter.advance(250000);
  const std::string line = meter.line(t.now);
  EXPECT_TRUE(contains(line, "sim  250 k/1 M vertices")) << line;
  EXPECT_TRUE(contains(line, "25.0%")) << line;
  EXPECT_TRUE(contains(line, "62.5 k vertices/s")) << line;  // 250 k in 4 s
  EXPECT_TRUE(contains(line, "ETA 0:12")) << line;            // 750 k at 62.5 k/s
}

TEST(ProgressMeter, NoRateYetGivesNoTimeLeft) {
  FakeClock t;
  std::ostringstream out;
  ProgressMeter meter("tessellate", "vertices", 10, out, t.clock());
  EXPECT_TRUE(contains(meter.line(t.now), "ETA --")) << meter.line(t.now);
  t.now += 3725.0;
  meter.advance(1);
  EXPECT_TRUE(contains(meter.line(t.now), "ETA 9:18:45")) << meter.line(t.now);  // 9 more at 1 per 3725 s
}

TEST(ProgressMeter, RedrawsInPlaceAtMostTenTimesASecond) {
  FakeClock t;
  std::ostringstream out;
  ProgressMeter meter("sim", "vertices", 100, out, t.clock());
  meter.draw();
  const std::string first = out.str();
  ASSERT_EQ(first.front(), '\r');
  EXPECT_EQ(first.find('\n'), std::string::npos);
  meter.advance(10);
  t.now += 0.05;
  meter.draw();  // too soon: nothing
  EXPECT_EQ(out.str(), first);
  t.now += 0.06;
  meter.draw();
  EXPECT_GT(out.str().size(), first.size());
  EXPECT_EQ(out.str()[first.size()], '\r');
  EXPECT_TRUE(contains(out.str().substr(first.size()), "10/100 vertices")) << out.str();
}

TEST(ProgressMeter, ShorterLineOverwritesTheLongerOne) {
  FakeClock t;
  std::ostringstream out;
  ProgressMeter meter("sim", "vertices", 100, out, t.clock());
  t.now += 1000.0;
  meter.advance(1);
  meter.draw();  // ... 0.001 vertices/s  ETA 27:30:00
  const std::size_t first = out.str().size() - 1;  // without the '\r'
  meter.advance(98);
  t.now += 1.0;
  const std::string second = meter.line(t.now);  // ... 0.0989 vertices/s  ETA 0:10
  ASSERT_LT(second.size(), first);
  meter.draw();
  EXPECT_EQ(out.str().substr(first + 1), "\r" + second + std::string(first - second.size(), ' '));
}

TEST(ProgressMeter, FinishEndsTheLineAndClearErasesIt) {
  FakeClock t;
  std::ostringstream finished, cleared, silent;
  {
    ProgressMeter meter("sim", "vertices", 100, finished, t.clock());
    meter.draw();
    t.now += 2.0;
    meter.advance(100);
    meter.finish();
    EXPECT_EQ(finished.str().back(), '\n');
    EXPECT_TRUE(contains(finished.str(), "100/100 vertices  100.0%")) << finished.str();
    EXPECT_TRUE(contains(finished.str(), "done in 0:02")) << finished.str();
  }
  {
    ProgressMeter meter("sim", "vertices", 100, cleared, t.clock());
    meter.draw();
    const std::size_t width = cleared.str().size() - 1;
    meter.clear();
    EXPECT_EQ(cleared.str().substr(width + 1), "\r" + std::string(width, ' ') + "\r");
  }
  {
    ProgressMeter meter("sim", "vertices", 100, silent, t.clock());
    meter.advance(100);
    meter.finish();  // never drawn: a run too short for a line stays silent
    meter.clear();
    EXPECT_EQ(silent.str(), "");
  }
}

TEST(ProgressMeter, CountsBeyondTheTotalShowAsTheTotal) {
  FakeClock t;
  std::ostringstream out;
  ProgressMeter meter("cosim", "vertices", 50, out, t.clock());
  meter.advance(70);
  t.now += 1.0;
  EXPECT_TRUE(contains(meter.line(t.now), "50/50 vertices  100.0%")) << meter.line(t.now);
}

TEST(ProgressDisplay, InactiveWithoutATerminalOrWhenQuiet) {
  // The tests run with standard error redirected (ctest): no meter, no counter, nothing drawn.
  if (::isatty(2) == 0) {
    ProgressDisplay display("sim", "vertices", 10, false);
    EXPECT_EQ(display.counter(), nullptr);
  }
  ProgressDisplay quiet("sim", "vertices", 10, true);
  EXPECT_EQ(quiet.counter(), nullptr);
  EXPECT_FALSE(progress_wanted(true));
}

}  // namespace
}  // namespace tessim
