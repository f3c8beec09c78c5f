// consumer MESH L INT_BLOCKS [OUT.png]: the float reference and the cycle model of an installed
// tessim on one mesh, with the configuration given as JSON (as `tessim sim --config` reads it),
// and optionally a small picture through the installed image writer.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"
#include "model/mesh_io.hpp"
#include "model/tessellate.hpp"
#include "render/raster.hpp"
#include "sim/config/config.hpp"
#include "sim/run/simulate.hpp"

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: consumer MESH L INT_BLOCKS [OUT.png]\n");
    return 2;
  }
  try {
    const tessim::Mesh mesh = tessim::load_mesh(argv[1]);
    const int L = std::atoi(argv[2]);

    const tessim::TessellationSummary ref =
        tessim::tessellate_mesh(mesh, L, tessim::NormalMode::Quadratic, [](const tessim::PatchView&) {});
    std::printf("reference %llu vertices %llu triangles\n", static_cast<unsigned long long>(ref.vertices),
                static_cast<unsigned long long>(ref.triangles));

    tessim::sim::UnitConfig cfg;
    const nlohmann::json params = {{"tess_factor", L}, {"int_blocks", std::atoi(argv[3])}};
    tessim::sim::apply_json(cfg, params, "consumer");
    cfg.validate("consumer");
    const tessim::sim::SimResult r = tessim::sim::simulate(mesh, cfg);
    std::printf("cycles %llu vertices %llu\n", static_cast<unsigned long long>(r.unit.cycles),
                static_cast<unsigned long long>(r.unit.vertices_out));

    if (argc == 5) {
      setenv("TESSIM_IMAGEIO_PLUGIN", TESSIM_IMAGEIO_PLUGIN_PATH, 0);
      tessim::render::Image image(8, 8);
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) image.pixel(x, y)[0] = static_cast<float>(x) / image.width;
      tessim::render::write_image(image, argv[4]);
      std::printf("image %s\n", argv[4]);
    }
  } catch (const tessim::InputError& e) {
    std::fprintf(stderr, "consumer: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
