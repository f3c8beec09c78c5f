#include "model/base/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "model/base/error.hpp"

namespace tessim {

namespace {

// Closes the descriptor however the read ends.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string byte_size_text(std::uint64_t bytes) {
  if (bytes >= kMiB && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
  if (bytes >= 1024 && bytes % 1024 == 0) return std::to_string(bytes / 1024) + " KiB";
  return std::to_string(bytes) + " bytes";
}

std::string read_whole_file(const std::filesystem::path& path, std::uint64_t max_bytes, const std::string& element) {
  const std::string name = path.string();
  const std::string too_large = "larger than " + byte_size_text(max_bytes) + " (the limit for this input)";
  // The kind of file is checked before it is opened for reading: open() of a FIFO without a
  // writer would block.
  struct stat st = {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(name, element, errno == ENOENT ? std::string("does not exist")
                                                    : std::string("cannot be read (") + std::strerror(errno) + ")");
  if (S_ISDIR(st.st_mode)) throw InputError(name, element, "is a directory");
  const char* kind = S_ISFIFO(st.st_mode)   ? "a pipe (FIFO)"
                     : S_ISCHR(st.st_mode)  ? "a character device"
                     : S_ISBLK(st.st_mode)  ? "a block device"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                                            : nullptr;
  if (kind || !S_ISREG(st.st_mode))
    throw InputError(name, element,
                     std::string("is ") + (kind ? kind : "not a regular file") +
                         ", not a regular file: inputs read whole are read from files (save it to a file first)");
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) throw InputError(name, element, too_large);

  // O_NONBLOCK: should the path have been replaced by a FIFO since stat(), open() still returns
  // at once, and fstat() below refuses it.
  Descriptor in{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (in.fd < 0) throw InputError(name, element, std::string("cannot be opened (") + std::strerror(errno) + ")");
  if (::fstat(in.fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw InputError(name, element, "is not a regular file: inputs read whole are read from files");

  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(in.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(name, element, std::string("read failed (") + std::strerror(errno) + ")");
    if (n == 0) break;
    // The file may grow while it is read: the limit holds for what is read, too.
    if (bytes.size() + static_cast<std::size_t>(n) > max_bytes) throw InputError(name, element, too_large);
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return bytes;
}

}  // namespace tessim
