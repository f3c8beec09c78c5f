// The statistics over time (docs/statistics.md, "timeline"): a run's cycles in at most kBuckets
// consecutive buckets of equal width, each with exact counts of the per-cycle classes. When a
// cycle falls past the last bucket, neighbouring pairs merge and the width doubles, so the
// memory is fixed at construction.
//
// The counts come from the run's cumulative counters (Unit, Gpe), read only at bucket
// boundaries: a bucket is the difference of the counters at its two ends. So a cycle costs the
// caller one comparison with next_boundary(), nothing more.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "sim/base/counter_registry.hpp"

namespace tessim::sim {

class Timeline {
 public:
  static constexpr std::size_t kBuckets = 256;  // even: pairs merge

  // Counts over some cycles: a bucket, or the run's totals from cycle 0.
  struct Bucket {
    ClassCounts<TeClass> te;    // cycles by TeClass
    ClassCounts<GpeClass> gpe;  // cycles by GpeClass
    std::uint64_t int_busy = 0;  // block-cycles: operations issued
    std::uint64_t cpg_busy = 0;  // cycles of CpgClass::Busy
    std::uint64_t vertices = 0;  // vertices out (popped from the VTX FIFO)
    bool operator==(const Bucket&) const = default;
  };
  // One cycle that issues nothing and moves no vertex (of a fast-forwarded stretch).
  static Bucket quiet_cycle(TeClass te, CpgClass cpg, GpeClass gpe);

  Timeline() : buckets_(kBuckets) {}

  // The cycle count at which the current bucket ends.
  std::uint64_t next_boundary() const { return end_; }
  // The run has reached next_boundary() cycles; `totals`: its counts from cycle 0 until then.
  void close(const Bucket& totals);
  // The run has reached `cycles` (>= next_boundary() or not) with a stretch of identical cycles,
  // each `one`, since the last boundary that was closed: closes every boundary up to `cycles`.
  void close_within(const Bucket& totals, std::uint64_t cycles, const Bucket& one);
  // The run ended after `cycles` cycles with `totals`: the last bucket, when not empty.
  void finish(const Bucket& totals, std::uint64_t cycles);

  // Timelines of consecutive runs (the chunks of a chunked run, sim/run/chunked.hpp) as one, exact:
  // each re-bucketed to the widest width among them (a run's buckets start at its cycle 0, so
  // whole groups merge), appended in order, and neighbouring pairs merged, the width doubling,
  // while there are more than kBuckets. Every run's last bucket may be partial, so any bucket
  // may hold fewer than bucket_cycles() cycles (cycles(i) says how many).
  static Timeline concatenate(std::span<const Timeline> parts);

  std::uint64_t bucket_cycles() const { return width_; }  // width of every bucket but the last
  std::size_t size() const { return count_; }              // buckets (after finish())
  const Bucket& bucket(std::size_t i) const { return buckets_[i]; }
  std::uint64_t cycles(std::size_t i) const {
    if (!cycles_.empty()) return cycles_[i];
    return i + 1 == count_ && last_ > 0 ? last_ : width_;
  }

 private:
  void store(const Bucket& totals);  // the bucket from start_ to `totals`

  std::vector<Bucket> buckets_;  // kBuckets entries, allocated once
  std::size_t count_ = 0;        // buckets stored
  std::uint64_t width_ = 1;      // cycles per bucket
  std::uint64_t end_ = 1;        // cycle count at which the current bucket ends
  std::uint64_t last_ = 0;       // cycles of a partial last bucket (after finish())
  Bucket start_;                 // totals at the start of the current bucket
  std::vector<std::uint64_t> cycles_;  // a concatenation's cycles per bucket (else empty)
};

// The "timeline" object of the statistics JSON.
nlohmann::json to_json(const Timeline& t);

}  // namespace tessim::sim
