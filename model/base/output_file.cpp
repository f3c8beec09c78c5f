#include "model/base/output_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <iostream>
#include <mutex>
#include <optional>
#include <string_view>
#include <system_error>

#include "model/base/error.hpp"

namespace tessim {

namespace {

// ---------------------------------------------------------------------------------------------
// Temporaries pending at SIGINT, SIGTERM or SIGHUP are removed before the process dies of the
// signal. The handler may only touch what is async-signal-safe: a fixed table of paths, each
// published by an atomic state, and unlink().

constexpr std::size_t kSlots = 64;
constexpr std::size_t kPathBytes = 4096;

enum SlotState : int { kFree = 0, kClaimed = 1, kPending = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes] = {};
};

std::array<Slot, kSlots> g_slots;
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void remove_temporaries_and_reraise(int sig) {
  const int saved_errno = errno;
  for (Slot& slot : g_slots)
    if (slot.state.load(std::memory_order_acquire) == kPending) ::unlink(slot.path);
  // Die of the signal as without the handler, so that the parent sees how the process ended.
  struct sigaction dfl = {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  errno = saved_errno;
  ::raise(sig);
}

void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : kCleanupSignals) {
      struct sigaction old = {};
      if (::sigaction(sig, nullptr, &old) != 0) continue;
      // A signal the caller ignores (nohup, background jobs) or handles itself stays that way.
      if (old.sa_handler != SIG_DFL) continue;
      struct sigaction sa = {};
      sa.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&sa.sa_mask);
      for (int other : kCleanupSignals) sigaddset(&sa.sa_mask, other);
      sa.sa_flags = 0;
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

// SIGBUS while a BusErrorExit exists: the temporaries go, the message is printed, status 2.
constexpr std::size_t kBusMessageBytes = 1024;
char g_bus_message[kBusMessageBytes] = {};
std::atomic<std::size_t> g_bus_message_length{0};
std::mutex g_bus_mutex;
int g_bus_depth = 0;  // guarded by g_bus_mutex
struct sigaction g_bus_previous = {};

extern "C" void remove_temporaries_and_exit(int /*sig*/) {
  for (Slot& slot : g_slots)
    if (slot.state.load(std::memory_order_acquire) == kPending) ::unlink(slot.path);
  const std::size_t length = g_bus_message_length.load(std::memory_order_acquire);
  for (std::size_t done = 0; done < length;) {
    const ssize_t n = ::write(2, g_bus_message + done, length - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::_exit(2);
}

// Returns the slot now holding `path`, or -1 when the table is full or the path too long (the
// temporary is then still removed on every other way out, only not on a signal).
int register_temporary(const std::filesystem::path& path) {
  install_handlers_once();
  std::error_code ec;
  const std::string absolute = std::filesystem::absolute(path, ec).string();
  const std::string& text = ec ? path.string() : absolute;
  if (text.size() >= kPathBytes) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kClaimed, std::memory_order_acq_rel)) {
      std::memcpy(g_slots[i].path, text.c_str(), text.size() + 1);
      g_slots[i].state.store(kPending, std::memory_order_release);
      return static_cast<int>(i);
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[static_cast<std::size_t>(slot)].state.store(kFree, std::memory_order_release);
}

// The descriptor a path names when it is one of the names under which a process reaches its own
// open files (/dev/stdout, /dev/fd/N, /proc/self/fd/N): these are written as the descriptor, never
// replaced or truncated behind the back of whoever opened it (`>> log` keeps appending).
std::optional<int> own_descriptor(const std::filesystem::path& path) {
  const std::string text = path.lexically_normal().string();
  if (text == "/dev/stdin") return 0;
  if (text == "/dev/stdout") return 1;
  if (text == "/dev/stderr") return 2;
  for (std::string_view prefix : {"/dev/fd/", "/proc/self/fd/", "/proc/thread-self/fd/"}) {
    if (!text.starts_with(prefix)) continue;
    const std::string_view digits = std::string_view(text).substr(prefix.size());
    int fd = -1;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), fd);
    if (!digits.empty() && ec == std::errc() && end == digits.data() + digits.size()) return fd;
  }
  return std::nullopt;
}

std::atomic<unsigned> g_external_temporaries{0};

}  // namespace

std::filesystem::path resolve_output_path(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {  // 40: the kernel's limit on links followed (ELOOP)
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) break;
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) break;
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return p.lexically_normal();
}

OutputKind output_kind(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (path == "-") return OutputKind::Stdout;
  if (const std::optional<int> fd = own_descriptor(path)) return *fd == 1 ? OutputKind::Stdout : OutputKind::Direct;
  std::error_code ec;
  const fs::file_status st = fs::status(resolve_output_path(path), ec);
  if (fs::is_character_file(st) || fs::is_fifo(st) || fs::is_socket(st) || fs::is_block_file(st))
    return OutputKind::Direct;
  return OutputKind::File;
}

std::string output_name(const std::filesystem::path& path) {
  return path == "-" ? std::string("standard output") : path.string();
}

PendingTemporary::PendingTemporary(std::filesystem::path path) : path_(std::move(path)) {
  // Registered before the file exists: a signal in between finds nothing to remove.
  slot_ = register_temporary(path_);
}

PendingTemporary::~PendingTemporary() {
  if (slot_ == -2) return;  // kept
  std::error_code ec;
  std::filesystem::remove(path_, ec);
  unregister_temporary(slot_);
}

