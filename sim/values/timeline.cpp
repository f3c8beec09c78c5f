#include "sim/values/timeline.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace tessim::sim {

namespace {

// a - k·b, field by field.
Timeline::Bucket minus(const Timeline::Bucket& a, const Timeline::Bucket& b, std::uint64_t k = 1) {
  Timeline::Bucket d;
  for (std::size_t c = 0; c < d.te.size(); ++c) d.te[c] = a.te[c] - k * b.te[c];
  for (std::size_t c = 0; c < d.gpe.size(); ++c) d.gpe[c] = a.gpe[c] - k * b.gpe[c];
  d.int_busy = a.int_busy - k * b.int_busy;
  d.cpg_busy = a.cpg_busy - k * b.cpg_busy;
  d.vertices = a.vertices - k * b.vertices;
  return d;
}

Timeline::Bucket plus(const Timeline::Bucket& a, const Timeline::Bucket& b) {
  Timeline::Bucket s;
  for (std::size_t c = 0; c < s.te.size(); ++c) s.te[c] = a.te[c] + b.te[c];
  for (std::size_t c = 0; c < s.gpe.size(); ++c) s.gpe[c] = a.gpe[c] + b.gpe[c];
  s.int_busy = a.int_busy + b.int_busy;
  s.cpg_busy = a.cpg_busy + b.cpg_busy;
  s.vertices = a.vertices + b.vertices;
  return s;
}

}  // namespace

Timeline::Bucket Timeline::quiet_cycle(TeClass te, CpgClass cpg, GpeClass gpe) {
  Bucket b;
  b.te[static_cast<std::size_t>(te)] = 1;
  b.gpe[static_cast<std::size_t>(gpe)] = 1;
  b.cpg_busy = cpg == CpgClass::Busy;
  return b;
}

void Timeline::store(const Bucket& totals) {
  if (count_ == kBuckets) {
    // A bucket past the last: bucket i takes the cycles of 2i and 2i + 1 (all full), and the new
    // one is the first after them, twice as wide (close() planned its end so).
    for (std::size_t i = 0; i < kBuckets / 2; ++i) buckets_[i] = plus(buckets_[2 * i], buckets_[2 * i + 1]);
    count_ = kBuckets / 2;
    width_ *= 2;
  }
  buckets_[count_++] = minus(totals, start_);
  start_ = totals;
}

void Timeline::close(const Bucket& totals) {
  store(totals);
  end_ += count_ == kBuckets ? 2 * width_ : width_;
}

void Timeline::close_within(const Bucket& totals, std::uint64_t cycles, const Bucket& one) {
  while (end_ <= cycles) close(minus(totals, one, cycles - end_));
}

void Timeline::finish(const Bucket& totals, std::uint64_t cycles) {
  if (cycles > end_)
    throw std::logic_error("Timeline: finished at cycle " + std::to_string(cycles) + " past the open bucket's end " +
                           std::to_string(end_));
  const std::uint64_t begin = end_ - (count_ == kBuckets ? 2 * width_ : width_);
  if (cycles == begin) return;  // the run ended on a boundary
  store(totals);
  last_ = cycles - begin;
}

Timeline Timeline::concatenate(std::span<const Timeline> parts) {
  std::uint64_t width = 1;
  for (const Timeline& t : parts) width = std::max(width, t.width_);
  std::vector<Bucket> buckets;
  std::vector<std::uint64_t> cycles;
  for (const Timeline& t : parts) {
    const std::uint64_t group = width / t.width_;  // both powers of two
    for (std::size_t i = 0; i < t.count_; ++i) {
      if (i % group == 0) {
        buckets.emplace_back();
        cycles.push_back(0);
      }
      buckets.back() = plus(buckets.back(), t.buckets_[i]);
      cycles.back() += t.cycles(i);
    }
  }
  while (buckets.size() > kBuckets) {
    const std::size_t n = (buckets.size() + 1) / 2;
    for (std::size_t i = 0; i < n; ++i) {
      const bool pair = 2 * i + 1 < buckets.size();
      buckets[i] = pair ? plus(buckets[2 * i], buckets[2 * i + 1]) : buckets[2 * i];
      cycles[i] = pair ? cycles[2 * i] + cycles[2 * i + 1] : cycles[2 * i];
    }
    buckets.resize(n);
    cycles.resize(n);
    width *= 2;
  }
  Timeline r;
  std::copy(buckets.begin(), buckets.end(), r.buckets_.begin());
  r.count_ = buckets.size();
  r.width_ = width;
  r.cycles_ = std::move(cycles);
  std::uint64_t total = 0;
  for (std::uint64_t c : r.cycles_) total += c;
  r.end_ = total;  // finished: nothing more is closed
  return r;
}

nlohmann::json to_json(const Timeline& t) {
  using nlohmann::json;
  const std::size_t n = t.size();
  auto series = [&](auto of) {
    json a = json::array();
    for (std::size_t i = 0; i < n; ++i) a.push_back(of(i));
    return a;
  };
  json te = json::object();
  for (TeClass c : kTeClasses)
    te[to_string(c)] = series([&](std::size_t i) { return t.bucket(i).te[static_cast<std::size_t>(c)]; });
  json gpe = json::object();
  for (GpeClass c : kGpeClasses)
    gpe[to_string(c)] = series([&](std::size_t i) { return t.bucket(i).gpe[static_cast<std::size_t>(c)]; });
  return {{"buckets", n},
          {"bucket_cycles", t.bucket_cycles()},
          {"cycles", series([&](std::size_t i) { return t.cycles(i); })},
          {"te", te},
          {"int_busy", series([&](std::size_t i) { return t.bucket(i).int_busy; })},
          {"cpg_busy", series([&](std::size_t i) { return t.bucket(i).cpg_busy; })},
          {"gpe", gpe},
          {"vertices_out", series([&](std::size_t i) { return t.bucket(i).vertices; })}};
}

}  // namespace tessim::sim
