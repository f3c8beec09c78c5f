#include "sim/run/schedule.hpp"

#include <cstdio>
#include <sstream>

namespace tessim::sim {

ScheduleRecorder::ScheduleRecorder(int table_cycles, std::size_t max_vertices)
    : table_cycles_(table_cycles), max_vertices_(max_vertices) {
  rows_.reserve(static_cast<std::size_t>(table_cycles));
  retire_cycles_.reserve(max_vertices);
}

bool ScheduleRecorder::on_cycle(const Unit& unit, const GpeCycle&) {
  const CycleActivity& a = unit.activity();
  const bool started = !rows_.empty() || a.ops_issued > 0;
  if (started && rows_.size() < static_cast<std::size_t>(table_cycles_)) {
    Row row{a.cycle, {unit.issued_ops(), unit.issued_ops() + a.ops_issued}, a.allocated, a.retired,
            a.allocated_vertex, a.retired_vertex, a.te};
    rows_.push_back(std::move(row));
  }
  if (a.retired && retire_cycles_.size() < max_vertices_) retire_cycles_.push_back(a.cycle);
  return rows_.size() < static_cast<std::size_t>(table_cycles_) || retire_cycles_.size() < max_vertices_;
}

double ScheduleRecorder::steady_cycles_per_vertex() const {
  const std::size_t n = retire_cycles_.size();
  if (n < 16) return 0.0;
  // A window of whole periods: 2520 is a multiple of every period of up to 10 vertices.
  std::size_t window = (n / 2) / 2520 * 2520;
  if (window == 0) window = n / 2;
  const std::size_t hi = n - 1, lo = hi - window;
  return static_cast<double>(retire_cycles_[hi] - retire_cycles_[lo]) / static_cast<double>(hi - lo);
}

std::string ScheduleRecorder::table(int int_blocks) const {
  std::ostringstream s;
  char buf[64];
  s << "cycle ";
  for (int b = 0; b < int_blocks; ++b) {
    std::snprintf(buf, sizeof buf, " INT%-5d", b);
    s << buf;
  }
  s << " TE              events\n";
  for (const Row& row : rows_) {
    std::snprintf(buf, sizeof buf, "%5llu ", static_cast<unsigned long long>(row.cycle));
    s << buf;
    for (int b = 0; b < int_blocks; ++b) {
      char cell[32] = ".";
      if (static_cast<std::size_t>(b) < row.ops.size()) {
        const IssuedOp& op = row.ops[static_cast<std::size_t>(b)];
        std::snprintf(cell, sizeof cell, "v%llu.%d", static_cast<unsigned long long>(op.vertex), op.op);
      }
      std::snprintf(buf, sizeof buf, " %-8s", cell);
      s << buf;
    }
    std::snprintf(buf, sizeof buf, " %-15s", to_string(row.te));
    s << buf;
    if (row.allocated) s << " alloc v" << row.allocated_vertex;
    if (row.retired) s << " retire v" << row.retired_vertex;
    s << "\n";
  }
  return s.str();
}

}  // namespace tessim::sim
