// The four normal fields of docs/mathematics.md §4.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace tessim {

enum class NormalMode {
  Quadratic,   // Vlachos et al.: normalized mid-edge normals (default)
  Reflect,     // Boubekeur & Schlick: unnormalized reflected mid-edge normals
  Linear,      // w N1 + u N2 + v N3
  Derivative,  // normal of the cubic surface, from the last de Casteljau level
};

inline std::string_view to_string(NormalMode m) {
  switch (m) {
    case NormalMode::Quadratic: return "quadratic";
    case NormalMode::Reflect: return "reflect";
    case NormalMode::Linear: return "linear";
    case NormalMode::Derivative: return "derivative";
  }
  return "?";
}

inline std::optional<NormalMode> parse_normal_mode(std::string_view s) {
  if (s == "quadratic") return NormalMode::Quadratic;
  if (s == "reflect") return NormalMode::Reflect;
  if (s == "linear") return NormalMode::Linear;
  if (s == "derivative") return NormalMode::Derivative;
  return std::nullopt;
}

}  // namespace tessim
