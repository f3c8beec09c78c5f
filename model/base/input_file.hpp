// Input files read whole into memory (configuration, statistics, coverage, embedded images):
// docs/architecture.md, Bad input. Each kind has a size limit, generous for what tessim writes
// itself but finite, so that a wrong path (/dev/zero, a huge log) is refused at once instead
// of filling the memory; only regular files are read (a device or pipe has no size to check
// and may never end or never start: reading one would block or grow without bound).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace tessim {

inline constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
// A configuration file holds a few dozen keys (well under 4 KiB).
inline constexpr std::uint64_t kConfigFileLimit = 1 * kMiB;
// Statistics (tessim sim --stats: some 100 KiB with the 256-bucket timeline) and functional
// coverage (tessim cosim --coverage: some 10 KiB).
inline constexpr std::uint64_t kDataFileLimit = 64 * kMiB;
// A PNG embedded by tessim report: the largest image tessim render writes (8192 x 8192 pixels,
// 8-bit RGB) is at most 192 MiB even uncompressed.
inline constexpr std::uint64_t kImageFileLimit = 256 * kMiB;

// The bytes of the regular file `path`, at most `max_bytes` of them. Throws InputError(path,
// element, reason) when the path does not exist, is a directory, is not a regular file (a FIFO,
// device or socket: refused without opening it for reading, so a pipe without a writer cannot
// block), cannot be read, or holds more than `max_bytes` ("larger than N MiB").
std::string read_whole_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                            const std::string& element = "input");

// "1 MiB", "64 MiB", "512 KiB", "100 bytes": a limit in messages.
std::string byte_size_text(std::uint64_t bytes);

}  // namespace tessim
