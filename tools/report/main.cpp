// tumble-report: the numerics lab's reports (`tumble report precision|stability ...`).
#include <CLI/CLI.hpp>

#include "tools/report/report_commands.h"

int main(int argc, char** argv) {
  CLI::App cli{"Numerics lab: integrator error against CPU time, and stability", "tumble report"};
  int exitCode = 0;
  tumble::tools::addReportCommands(cli, exitCode);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 1;  // usage errors: "could not start", as in tumble
  }
  return exitCode;
}
