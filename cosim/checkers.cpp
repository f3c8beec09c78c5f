#include "cosim/checkers.hpp"

#include "sim/run/reference_check.hpp"

namespace tessim::cosim {

std::optional<Mismatch> OutputChecker::diff(const sim::VertexFx& e, const sim::VertexFx& a) {
  for (const sim::VertexField& f : sim::kVertexFields) {
    for (int c = 0; c < f.count; ++c) {
      const std::int64_t x = f.get(e, c), y = f.get(a, c);
      if (x == y) continue;
      std::string name = f.name;
      if (f.count > 1) name.append(1, '[').append(std::to_string(c)).append(1, ']');
      return Mismatch{name, std::to_string(x), std::to_string(y)};
    }
  }
  return std::nullopt;
}

std::optional<Mismatch> OutputChecker::check(const sim::Dut& expected, const sim::Dut& actual) const {
  if (expected.tri_ready() != actual.tri_ready())
    return Mismatch{"tri_ready", std::to_string(expected.tri_ready()), std::to_string(actual.tri_ready())};
  if (expected.vtx_valid() != actual.vtx_valid())
    return Mismatch{"vtx_valid", std::to_string(expected.vtx_valid()), std::to_string(actual.vtx_valid())};
  if (!expected.vtx_valid()) return std::nullopt;
  const sim::VertexFx e = expected.vtx(), a = actual.vtx();
  if (auto d = diff(e, a)) {
    d->expected += "  [" + sim::describe(e) + "]";
    d->actual += "  [" + sim::describe(a) + "]";
    return d;
  }
  return std::nullopt;
}

std::optional<Mismatch> CounterChecker::check(const sim::UnitCounters& e, const sim::UnitCounters& a) const {
  // Called every cycle: names are built only for a difference.
  auto diff = [](const std::string& name, std::uint64_t x, std::uint64_t y) {
    return Mismatch{"counters." + name, std::to_string(x), std::to_string(y)};
  };
  // Every counter the unit keeps, in registry order (sim/base/counter_registry.hpp): the run's
  // counts, INT busy per block, the TE's and the CPG's classes.
  for (std::size_t row = 0; row < sim::kCounterRegistry.size(); ++row) {
    const sim::CounterRow& r = sim::kCounterRegistry[row];
    const int instances = r.block == sim::CounterBlock::Int ? int_blocks_ : 1;
    for (int i = 0; i < instances; ++i) {
      const std::uint64_t* x = sim::counter_slot(e, row, i);
      if (!x) continue;  // derived (an INT block's idle) or not the unit's (the GPE's)
      const std::uint64_t y = *sim::counter_slot(a, row, i);
      if (*x == y) continue;
      return diff(r.block == sim::CounterBlock::Int ? std::string(r.name) + "[" + std::to_string(i) + "]" : r.name, *x, y);
    }
  }
  return std::nullopt;
}

}  // namespace tessim::cosim
