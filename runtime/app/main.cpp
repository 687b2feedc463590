// tumble: the runtime's command line. See ARCHITECTURE.md "Command line".
// Commands it does not know may be offline tools beside it (tumble-TOOL,
// tools/README.md), which it runs with the rest of the command line.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>

#include "app/commands.h"
#include "app/external_tools.h"

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"Tumble: a physics-scenario runtime with a Lua gameplay layer", "tumble"};
  int exitCode = 0;
  tumble::app::addCommands(cli, &exitCode);
  std::vector<std::string> builtins;
  for (const CLI::App* sub : cli.get_subcommands([](CLI::App*) { return true; })) builtins.push_back(sub->get_name());
  if (auto status = tumble::app::runExternalTool(argc, argv, builtins)) return *status;
  cli.footer([] {
    return "Tools (programs beside this one, run as tumble TOOL ARGS...; tumble TOOL --help): " +
           joined(tumble::app::externalTools());
  });
  if (argc >= 2 && argv[1][0] != '-' && std::find(builtins.begin(), builtins.end(), argv[1]) == builtins.end()) {
    // Neither a command nor a tool: say what there is.
    std::fprintf(stderr, "tumble: '%s' is not a command. Commands: %s. Tools: %s. See tumble --help.\n", argv[1],
                 joined(builtins).c_str(), joined(tumble::app::externalTools()).c_str());
    return 1;
  }
  tumble::app::removeOrphanedUserTemporaries();
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = cli.exit(e);
    return code == 0 ? 0 : 1;  // usage errors: "could not start"
  }
  return exitCode;
}
