// foglab — command-line tool for fiber-optic gyroscope signals.
// Exit codes (SPEC.md Part D): 0 ok, 1 internal error, 2 usage, 3 bad input data.
#include <fmt/format.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>
#include <vector>

#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/version.h"

int main(int argc, char** argv) {
  using namespace foglab;
  CLI::App app{"foglab — fiber-optic gyroscope signal chain simulation and noise analysis"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(version()));
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);

  std::vector<std::pair<CLI::App*, std::function<void()>>> commands;
  auto add = [&](std::function<void()> (*reg)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    auto action = reg(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(action));
  };
  add(cli::register_analyze);
  add(cli::register_allan);
  add(cli::register_psd);
  add(cli::register_generate);
  add(cli::register_lab2_data);
  add(cli::register_lab2);
  add(cli::register_coil);
  add(cli::register_simulate);
  add(cli::register_sweep);
  add(cli::register_lab1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "foglab: " << e.what() << "\n"
              << "Run 'foglab --help' or 'foglab COMMAND --help' for usage.\n";
    return kExitUsage;
  }
  if (threads > 0) omp_set_num_threads(threads);

  try {
    for (auto& [command, action] : commands) {
      if (command->parsed()) action();
    }
    return kExitOk;
  } catch (const UsageError& e) {
    std::cerr << "foglab: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::invalid_argument& e) {
    std::cerr << "foglab: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const DataError& e) {
    std::cerr << "foglab: error: " << e.what() << "\n";
    return kExitData;
  } catch (const std::bad_alloc&) {
    std::cerr << "foglab: error: out of memory\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "foglab: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
}
