// libFuzzer target: option parsing. The input is split at newlines into
// arguments and parsed by the foglab command line (CLI11 with every
// subcommand registered, validators included) without running anything;
// each argument also goes through the library's own string parsers (tau
// grids, rate units, modulations, lab variants).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "app.h"
#include "foglab/core/units.h"
#include "foglab/sim/optics.h"
#include "foglab/stats/tau_grid.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args;
  std::string current;
  for (std::size_t i = 0; i < size && args.size() < 64; ++i) {
    if (data[i] == '\n') {
      args.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[i]));
    }
  }
  if (!current.empty()) args.push_back(current);

  for (const std::string& a : args) {
    foglab::fuzz::expect_only_foglab_errors([&] { foglab::stats::parse_tau_grid(a); });
    foglab::fuzz::expect_only_foglab_errors([&] { foglab::rate_unit_from_string(a); });
    foglab::fuzz::expect_only_foglab_errors([&] { foglab::sim::modulation_from_string(a); });
  }

  auto cli = foglab::cli::make_command_line();
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them reversed
  try {
    cli->app.parse(reversed);
  } catch (const CLI::ParseError&) {
    // A usage error (or --help / --version): exit code 0 or 2, never a crash.
  }
  return 0;
}
