// Registration of the tessim subcommands. Each lives in its own cmd_*.cpp; a subcommand
// reports bad input by throwing tessim::InputError, which main() turns into a message and a
// non-zero exit status.
#pragma once

#include <CLI/CLI.hpp>

namespace tessim::app {

void register_info(CLI::App& app);
void register_tessellate(CLI::App& app);
void register_render(CLI::App& app);
void register_sim(CLI::App& app);
void register_bench(CLI::App& app);
void register_schema(CLI::App& app);
#ifdef TESSIM_HAVE_COSIM
void register_cosim(CLI::App& app);
void register_rtlbench(CLI::App& app);
#endif

}  // namespace tessim::app
