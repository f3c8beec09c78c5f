#include "sim/run/trace.hpp"

#include <zlib.h>

#include <array>
#include <cstdio>
#include <stdexcept>

namespace tessim::sim {

namespace {

constexpr int kPid = 1;
// Thread ids: INT blocks 1..N, then the state tracks, then the contexts.
constexpr int kTidCpg = 1000;
constexpr int kTidTe = 1001;
constexpr int kTidGpe = 1002;
constexpr int kTidContext = 2000;

// A write-only stream buffer that gzip-compresses into another stream (zlib's deflate with a
// gzip header), so that a trace of hundreds of megabytes never exists uncompressed.
class GzipBuf : public std::streambuf {
 public:
  explicit GzipBuf(std::ostream& sink) : sink_(sink) {
    if (deflateInit2(&z_, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
      throw std::runtime_error("zlib: deflateInit2 failed");
    setp(in_.data(), in_.data() + in_.size());
  }
  ~GzipBuf() override { deflateEnd(&z_); }
  GzipBuf(const GzipBuf&) = delete;
  GzipBuf& operator=(const GzipBuf&) = delete;

  // Compresses what is left and writes the gzip trailer.
  void finish() {
    deflate_input(Z_FINISH);
    sink_.flush();
  }

 protected:
  int_type overflow(int_type ch) override {
    deflate_input(Z_NO_FLUSH);
    if (ch != traits_type::eof()) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override {
    deflate_input(Z_NO_FLUSH);
    return sink_ ? 0 : -1;
  }

 private:
  void deflate_input(int flush) {
    z_.next_in = reinterpret_cast<Bytef*>(pbase());
    z_.avail_in = static_cast<uInt>(pptr() - pbase());
    do {
      z_.next_out = reinterpret_cast<Bytef*>(out_.data());
      z_.avail_out = static_cast<uInt>(out_.size());
      const int rc = deflate(&z_, flush);
      if (rc == Z_STREAM_ERROR) throw std::runtime_error("zlib: deflate failed");
      sink_.write(out_.data(), static_cast<std::streamsize>(out_.size() - z_.avail_out));
    } while (z_.avail_out == 0 || (flush == Z_FINISH && z_.avail_in > 0));
    setp(in_.data(), in_.data() + in_.size());
  }

  std::ostream& sink_;
  z_stream z_{};
  std::array<char, 1 << 16> in_{};
  std::array<char, 1 << 16> out_{};
};

bool gzip_path(const std::filesystem::path& p) { return p.extension() == ".gz"; }

}  // namespace

TraceWriter::TraceWriter(const std::filesystem::path& path, int int_blocks, int contexts, TraceWindow window)
    : out_(path, gzip_path(path)), window_(window), contexts_(contexts), in_context_(static_cast<std::size_t>(contexts)) {
  if (gzip_path(path)) {
    gzip_ = std::make_unique<GzipBuf>(out_.stream());
    gzip_stream_ = std::make_unique<std::ostream>(gzip_.get());
    os_ = gzip_stream_.get();
  } else {
    os_ = &out_.stream();
  }
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "{\"otherData\":{\"time_unit\":\"1 us = 1 cycle\",\"first_cycle\":%llu,\"end_cycle\":%llu},"
                "\"traceEvents\":[\n",
                static_cast<unsigned long long>(window.from), static_cast<unsigned long long>(window.to));
  *os_ << buf;
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
  for (int c = 0; c < contexts; ++c) thread(kTidContext + c, "context " + std::to_string(c));
}

TraceWriter::~TraceWriter() = default;

void TraceWriter::event(const char* json) {
  if (!first_event_) *os_ << ",\n";
  first_event_ = false;
  *os_ << json;
}

void TraceWriter::close_span(Span& span, int tid, std::uint64_t end) {
  if (span.name == nullptr || end <= span.start) return;
  char buf[200];
  if (span.has_triangle) {
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"%s t%u\",\"ph\":\"X\",\"ts\":%llu,\"dur\":%llu,\"pid\":%d,\"tid\":%d,"
                  "\"args\":{\"triangle\":%u}}",
                  span.name, span.triangle, static_cast<unsigned long long>(span.start),
                  static_cast<unsigned long long>(end - span.start), kPid, tid, span.triangle);
  } else {
    std::snprintf(buf, sizeof buf, "{\"name\":\"%s\",\"ph\":\"X\",\"ts\":%llu,\"dur\":%llu,\"pid\":%d,\"tid\":%d}",
                  span.name, static_cast<unsigned long long>(span.start),
                  static_cast<unsigned long long>(end - span.start), kPid, tid);
  }
  event(buf);
}

void TraceWriter::update_span(Span& span, int tid, const char* name, std::uint64_t cycle, bool has_triangle,
                              std::uint32_t triangle) {
  // Names are static strings: pointer equality is identity.
  if (span.name == name && span.has_triangle == has_triangle && span.triangle == triangle) return;
  close_span(span, tid, cycle);
  span = Span{name, triangle, has_triangle, cycle};
}

void TraceWriter::close_vertex(int context, std::uint64_t end) {
  Vertex& v = in_context_[static_cast<std::size_t>(context)];
  if (!v.valid) return;
  v.valid = false;
  if (end <= v.start) return;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "{\"name\":\"v%llu p%u\",\"ph\":\"X\",\"ts\":%llu,\"dur\":%llu,\"pid\":%d,\"tid\":%d,"
                "\"args\":{\"vertex\":%llu,\"patch\":%u}}",
                static_cast<unsigned long long>(v.vertex), v.patch, static_cast<unsigned long long>(v.start),
                static_cast<unsigned long long>(end - v.start), kPid, kTidContext + context,
                static_cast<unsigned long long>(v.vertex), v.patch);
  event(buf);
}

void TraceWriter::counter(const char* name, int value, std::uint64_t ts) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "{\"name\":\"%s\",\"ph\":\"C\",\"ts\":%llu,\"pid\":%d,\"args\":{\"count\":%d}}",
                name, static_cast<unsigned long long>(ts), kPid, value);
  event(buf);
}

