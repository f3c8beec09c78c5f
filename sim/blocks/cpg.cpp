#include "sim/blocks/cpg.hpp"

namespace tessim::sim {

const char* to_string(CpgAction a) {
  switch (a) {
    case CpgAction::Idle: return "idle";
    case CpgAction::Accept: return "accept";
    case CpgAction::Compute: return "compute";
    case CpgAction::WaitGpe: return "wait_gpe";
    case CpgAction::Write: return "write";
    case CpgAction::Blocked: return "blocked";
  }
  return "?";
}

}  // namespace tessim::sim
