// foglab CLI — building the command line and mapping errors to exit codes.
#include "app.h"

#include <omp.h>

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <system_error>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"

namespace foglab::cli {

std::unique_ptr<CommandLine> make_command_line() {
  auto c = std::make_unique<CommandLine>();
  CLI::App& app = c->app;
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(version()));
  app.add_option("--threads", c->threads, "worker threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  auto add = [&](std::function<void()> (*reg)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    auto action = reg(app);
    c->commands.emplace_back(app.get_subcommands({})[before], std::move(action));
  };
  add(register_analyze);
  add(register_batch);
  add(register_allan);
  add(register_fit);
  add(register_calibrate);
  add(register_rate_table);
  add(register_psd);
  add(register_generate);
  add(register_lab2_data);
  add(register_lab2);
  add(register_coil);
  add(register_simulate);
  add(register_sweep);
  add(register_lab1);
  return c;
}

namespace {

// Nothing was written: outputs are rendered before any is written, and an
// unfinished one is removed on the way out (core/output.h).
int out_of_memory() {
  std::cerr << "foglab: error: out of memory: the record and its analysis need more memory "
               "(or threads) than this process may use (analyze: 10-40 bytes per sample; see "
               "bench/RESULTS.md); no output was written\n";
  return kExitInternal;
}

}  // namespace

int run_command_line(int argc, char** argv) {
  std::unique_ptr<CommandLine> c = make_command_line();
  CLI::App& app = c->app;
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
  if (c->threads > 0) omp_set_num_threads(c->threads);

  try {
    for (auto& [command, action] : c->commands) {
      if (command->parsed()) action();
    }
    finish_standard_output();  // a lost stdout is a failed run, not exit 0
    return kExitOk;
  } catch (const UsageError& e) {
    std::cerr << "foglab: error: " << in_cli_terms(e.what()) << "\n";
    return kExitUsage;
  } catch (const std::invalid_argument& e) {
    std::cerr << "foglab: error: " << in_cli_terms(e.what()) << "\n";
    return kExitUsage;
  } catch (const DataError& e) {
    std::cerr << "foglab: error: " << in_cli_terms(e.what()) << "\n";
    return kExitData;
  } catch (const std::bad_alloc&) {
    return out_of_memory();
  } catch (const std::system_error& e) {
    // A thread that could not start (its stack is memory too: `ulimit -v`).
    if (e.code() == std::errc::resource_unavailable_try_again ||
        e.code() == std::errc::not_enough_memory) {
      return out_of_memory();
    }
    std::cerr << "foglab: internal error: " << e.what() << "\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "foglab: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
}

}  // namespace foglab::cli
