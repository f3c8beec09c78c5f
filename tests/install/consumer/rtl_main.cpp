// rtl_consumer MESH L: the installed Verilated RTL (tessim::rtl, a TESSIM_BUILD_RTL tree) on a
// whole mesh, clocked cycle by cycle in the shared testbench, against the installed cycle model:
// the two take the same number of cycles (what `tessim cosim` checks cycle by cycle).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <string>

#include "model/mesh_io.hpp"
#include "rtl/verilated/rtl_unit.hpp"
#include "sim/config/config.hpp"
#include "sim/run/simulate.hpp"
#include "sim/run/testbench.hpp"
#include "sim/values/host.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rtl_consumer MESH L\n");
    return 2;
  }
  try {
    namespace sim = tessim::sim;
    const tessim::Mesh mesh = tessim::load_mesh(argv[1]);
    sim::UnitConfig cfg;
    cfg.tess_factor = std::atoi(argv[2]);
    cfg.validate("rtl_consumer");
    const std::optional<std::string> variant = tessim::rtl::find_rtl_variant(cfg.hardware(), false);
    if (!variant) {
      std::printf("rtl no build of the default hardware\n");
      return 0;
    }
    const std::unique_ptr<tessim::rtl::RtlUnit> rtl = tessim::rtl::make_rtl_unit(*variant);
    tessim::rtl::check_config(*rtl, cfg);
    rtl->set_mode(cfg.normals);
    rtl->reset();
    const sim::HostScaling scaling = sim::host_scaling(mesh);
    sim::BasicTestbench<sim::MeshSource> tb(sim::MeshSource(mesh, scaling, cfg.format, cfg.tess_factor), cfg);
    while (!tb.done()) rtl->tick(tb.inputs(*rtl));
    const sim::SimResult model = sim::simulate(mesh, cfg);
    std::printf("rtl %s cycles %llu vertices %llu model cycles %llu\n", variant->c_str(),
                static_cast<unsigned long long>(rtl->counters().cycles),
                static_cast<unsigned long long>(rtl->counters().vertices_out),
                static_cast<unsigned long long>(model.unit.cycles));
    return rtl->counters().cycles == model.unit.cycles ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rtl_consumer: error: %s\n", e.what());
    return 1;
  }
}
