// Loading a mesh that must be refused: the InputError and the parts its message must contain.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/base/error.hpp"
#include "model/mesh_io.hpp"

namespace tessim::testing {

// Loads `file` expecting an InputError whose message contains every one of `parts`.
inline ::testing::AssertionResult rejects(const std::filesystem::path& file, const std::vector<std::string>& parts) {
  try {
    const Mesh mesh = load_mesh(file);
    return ::testing::AssertionFailure() << file << " loaded (" << mesh.vertex_count() << " vertices, "
                                         << mesh.triangle_count() << " triangles) instead of being rejected";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& part : parts)
      if (message.find(part) == std::string::npos)
        return ::testing::AssertionFailure() << "message \"" << message << "\" lacks \"" << part << "\"";
    return ::testing::AssertionSuccess() << message;
  }
}

}  // namespace tessim::testing
