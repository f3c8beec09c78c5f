// tessim: simulator of a PN-triangle tessellation unit (float reference, cycle model, RTL).
#include <cstdio>
#include <exception>

#include "model/error.hpp"
#include "app/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"tessim: PN-triangle tessellation unit simulator (reference, cycle model, RTL)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tessim 0.1.0");
  tessim::app::register_info(app);
  tessim::app::register_tessellate(app);
  tessim::app::register_render(app);
  tessim::app::register_sim(app);
  tessim::app::register_bench(app);
  tessim::app::register_schema(app);
  tessim::app::register_pattern(app);
#ifdef TESSIM_HAVE_COSIM
  tessim::app::register_cosim(app);
  tessim::app::register_rtlbench(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const tessim::InputError& e) {
    std::fprintf(stderr, "tessim: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessim: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
