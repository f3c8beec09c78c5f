#include "model/base/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace tessim {

namespace {

constexpr double kRedrawSeconds = 0.1;

// 1234567 -> "1.23 M": three significant digits, SI prefix.
std::string count_text(double n) {
  static constexpr const char* kPrefixes[] = {"", " k", " M", " G", " T"};
  int p = 0;
  while (std::abs(n) >= 999.5 && p < 4) {
    n /= 1000.0;
    ++p;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g%s", n, kPrefixes[p]);
  return buf;
}

// Seconds as "m:ss" or "h:mm:ss".
std::string duration_text(double seconds) {
  const auto s = static_cast<long long>(std::llround(std::max(0.0, seconds)));
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  return buf;
}

}  // namespace

ProgressMeter::ProgressMeter(std::string what, std::string unit, std::uint64_t total, std::ostream& out, Clock clock)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), out_(out), clock_(std::move(clock)),
      start_(clock_()) {}

std::string ProgressMeter::line(double now) const {
  const std::uint64_t done = std::min(done_.load(std::memory_order_relaxed), total_);
  const double elapsed = now - start_;
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  std::string s = what_ + "  " + count_text(static_cast<double>(done)) + "/" + count_text(static_cast<double>(total_)) +
                  " " + unit_;
  char buf[64];
  std::snprintf(buf, sizeof buf, "  %.1f%%", total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0);
  s += buf;
  s += "  " + count_text(rate) + " " + unit_ + "/s";
  if (done >= total_) s += "  done in " + duration_text(elapsed);
  else if (rate > 0.0) s += "  ETA " + duration_text(static_cast<double>(total_ - done) / rate);
  else s += "  ETA --";
  return s;
}

void ProgressMeter::draw() {
  const double now = clock_();
  if (last_draw_ >= 0.0 && now - last_draw_ < kRedrawSeconds) return;
  last_draw_ = now;
  std::string text = line(now);
  const std::size_t width = text.size();
  if (width < drawn_width_) text.append(drawn_width_ - width, ' ');  // over the longer previous line
  drawn_width_ = width;
  out_ << '\r' << text << std::flush;
}

void ProgressMeter::finish() {
  if (drawn_width_ == 0) return;  // never drawn: a short run stays silent
  done_.store(std::max(done_.load(), total_));
  last_draw_ = -1.0;
  draw();
  out_ << '\n' << std::flush;
  drawn_width_ = 0;
}

void ProgressMeter::clear() {
  if (drawn_width_ == 0) return;
  out_ << '\r' << std::string(drawn_width_, ' ') << '\r' << std::flush;
  drawn_width_ = 0;
}

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool progress_wanted(bool quiet) { return !quiet && ::isatty(STDERR_FILENO) == 1; }

ProgressDisplay::ProgressDisplay(std::string what, std::string unit, std::uint64_t total, bool quiet) {
  if (!progress_wanted(quiet)) return;
  meter_ = std::make_unique<ProgressMeter>(std::move(what), std::move(unit), total, std::cerr, steady_seconds);
  thread_ = std::thread([this] {
    std::unique_lock lock(mutex_);
    const auto stopping = [this] { return stopping_; };
    // The first line after a moment: a run that ends at once draws nothing.
    if (wake_.wait_for(lock, std::chrono::milliseconds(250), stopping)) return;
    do meter_->draw();
    while (!wake_.wait_for(lock, std::chrono::milliseconds(100), stopping));
  });
}

void ProgressDisplay::stop() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ProgressDisplay::finish() {
  if (!meter_) return;
  stop();
  meter_->finish();
  meter_.reset();
}

ProgressDisplay::~ProgressDisplay() {
  if (!meter_) return;
  stop();
  meter_->clear();
}

}  // namespace tessim
