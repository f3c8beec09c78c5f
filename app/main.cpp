// tessim: simulator of a PN-triangle tessellation unit (float reference, cycle model, RTL).
#include <cstdio>
#include <exception>
#include <string>

#include "model/error.hpp"
#include "app/commands.hpp"
#include "sim/version.hpp"

namespace {

// A command-line error CLI11 found itself (an unknown option, a missing argument, a failed
// CLI11 check), in the form of every other bad input: "command line: ELEMENT: REASON".
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& e) {
  // No subcommand matched: name the word that was given instead.
  if (app.get_subcommands().empty() && !app.remaining().empty() && app.remaining().front().rfind("-", 0) != 0) {
    std::string commands;
    for (const CLI::App* sub : app.get_subcommands({}))
      commands += (commands.empty() ? "" : ", ") + sub->get_name();
    return "command line: " + app.remaining().front() + ": not a tessim command (the commands are " + commands + ")";
  }
  std::string reason = e.what();
  std::string element = "arguments";
  // CLI11's ValidationError reads "--option: reason".
  if (dynamic_cast<const CLI::ValidationError*>(&e) != nullptr) {
    const std::size_t colon = reason.find(": ");
    if (colon != std::string::npos && colon > 0 && reason[0] == '-') {
      element = reason.substr(0, colon);
      reason = reason.substr(colon + 2);
    }
  }
  return "command line: " + element + ": " + reason + " (see tessim --help)";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tessim: PN-triangle tessellation unit simulator (reference, cycle model, RTL)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("tessim 0.1.0 (") + tessim::tool_version() + ")");
  tessim::app::register_info(app);
  tessim::app::register_tessellate(app);
  tessim::app::register_render(app);
  tessim::app::register_sim(app);
  tessim::app::register_bench(app);
  tessim::app::register_schema(app);
  tessim::app::register_pattern(app);
  tessim::app::register_stpn_import(app);
  tessim::app::register_compare(app);
  tessim::app::register_report(app);
#ifdef TESSIM_HAVE_COSIM
  tessim::app::register_cosim(app);
  tessim::app::register_rtlbench(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own failure status (cosim: 1 on divergence)
  } catch (const CLI::ParseError& e) {
    // --help and --version end parsing with a "success" error: CLI11 prints them.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::fprintf(stderr, "tessim: error: %s\n", parse_error_message(app, e).c_str());
    return 2;
  } catch (const tessim::InputError& e) {
    std::fprintf(stderr, "tessim: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessim: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