void PendingTemporary::keep() {
  // Unregistered first: once the name is gone, a signal must not remove anything (it could be
  // reused).
  unregister_temporary(slot_);
  slot_ = -2;
}

BusErrorExit::BusErrorExit(const std::string& file, const std::string& reason) {
  std::string message = "tessim: error: " + printable_text(file, 240) + ": output: " + printable_text(reason, 480) + "\n";
  message.resize(std::min(message.size(), kBusMessageBytes));
  const std::lock_guard<std::mutex> lock(g_bus_mutex);
  previous_message_.assign(g_bus_message, g_bus_message_length.load(std::memory_order_acquire));
  g_bus_message_length.store(0, std::memory_order_release);
  std::memcpy(g_bus_message, message.data(), message.size());
  g_bus_message_length.store(message.size(), std::memory_order_release);
  if (g_bus_depth++ == 0) {
    struct sigaction sa = {};
    sa.sa_handler = remove_temporaries_and_exit;
    sigemptyset(&sa.sa_mask);
    for (int other : kCleanupSignals) sigaddset(&sa.sa_mask, other);
    ::sigaction(SIGBUS, &sa, &g_bus_previous);
  }
}

BusErrorExit::~BusErrorExit() {
  const std::lock_guard<std::mutex> lock(g_bus_mutex);
  if (--g_bus_depth == 0) ::sigaction(SIGBUS, &g_bus_previous, nullptr);
  g_bus_message_length.store(0, std::memory_order_release);
  std::memcpy(g_bus_message, previous_message_.data(), previous_message_.size());
  g_bus_message_length.store(previous_message_.size(), std::memory_order_release);
}

AtomicOutput::AtomicOutput(std::filesystem::path target, bool binary)
    : target_(std::move(target)), kind_(output_kind(target_)) {
  const std::ios::openmode mode = binary ? std::ios::out | std::ios::binary : std::ios::out;
  const std::string name = output_name(target_);
  switch (kind_) {
    case OutputKind::Stdout:
      stream_ = &std::cout;
      return;
    case OutputKind::Direct: {
      resolved_ = target_;
      const std::optional<int> fd = own_descriptor(target_);
      if (fd == 2) {
        stream_ = &std::cerr;
        return;
      }
      // A descriptor of the process is appended to as it stands; a device or pipe has no
      // contents to truncate.
      file_.open(resolved_, fd ? mode | std::ios::app : mode);
      if (!file_) throw InputError(name, "output", std::string("cannot open for writing (") + std::strerror(errno) + ")");
      stream_ = &file_;
      return;
    }
    case OutputKind::File: {
      resolved_ = resolve_output_path(target_);
      std::error_code ec;
      if (std::filesystem::is_directory(resolved_, ec)) throw InputError(name, "output", "is a directory");
      temp_ = resolved_;
      temp_ += ".tmp-" + std::to_string(::getpid());
      pending_ = std::make_unique<PendingTemporary>(temp_);
      file_.open(temp_, mode | std::ios::trunc);
      if (!file_) {
        pending_.reset();
        throw InputError(name, "output", "cannot open for writing");
      }
      stream_ = &file_;
      return;
    }
  }
}

AtomicOutput::~AtomicOutput() {
  if (file_.is_open()) file_.close();
  pending_.reset();  // removes the temporary unless it was moved into place
  if (kind_ != OutputKind::File && !committed_ && stream_) stream_->flush();
}

const std::filesystem::path& AtomicOutput::temp_path() {
  if (temp_.empty()) {
    // A device, pipe or standard output: the writer writes a regular file, copied in at commit.
    temp_ = std::filesystem::temp_directory_path() /
            ("tessim-" + std::to_string(::getpid()) + "-" + std::to_string(g_external_temporaries++) +
             target_.filename().string() + ".tmp");
    pending_ = std::make_unique<PendingTemporary>(temp_);
  }
  return temp_;
}

void AtomicOutput::commit() {
  const std::string name = output_name(target_);
  stream_->flush();
  if (!*stream_) throw InputError(name, "output", "write failed");
  if (file_.is_open()) {
    file_.close();
    if (!file_) throw InputError(name, "output", "write failed");
  }
  if (kind_ == OutputKind::File) {
    std::error_code ec;
    std::filesystem::rename(temp_, resolved_, ec);
    if (ec) throw InputError(name, "output", "cannot move into place: " + ec.message());
    pending_->keep();
  }
  committed_ = true;
}

void AtomicOutput::commit_external() {
  const std::string name = output_name(target_);
  if (kind_ == OutputKind::File) {
    if (file_.is_open()) file_.close();
    std::error_code ec;
    std::filesystem::rename(temp_, resolved_, ec);
    if (ec) throw InputError(name, "output", "cannot move into place: " + ec.message());
    pending_->keep();
    committed_ = true;
    return;
  }
  std::ifstream in(temp_path(), std::ios::binary);
  if (!in) throw InputError(name, "output", "the written temporary " + temp_.string() + " cannot be read back");
  std::array<char, 1 << 16> buffer;
  while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0) {
    stream_->write(buffer.data(), in.gcount());
    if (!*stream_) throw InputError(name, "output", "write failed");
  }
  if (in.bad()) throw InputError(name, "output", "the written temporary " + temp_.string() + " cannot be read back");
  in.close();
  pending_.reset();  // the copy is complete: the temporary goes
  commit();
}

}  // namespace tessim
