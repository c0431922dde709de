// foglab — a spectral line's Allan variance (spectral_line.h).
#include "foglab/core/spectral_line.h"

#include <cmath>
#include <numbers>

namespace foglab {

double line_allan_variance(const SpectralLine& line, double tau_s, double sample_interval_s) {
  if (!(sample_interval_s > 0.0) || !(tau_s > 0.0)) return 0.0;
  const double m = tau_s / sample_interval_s;
  double sum = 0.0;
  for (std::size_t b = 0; b < line.bin_frequency_hz.size(); ++b) {
    const double f = line.bin_frequency_hz[b];
    const double s_tau = std::sin(std::numbers::pi * f * tau_s);
    const double s_tau0 = m * std::sin(std::numbers::pi * f * sample_interval_s);
    if (s_tau0 == 0.0) continue;  // a line at the sample rate aliases to DC
    const double s2 = s_tau * s_tau;
    sum += 2.0 * line.bin_variance[b] * s2 * s2 / (s_tau0 * s_tau0);
  }
  return sum;
}

}  // namespace foglab
