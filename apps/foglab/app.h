// foglab CLI — the command line as a library: main() runs it, and the
// option-parsing fuzz target (fuzz/fuzz_options.cc) builds and parses it
// without running anything.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace foglab::cli {

/// Every subcommand registered on one CLI11 app.
struct CommandLine {
  CLI::App app{"foglab — fiber-optic gyroscope signal chain simulation and noise analysis"};
  int threads = 0;  ///< --threads (0: all cores)
  /// Each subcommand and the action to run when it was chosen.
  std::vector<std::pair<CLI::App*, std::function<void()>>> commands;
};

std::unique_ptr<CommandLine> make_command_line();

/// Parses the arguments, runs the chosen subcommand and maps errors to the
/// exit codes of docs/conventions.md section 11 (0 ok, 1 internal, 2 usage, 3 bad data).
int run_command_line(int argc, char** argv);

}  // namespace foglab::cli
