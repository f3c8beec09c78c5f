// tessim: simulator of a PN-triangle tessellation unit (float reference, cycle model, RTL).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <exception>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "app/commands.hpp"
#include "model/base/error.hpp"
#include "sim/version.hpp"

namespace {

// CLI11's help puts "Needs: --x" and "Excludes: --y" on the option's name line, where they read
// as part of the syntax. Here they end the description instead.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* opt) const override {
    std::stringstream out;
    if (!opt->get_option_text().empty()) return " " + opt->get_option_text();
    if (opt->get_type_size() != 0) {
      if (!opt->get_type_name().empty()) out << " " << get_label(opt->get_type_name());
      if (!opt->get_default_str().empty()) out << "=" << opt->get_default_str();
      if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) out << " ...";
      else if (opt->get_expected_min() > 1) out << " x " << opt->get_expected();
      if (opt->get_required()) out << " " << get_label("REQUIRED");
    }
    return out.str();
  }
  std::string make_option_desc(const CLI::Option* opt) const override {
    std::string desc = opt->get_description();
    auto names = [](const std::set<CLI::Option*>& options) {
      std::string s;
      for (const CLI::Option* o : options) s += (s.empty() ? "" : ", ") + o->get_name();
      return s;
    };
    if (!opt->get_needs().empty()) desc += " (needs " + names(opt->get_needs()) + ")";
    if (!opt->get_excludes().empty()) desc += " (excludes " + names(opt->get_excludes()) + ")";
    return desc;
  }
};

// A command-line error CLI11 found itself (an unknown option, a missing argument, a failed
// CLI11 check), in the form of every other bad input: "command line: ELEMENT: REASON".
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& e) {
  // No subcommand matched: name the word that was given instead.
  if (app.get_subcommands().empty() && !app.remaining().empty() && app.remaining().front().rfind("-", 0) != 0) {
    std::string commands;
    for (const CLI::App* sub : app.get_subcommands({}))
      commands += (commands.empty() ? "" : ", ") + sub->get_name();
    return tessim::InputError("command line", app.remaining().front(),
                              "not a tessim command (the commands are " + commands + ")")
        .what();
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
  return tessim::InputError("command line", element, reason + " (see tessim --help)").what();
}

// An option given with an empty value ("--stats ''", "-o \"$UNSET\"") is a bad value, never "not
// given": a script with an unset variable would otherwise lose that output without a word.
// Checked for every subcommand once its arguments are parsed, before it runs.
void refuse_empty_values(const CLI::App& sub) {
  for (const CLI::Option* opt : sub.get_options()) {
    if (opt->count() == 0 || opt->get_type_size() == 0) continue;  // not given, or a flag
    for (const std::string& value : opt->results())
      if (value.empty())
        throw tessim::InputError("command line", opt->get_name(), "has an empty value (give a value or leave it out)");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tessim: PN-triangle tessellation unit simulator (reference, cycle model, RTL)"};
  app.require_subcommand(1);
  app.formatter(std::make_shared<HelpFormatter>());  // before the subcommands, which inherit it
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
  tessim::app::register_power(app);
#ifdef TESSIM_HAVE_COSIM
  tessim::app::register_cosim(app);
  tessim::app::register_rtlbench(app);
#endif
  for (CLI::App* sub : app.get_subcommands({})) sub->parse_complete_callback([sub] { refuse_empty_values(*sub); });
  if (argc == 1) {  // no command at all: what a new user needs is the list of commands
    std::fputs(app.help().c_str(), stdout);
    return std::fflush(stdout) == 0 ? 0 : 2;
  }
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
  // Everything a command printed to standard output (summaries, `schema`, `info --json`, ...)
  // must have reached it: a full disk or a closed pipe is a failed run, not a short one.
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::fprintf(stderr, "tessim: error: standard output: cannot write (%s)\n", std::strerror(errno));
    return 2;
  }
  return 0;
}
