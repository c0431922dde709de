// Example 2: the two-sided rate PSD by Welch's method and its log-frequency
// smoothing; reads the white-noise level N off the flat part.
//
//   ./build/examples/example_02_psd [FILE] [CHANNEL]
#include <cmath>
#include <cstdio>

#include "foglab/core/error.h"
#include "foglab/io/reader.h"
#include "foglab/io/sample.h"
#include "foglab/stats/psd.h"

namespace {

int run(int argc, char** argv) {
  using namespace foglab;
  io::Series series;
  if (argc > 1) {
    io::ReadOptions options;
    if (argc > 2) options.channel = argv[2];
    series = io::read_series(argv[1], options);
  } else {
    series = io::builtin_sample();
  }
  const stats::PsdResult psd = stats::welch_psd(series.values, series.sample_rate_hz);
  const stats::PsdResult smooth = stats::log_smooth(psd, 10.0);
  for (std::size_t k = 0; k < smooth.frequency_hz.size(); ++k) {
    std::printf("%12.5g Hz  %12.5g deg/h/sqrt(Hz)\n", smooth.frequency_hz[k], smooth.sqrt_psd[k]);
  }
  // White rate noise is flat at N^2 in the two-sided PSD: the upper decade
  // of the spectrum estimates N.
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < psd.frequency_hz.size(); ++k) {
    if (psd.frequency_hz[k] > series.sample_rate_hz / 20.0) {
      sum += psd.psd[k];
      ++count;
    }
  }
  std::printf("white-noise density N = %.4g deg/h/sqrt(Hz)\n", std::sqrt(sum / count));
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
