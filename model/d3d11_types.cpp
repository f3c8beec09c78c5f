#include "model/d3d11_types.hpp"

namespace tessim {

const char* partitioning_name(Partitioning p) {
  switch (p) {
    case Partitioning::integer: return "integer";
    case Partitioning::pow2: return "pow2";
    case Partitioning::fractional_odd: return "fractional_odd";
    case Partitioning::fractional_even: return "fractional_even";
  }
  return "?";
}

std::optional<Partitioning> parse_partitioning(std::string_view name) {
  for (Partitioning p : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                         Partitioning::fractional_even})
    if (name == partitioning_name(p)) return p;
  return std::nullopt;
}

const char* winding_name(Winding w) { return w == Winding::ccw ? "ccw" : "cw"; }

std::optional<Winding> parse_winding(std::string_view name) {
  if (name == "ccw") return Winding::ccw;
  if (name == "cw") return Winding::cw;
  return std::nullopt;
}

}  // namespace tessim
