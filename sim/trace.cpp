#include "sim/trace.hpp"

#include <cstdio>

namespace tessim::sim {

namespace {

constexpr int kPid = 1;
// Thread ids: INT blocks 1..N, then the state tracks.
constexpr int kTidCpg = 1000;
constexpr int kTidTe = 1001;
constexpr int kTidGpe = 1002;

}  // namespace

TraceWriter::TraceWriter(const std::filesystem::path& path, int int_blocks, std::uint64_t window_cycles)
    : out_(path), window_(window_cycles) {
  out_.stream() << "{\"otherData\":{\"time_unit\":\"1 us = 1 cycle\"},"
                   "\"traceEvents\":[\n";
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "{\"name\":\"process_name\",\"ph\":\"M\",\"pid\":%d,\"args\":{\"name\":\"tessellation unit\"}}",
                kPid);
  event(buf);
  auto thread = [&](int tid, const std::string& name) {
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":%d,\"tid\":%d,\"args\":{\"name\":\"%s\"}}",
                  kPid, tid, name.c_str());
    event(buf);
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"thread_sort_index\",\"ph\":\"M\",\"pid\":%d,\"tid\":%d,\"args\":{\"sort_index\":%d}}",
                  kPid, tid, tid);
    event(buf);
  };
  thread(kTidCpg, "CPG");
  thread(kTidTe, "TE");
  for (int b = 0; b < int_blocks; ++b) thread(1 + b, "INT " + std::to_string(b));
  thread(kTidGpe, "GPE");
}

TraceWriter::~TraceWriter() = default;

void TraceWriter::event(const std::string& json) {
  if (!first_event_) out_.stream() << ",\n";
  first_event_ = false;
  out_.stream() << json;
}

void TraceWriter::close_span(Span& span, int tid, std::uint64_t end) {
  if (span.name == nullptr || end <= span.start) return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "{\"name\":\"%s\",\"ph\":\"X\",\"ts\":%llu,\"dur\":%llu,\"pid\":%d,\"tid\":%d}",
                span.name, static_cast<unsigned long long>(span.start),
                static_cast<unsigned long long>(end - span.start), kPid, tid);
  event(buf);
}

void TraceWriter::update_span(Span& span, int tid, const char* name, std::uint64_t cycle) {
  if (span.name == name) return;  // names are static strings: pointer equality is identity
  close_span(span, tid, cycle);
  span.name = name;
  span.start = cycle;
}

void TraceWriter::counter(const char* name, int value, std::uint64_t ts) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "{\"name\":\"%s\",\"ph\":\"C\",\"ts\":%llu,\"pid\":%d,\"args\":{\"count\":%d}}",
                name, static_cast<unsigned long long>(ts), kPid, value);
  event(buf);
}

bool TraceWriter::on_cycle(const Unit& unit, const GpeCycle& gpe) {
  const CycleActivity& a = unit.activity();
  if (a.cycle >= window_) return false;
  const std::uint64_t t = a.cycle;
  char buf[200];
  for (int i = 0; i < a.ops_issued; ++i) {
    const IssuedOp& op = unit.issued_ops()[i];
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"op%d v%llu\",\"ph\":\"X\",\"ts\":%llu,\"dur\":1,\"pid\":%d,\"tid\":%d,"
                  "\"args\":{\"vertex\":%llu,\"op\":%d,\"context\":%d}}",
                  op.op, static_cast<unsigned long long>(op.vertex), static_cast<unsigned long long>(t), kPid,
                  1 + op.block, static_cast<unsigned long long>(op.vertex), op.op, op.context);
    event(buf);
  }
  update_span(cpg_, kTidCpg, to_string(a.cpg_action), t);
  update_span(te_, kTidTe, to_string(a.te), t);
  update_span(gpe_, kTidGpe, to_string(gpe.cls), t);
  // Occupancy after the clock edge of cycle t, i.e. during cycle t + 1.
  if (unit.tri_fifo_count() != tri_count_) counter("TRI FIFO", tri_count_ = unit.tri_fifo_count(), t + 1);
  if (unit.vtx_fifo_count() != vtx_count_) counter("VTX FIFO", vtx_count_ = unit.vtx_fifo_count(), t + 1);
  if (unit.contexts_in_use() != contexts_) counter("TE contexts", contexts_ = unit.contexts_in_use(), t + 1);
  last_cycle_ = t + 1;
  return last_cycle_ < window_;
}

void TraceWriter::finish() {
  if (finished_) return;
  close_span(cpg_, kTidCpg, last_cycle_);
  close_span(te_, kTidTe, last_cycle_);
  close_span(gpe_, kTidGpe, last_cycle_);
  out_.stream() << "\n]}\n";
  out_.commit();
  finished_ = true;
}

}  // namespace tessim::sim
