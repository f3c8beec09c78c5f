#include "sim/ge/gpe.hpp"

#include <stdexcept>

namespace tessim::sim {

Gpe::Gpe(int cycles_per_vertex, double stall_prob, std::uint64_t seed)
    : cycles_per_vertex_(cycles_per_vertex), stall_prob_(stall_prob), seed_(seed), rng_(seed) {
  if (cycles_per_vertex < 1) throw std::invalid_argument("Gpe: cycles per vertex must be >= 1");
  if (!(stall_prob >= 0.0 && stall_prob < 1.0))
    throw std::invalid_argument("Gpe: stall probability must be in [0, 1)");
}

void Gpe::reset() {
  rng_ = SplitMix64(seed_);
  remaining_ = 0;
  stats_ = GpeStats{};
}

}  // namespace tessim::sim
