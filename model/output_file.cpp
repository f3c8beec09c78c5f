#include "model/output_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <atomic>
#include <cstring>
#include <mutex>
#include <system_error>

#include "model/error.hpp"

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

}  // namespace

AtomicOutput::AtomicOutput(std::filesystem::path target, bool binary) : target_(std::move(target)) {
  std::error_code ec;
  if (std::filesystem::is_directory(target_, ec))
    throw InputError(target_.string(), "output", "is a directory");
  temp_ = target_;
  temp_ += ".tmp-" + std::to_string(::getpid());
  // Registered before the file exists: a signal in between finds nothing to remove.
  slot_ = register_temporary(temp_);
  out_.open(temp_, binary ? std::ios::out | std::ios::binary | std::ios::trunc
                          : std::ios::out | std::ios::trunc);
  if (!out_) {
    unregister_temporary(slot_);
    slot_ = -1;
    throw InputError(target_.string(), "output", "cannot open for writing");
  }
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
  unregister_temporary(slot_);
}

void AtomicOutput::commit() {
  out_.flush();
  if (!out_) throw InputError(target_.string(), "output", "write failed");
  out_.close();
  commit_external();
}

void AtomicOutput::commit_external() {
  if (out_.is_open()) out_.close();
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw InputError(target_.string(), "output", "cannot move into place: " + ec.message());
  committed_ = true;
  // The temporary is gone: a signal now must not remove anything (the name could be reused).
  unregister_temporary(slot_);
  slot_ = -1;
}

}  // namespace tessim
