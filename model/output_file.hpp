// All-or-nothing output files: data goes to a temporary file beside the target and is renamed
// into place only when complete, so a failed run never leaves a half-written result
// (docs/architecture.md, Bad input). Pending temporaries are also removed when the process is
// killed by SIGINT, SIGTERM or SIGHUP: the first AtomicOutput installs handlers for those
// signals (where they are not ignored or handled already) that unlink every pending temporary
// and re-raise the signal.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace tessim {

class AtomicOutput {
 public:
  explicit AtomicOutput(std::filesystem::path target, bool binary = false);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  ~AtomicOutput();  // removes the temporary file unless commit() succeeded

  std::ofstream& stream() { return out_; }
  // Path of the temporary file, for writers (e.g. OpenImageIO) that open files themselves.
  const std::filesystem::path& temp_path() const { return temp_; }
  // Flushes, checks for write errors and renames into place. Throws InputError on failure.
  void commit();
  // For writers that wrote temp_path() themselves: rename into place.
  void commit_external();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::ofstream out_;
  bool committed_ = false;
  int slot_ = -1;  // entry in the table of temporaries the signal handler removes
};

}  // namespace tessim
