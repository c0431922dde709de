// Peak memory of foglab::stats::allan_deviation (OADEV, octave, with
// intervals) relative to the input array: ru_maxrss after the call over the
// input's size. Usage: bench_allan_memory [SAMPLES] (default 10^8).
#include <fmt/format.h>
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdlib>
#include <string>

#include "bench_support.h"
#include "foglab/stats/allan.h"

int main(int argc, char** argv) {
  using namespace foglab;
  CLI::App app{"Peak memory of allan_deviation relative to the input array", "bench_allan_memory"};
  std::size_t n = 100'000'000;
  app.add_option("samples", n, "record length")
      ->check(CLI::Range(std::size_t{16}, std::size_t{1} << 40));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help is not an error; anything else is a usage error
  }
  const std::vector<double> y = bench::gyro_record(n);
  const auto t0 = std::chrono::steady_clock::now();
  const stats::AllanResult r = stats::allan_deviation(y, 100.0, InputKind::rate, {});
  const auto t1 = std::chrono::steady_clock::now();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;
  const double input_bytes = static_cast<double>(n) * sizeof(double);
  fmt::print("samples {} taus {} time {:.3f} s peak RSS {:.1f} MB input {:.1f} MB ratio {:.2f}\n",
             n, r.tau_s.size(), std::chrono::duration<double>(t1 - t0).count(), peak_bytes / 1e6,
             input_bytes / 1e6, peak_bytes / input_bytes);
  return 0;
}
