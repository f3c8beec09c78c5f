// Mesh import under libFuzzer: the first byte picks the format (PLY, OBJ, STL, OFF), the rest is
// the file. Every input must load or end as an InputError (docs/architecture.md, Bad input);
// anything else — a crash, a sanitizer report, another exception — is a finding.
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "model/base/error.hpp"
#include "model/mesh_io.hpp"

namespace {

const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    const char* shm = "/dev/shm";
    std::filesystem::path base = std::filesystem::exists(shm) ? shm : std::filesystem::temp_directory_path();
    std::filesystem::path d = base / ("tessim-fuzz-mesh-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static constexpr std::array<const char*, 4> kExtensions{".ply", ".obj", ".stl", ".off"};
  const std::filesystem::path path = scratch_dir() / (std::string("input") + kExtensions[data[0] % 4]);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const tessim::Mesh mesh = tessim::load_mesh(path);
    // A loaded mesh is usable: its statistics are computed without surprises.
    (void)tessim::mesh_stats(mesh);
  } catch (const tessim::InputError&) {
    // rejected with file, element and reason: the documented outcome for bad input
  }
  std::filesystem::remove(path);
  return 0;
}
