// Output files (docs/architecture.md, Bad input). What an output path names decides how it is
// written, once, when the output is opened:
//   - a regular file or a path that does not exist yet: all-or-nothing. Data goes to a temporary
//     file beside the target and is renamed into place only when complete, so a failed run never
//     leaves a half-written result. A symbolic link is followed first: its final target is
//     replaced and the link stays a link.
//   - a character device, FIFO or socket (/dev/null, a named pipe, a terminal) and the names of
//     the process's own streams (/dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N): written
//     directly, as a shell redirection would. There is nothing to rename, and nothing to remove
//     when the run fails: a reader of the pipe has seen what was written.
//   - "-": standard output, written directly.
// Pending temporaries are also removed when the process is killed by SIGINT, SIGTERM or SIGHUP:
// the first temporary installs handlers for those signals (where they are not ignored or handled
// already) that unlink every pending temporary and re-raise the signal.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>

namespace tessim {

enum class OutputKind {
  File,    // temporary beside the (link-resolved) target, renamed into place by commit()
  Direct,  // a device, FIFO, socket or a name of one of the process's streams: written in place
  Stdout,  // "-", /dev/stdout, /dev/fd/1, /proc/self/fd/1: std::cout
};

// How `path` is written (see above). Decided from what the path names now.
OutputKind output_kind(const std::filesystem::path& path);

// The path a regular output replaces: `path` with every symbolic link along it followed (relative
// links against the directory of the link), whether or not the final target exists yet.
std::filesystem::path resolve_output_path(const std::filesystem::path& path);

// The name of an output in messages: "standard output" for "-", else the path.
std::string output_name(const std::filesystem::path& path);

// A file removed when the process is killed by SIGINT, SIGTERM or SIGHUP (see above), and when
// this object is destroyed unless keep() was called: for temporaries that a library creates by
// name (a waveform recording, its side files).
class PendingTemporary {
 public:
  explicit PendingTemporary(std::filesystem::path path);
  PendingTemporary(const PendingTemporary&) = delete;
  PendingTemporary& operator=(const PendingTemporary&) = delete;
  ~PendingTemporary();

  const std::filesystem::path& path() const { return path_; }
  // The file is no longer this object's to remove (renamed away, or removed by its writer).
  void keep();

 private:
  std::filesystem::path path_;
  int slot_ = -1;  // entry in the table of temporaries the signal handler removes
};

// While one exists, SIGBUS — what a store through a memory-mapped file raises when the file
// system cannot back it, as on a full disk under a library that maps the files it writes (the FST
// writer maps its hierarchy and value tables) — removes every pending temporary, prints
// "tessim: error: FILE: output: REASON" and exits with status 2 (a failed write) instead of
// dying of the signal with the temporaries left behind. The innermost one's message is printed.
class BusErrorExit {
 public:
  BusErrorExit(const std::string& file, const std::string& reason);
  BusErrorExit(const BusErrorExit&) = delete;
  BusErrorExit& operator=(const BusErrorExit&) = delete;
  ~BusErrorExit();

 private:
  std::string previous_message_;
};

class AtomicOutput {
 public:
  explicit AtomicOutput(std::filesystem::path target, bool binary = false);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  ~AtomicOutput();  // removes the temporary file unless commit() succeeded

  OutputKind kind() const { return kind_; }
  std::ostream& stream() { return *stream_; }
  // Path for writers (e.g. OpenImageIO) that open files themselves: the temporary of a regular
  // output, else a temporary file in the system's temporary directory that commit_external()
  // copies into the device, pipe or standard output (such writers may seek, which a pipe
  // cannot).
  const std::filesystem::path& temp_path();
  // Flushes, checks for write errors and moves a temporary into place. Throws InputError.
  void commit();
  // For writers that wrote temp_path() themselves: rename into place, or copy into the device.
  void commit_external();

 private:
  std::filesystem::path target_;    // as given
  std::filesystem::path resolved_;  // the file replaced (File) or opened (Direct)
  std::filesystem::path temp_;
  OutputKind kind_;
  std::ofstream file_;
  std::ostream* stream_ = nullptr;
  bool committed_ = false;
  std::unique_ptr<PendingTemporary> pending_;
};

}  // namespace tessim