bool TraceWriter::on_cycle(const Unit& unit, const GpeCycle& gpe) {
  const CycleActivity& a = unit.activity();
  if (a.cycle >= window_.to) return false;
  if (a.cycle < window_.from) return true;  // the run has not reached the window yet
  const std::uint64_t t = a.cycle;
  char buf[240];
  // Contexts are allocated and retired in a ring: vertex v (numbered from reset) is in context
  // v mod V.
  for (int i = 0; i < a.ops_issued; ++i) {
    const IssuedOp& op = unit.issued_ops()[i];
    const Vertex& v = in_context_[static_cast<std::size_t>(op.context)];
    std::snprintf(buf, sizeof buf,
                  "{\"name\":\"op%d v%llu\",\"ph\":\"X\",\"ts\":%llu,\"dur\":1,\"pid\":%d,\"tid\":%d,"
                  "\"args\":{\"vertex\":%llu,\"op\":%d,\"context\":%d%s%s}}",
                  op.op, static_cast<unsigned long long>(op.vertex), static_cast<unsigned long long>(t), kPid,
                  1 + op.block, static_cast<unsigned long long>(op.vertex), op.op, op.context,
                  v.valid ? ",\"patch\":" : "", v.valid ? std::to_string(v.patch).c_str() : "");
    event(buf);
  }
  const bool cpg_idle = a.cpg_action == CpgAction::Idle;
  update_span(cpg_, kTidCpg, to_string(a.cpg_action), t, !cpg_idle, cpg_idle ? 0 : a.cpg_triangle);
  if (a.cpg_action == CpgAction::Write) {
    writes_.emplace_back(a.cpg_triangle, t);
    if (writes_.size() > 16) writes_.pop_front();
  }
  update_span(te_, kTidTe, to_string(a.te), t);
  update_span(gpe_, kTidGpe, to_string(gpe.cls), t);
  if (a.retired) close_vertex(static_cast<int>(a.retired_vertex % static_cast<std::uint64_t>(contexts_)), t + 1);
  if (a.allocated) {
    // The context holds the vertex from the next cycle on; a flow joins it to its patch's write.
    const int c = static_cast<int>(a.allocated_vertex % static_cast<std::uint64_t>(contexts_));
    close_vertex(c, t + 1);
    in_context_[static_cast<std::size_t>(c)] = Vertex{true, a.allocated_vertex, a.allocated_patch, t + 1};
    for (const auto& [patch, write] : writes_) {
      if (patch != a.allocated_patch) continue;
      for (const auto& [ph, ts, tid] : {std::tuple{"s", write, kTidCpg}, std::tuple{"f", t + 1, kTidContext + c}}) {
        std::snprintf(buf, sizeof buf,
                      "{\"name\":\"patch %u\",\"cat\":\"patch\",\"ph\":\"%s\",%s\"id\":%llu,\"ts\":%llu,\"pid\":%d,"
                      "\"tid\":%d}",
                      patch, ph, *ph == 'f' ? "\"bp\":\"e\"," : "",
                      static_cast<unsigned long long>(a.allocated_vertex), static_cast<unsigned long long>(ts), kPid,
                      tid);
        event(buf);
      }
      break;
    }
  }
  // Occupancy after the clock edge of cycle t, i.e. during cycle t + 1.
  if (unit.tri_fifo_count() != tri_count_) counter("TRI FIFO", tri_count_ = unit.tri_fifo_count(), t + 1);
  if (unit.vtx_fifo_count() != vtx_count_) counter("VTX FIFO", vtx_count_ = unit.vtx_fifo_count(), t + 1);
  if (unit.contexts_in_use() != contexts_in_use_) counter("TE contexts", contexts_in_use_ = unit.contexts_in_use(), t + 1);
  last_cycle_ = t + 1;
  return last_cycle_ < window_.to;
}

void TraceWriter::finish() {
  if (finished_) return;
  close_span(cpg_, kTidCpg, last_cycle_);
  close_span(te_, kTidTe, last_cycle_);
  close_span(gpe_, kTidGpe, last_cycle_);
  for (int c = 0; c < contexts_; ++c) close_vertex(c, last_cycle_);
  *os_ << "\n]}\n";
  if (gzip_) static_cast<GzipBuf*>(gzip_.get())->finish();
  out_.commit();
  finished_ = true;
}

}  // namespace tessim::sim
