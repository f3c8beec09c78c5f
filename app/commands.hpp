// Registration of the tessim subcommands. Each lives in its own cmd_*.cpp; a subcommand
// reports bad input by throwing tessim::InputError, which main() turns into a message and a
// non-zero exit status.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "model/normal_mode.hpp"

namespace tessim::app {

// Checks of options shared by the reference commands (tessellate, render): InputError naming
// the command and the option. The cycle-model commands check theirs through sim/params.hpp.
void check_tess_factor(const char* command, int factor);
NormalMode parse_normals_option(const char* command, const std::string& text);

void register_info(CLI::App& app);
void register_tessellate(CLI::App& app);
void register_render(CLI::App& app);
void register_sim(CLI::App& app);
void register_bench(CLI::App& app);
void register_schema(CLI::App& app);
void register_pattern(CLI::App& app);
#ifdef TESSIM_HAVE_COSIM
void register_cosim(CLI::App& app);
void register_rtlbench(CLI::App& app);
#endif

}  // namespace tessim::app
