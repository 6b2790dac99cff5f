// The intgrid command: analysis, mapping and the demo of the golden model.
//
// Exit status: 0 done (or --help); 2 bad input: a parse error (unknown option, missing or bad
// value, extra argument), a bad option value found later (OptionError), a bad input file
// (io::InputError); 1 anything else, an internal error.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "intgrid/io/input_error.hpp"

namespace {

// The help shows an option by its short names and its first long name: the later long names are
// old ones kept working for existing scripts (`--cell,--res`), not documented.
class Formatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* opt, bool positional) const override {
    if (positional || opt->get_lnames().empty())
      return CLI::Formatter::make_option_name(opt, positional);
    std::string name;
    for (const std::string& s : opt->get_snames()) name += "-" + s + ",";
    return name + "--" + opt->get_lnames().front();
  }
};

// "intgrid figure globloc-sweeps": the subcommands that were selected, deepest last.
std::string command_path(const CLI::App& app) {
  std::string path = "intgrid";
  const CLI::App* at = &app;
  while (!at->get_subcommands().empty()) {
    at = at->get_subcommands().front();
    path += " " + at->get_name();
  }
  return path;
}

// "unknown option --bogus", "unexpected arguments: a b".
std::string not_expected(const std::vector<std::string>& args) {
  std::string joined;
  for (const std::string& a : args) joined += (joined.empty() ? "" : " ") + a;
  if (args.size() == 1 && args[0].size() > 1 && args[0][0] == '-')
    return "unknown option " + joined;
  return (args.size() == 1 ? "unexpected argument: " : "unexpected arguments: ") + joined;
}

int usage_error(const CLI::App& app, const std::string& message) {
  std::fprintf(stderr, "intgrid: error: %s; run '%s --help'\n", message.c_str(),
               command_path(app).c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"intgrid: integer-arithmetic occupancy grids, from the exact inverse sensor model"};
  app.name("intgrid");
  app.require_subcommand(1);
  app.formatter(std::make_shared<Formatter>());
  intgrid::cli::add_ism_command(app);
  intgrid::cli::add_resolution_command(app);
  intgrid::cli::add_map_command(app);
  intgrid::cli::add_compare_command(app);
  intgrid::cli::add_figure_command(app);
  intgrid::cli::add_demo_command(app);
  intgrid::cli::add_simulate_command(app);
  intgrid::cli::add_slam_command(app);
  intgrid::cli::add_globloc_command(app);
  intgrid::cli::add_localize_command(app);
  intgrid::cli::add_hw_config_command(app);
  // After the subcommands, which would inherit it.
  app.footer("Run 'intgrid SUBCOMMAND --help' for a subcommand's options.");
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help: the help text, exit 0
  } catch (const CLI::RequiredError& e) {
    // CLI11 checks requirements before it complains of unknown arguments: an unknown option
    // (a misspelt --log, say) is the error to report.
    const std::vector<std::string> unknown = app.remaining(true);
    return usage_error(app, unknown.empty() ? e.what() : not_expected(unknown));
  } catch (const CLI::ExtrasError& e) {
    const std::vector<std::string> unknown = app.remaining(true);
    return usage_error(app, unknown.empty() ? e.what() : not_expected(unknown));
  } catch (const CLI::ArgumentMismatch& e) {
    // "--cell: 1 required FLOAT:> 0 missing" -> "--cell: needs a value".
    const std::string what = e.what();
    const std::size_t colon = what.find(": ");
    if (colon != std::string::npos && what.ends_with(" missing"))
      return usage_error(app, what.substr(0, colon) + ": needs a value");
    return usage_error(app, what);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e.what());
  } catch (const intgrid::cli::OptionError& e) {
    return usage_error(app, e.what());
  } catch (const intgrid::io::InputError& e) {
    std::fprintf(stderr, "intgrid: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "intgrid: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
