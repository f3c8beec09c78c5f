// The structural checks that run before Assimp sees a file (model/io/format.hpp) under
// libFuzzer, without the import behind them (fuzz_mesh covers that, at Assimp's speed): the
// first byte picks PLY (with its scalar tags), OFF, ASCII STL or OBJ face indices, the rest is
// the file's content.
// Every input must pass or end as an InputError naming the file, element and reason.
#include <cstddef>
#include <cstdint>
#include <string>

#include "model/base/error.hpp"
#include "model/io/format.hpp"
#include "model/io/ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string content(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    switch (data[0] % 4) {
      case 0:
        tessim::io::check_ply("fuzz.ply", content);
        (void)tessim::io::read_ply_tags("fuzz.ply", content);  // after the check, as import_mesh reads tags
        break;
      case 1: tessim::io::check_off("fuzz.off", content); break;
      case 2: tessim::io::check_stl("fuzz.stl", content); break;
      default: {
        const auto bad = tessim::io::find_bad_obj_face("fuzz.obj", content);
        if (bad && bad->what()[0] == '\0') __builtin_trap();  // a finding must say what is wrong
        break;
      }
    }
  } catch (const tessim::InputError& e) {
    if (e.what()[0] == '\0') __builtin_trap();
  }
  return 0;
}
