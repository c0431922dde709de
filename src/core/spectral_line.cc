// foglab — a spectral line's Allan variance (spectral_line.h).
#include "foglab/core/spectral_line.h"

#include <cmath>
#include <numbers>

namespace foglab {

double dirichlet_kernel(double frequency_hz, double samples, double sample_interval_s) {
  return std::sin(std::numbers::pi * frequency_hz * samples * sample_interval_s) /
         (samples * std::sin(std::numbers::pi * frequency_hz * sample_interval_s));
}

double line_allan_variance(const SpectralLine& line, double tau_s, double sample_interval_s) {
  if (!(sample_interval_s > 0.0) || !(tau_s > 0.0)) return 0.0;
  const double m = tau_s / sample_interval_s;
  double sum = 0.0;
  for (std::size_t b = 0; b < line.bin_frequency_hz.size(); ++b) {
    const double f = line.bin_frequency_hz[b];
    const double kernel = dirichlet_kernel(f, m, sample_interval_s);
    if (!std::isfinite(kernel)) continue;  // a line at the sample rate aliases to DC
    // two neighbouring m-averages differ by 2 sin(pi f tau) times the kernel
    const double difference = std::sin(std::numbers::pi * f * tau_s) * kernel;
    sum += 2.0 * line.bin_variance[b] * difference * difference;
  }
  return sum;
}

}  // namespace foglab
