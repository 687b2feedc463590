#pragma once
// `tumble report precision --out DIR [--quick]` and
// `tumble report stability --out DIR [--quick]` (the program tumble-report):
// the numerics lab's reports. The computations live in runtime/numerics and
// the rigid-body cases beside this file (rigid_body_cases.h); this file owns
// the command line, the files (written atomically) and running gnuplot.
//
//   precision  DIR/precision.csv   problem,method,dt,error,cpu_seconds
//              DIR/precision.md    tables + cheapest method per target error
//              DIR/precision_<problem>.png (+ .gp script that drew it)
//   stability  DIR/stability.csv   case,method,dt,outcome,time_to_failure_s,
//                                  energy_growth,penetration_max_m,
//                                  joint_error_max_m,nan_events,failed_body
//              DIR/stability_regions.csv, DIR/stability.md
//
// Exit code: 0 written; 1 a file could not be written or gnuplot failed
// (gnuplot missing is not an error: the CSV/MD are written and the output
// says how to get the plots).
namespace CLI {
class App;
}

namespace tumble::tools {

/// Adds the `precision` and `stability` subcommands to `report` (the
/// program's own command line) and requires one of them; their callbacks
/// store the exit code in exitCode (which must outlive report's parse).
void addReportCommands(CLI::App& report, int& exitCode);

}  // namespace tumble::tools
