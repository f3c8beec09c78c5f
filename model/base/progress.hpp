// Progress of a long run for a person at a terminal: work units done of a total, the rate and
// the time left, redrawn in place on one line. The workers only add to an atomic counter (one
// relaxed add per patch or triangle, never a clock or an allocation in their loops); a thread
// of the meter's own reads it about ten times a second and redraws the line.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

namespace tessim {

// The line and its timing, without a thread: drawn when draw() is called (tests inject the
// clock and the stream).
class ProgressMeter {
 public:
  using Clock = std::function<double()>;  // seconds, monotonic

  // `what`: the run ("sim"), `unit`: what is counted ("vertices"), `total`: units of the whole run.
  ProgressMeter(std::string what, std::string unit, std::uint64_t total, std::ostream& out, Clock clock);

  std::atomic<std::uint64_t>& counter() { return done_; }
  void advance(std::uint64_t units) { done_.fetch_add(units, std::memory_order_relaxed); }

  // Redraws the line ("\r" + text, padded over the previous one) unless it was drawn less than
  // a tenth of a second ago.
  void draw();
  // The final line (all done, elapsed time, average rate) and a newline; nothing when the line
  // was never drawn.
  void finish();
  // Erases the line (a run that failed: its error message starts at the line's beginning).
  void clear();

  // "sim  123.4 k/1.34 M vertices  9.2%  45.6 k vertices/s  ETA 0:27" at time `now`.
  std::string line(double now) const;

 private:
  std::string what_, unit_;
  std::uint64_t total_;
  std::ostream& out_;
  Clock clock_;
  std::atomic<std::uint64_t> done_{0};
  double start_;
  double last_draw_ = -1.0;
  std::size_t drawn_width_ = 0;
};

// Seconds on std::chrono::steady_clock.
double steady_seconds();

// The help of the commands' --quiet flag.
inline constexpr const char* kQuietHelp =
    "no progress line (shown on standard error only when it is a terminal: done/total, rate, ETA)";

// True when progress should be shown: standard error is a terminal and not `quiet`.
bool progress_wanted(bool quiet);

// A meter on standard error redrawn by a thread of its own, or nothing at all (no thread, not a
// byte written) when progress is not wanted. Hand counter() (nullptr when inactive) to the run;
// call finish() after a run that succeeded; the destructor erases a line left unfinished.
class ProgressDisplay {
 public:
  ProgressDisplay(std::string what, std::string unit, std::uint64_t total, bool quiet);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  std::atomic<std::uint64_t>* counter() { return meter_ ? &meter_->counter() : nullptr; }
  void finish();

 private:
  void stop();
  std::unique_ptr<ProgressMeter> meter_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace tessim
