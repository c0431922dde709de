// Example 1: the overlapping Allan deviation of a gyro record, with its
// confidence intervals, through the library API.
//
//   ./build/examples/example_01_allan_deviation [FILE.mat|.csv] [CHANNEL]
//
// With no argument it uses foglab's built-in sample record.
#include <cstdio>
#include <string>

#include "foglab/core/error.h"
#include "foglab/io/reader.h"
#include "foglab/io/sample.h"
#include "foglab/stats/allan.h"

namespace {

int run(int argc, char** argv) {
  using namespace foglab;
  io::Series series;
  if (argc > 1) {
    io::ReadOptions options;
    if (argc > 2) options.channel = argv[2];
    series = io::read_series(argv[1], options);  // rate in deg/h, fs from the file
  } else {
    series = io::builtin_sample();
  }

  stats::AllanOptions options;  // OADEV, octave grid, >= 10 clusters per tau
  const stats::AllanResult r =
      stats::allan_deviation(series.values, series.sample_rate_hz, InputKind::rate, options);

  std::printf("%10s %14s %14s %14s %6s\n", "tau [s]", "ADEV [deg/h]", "95% low", "95% high",
              "alpha");
  for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
    std::printf("%10.4g %14.6g %14.6g %14.6g %6d\n", r.tau_s[k], r.dev[k], r.ci95_low[k],
                r.ci95_high[k], r.alpha[k]);
  }
  return 0;
}

}  // namespace

// foglab's error policy (core/error.h): a bad argument is a UsageError, bad
// data a DataError naming the file and what was expected.
int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const foglab::UsageError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return foglab::kExitUsage;
  } catch (const foglab::DataError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return foglab::kExitData;
  }
}
