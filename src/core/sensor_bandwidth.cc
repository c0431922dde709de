// foglab — a sensor's output bandwidth in the Allan variance (sensor_bandwidth.h).
#include "foglab/core/sensor_bandwidth.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace foglab {

double cutoff_hz(const SensorBandwidth& bandwidth) {
  if (!(bandwidth.time_constant_s > 0.0)) return std::numeric_limits<double>::infinity();
  return 1.0 / (2.0 * std::numbers::pi * bandwidth.time_constant_s);
}

double filtered_lag1(const SensorBandwidth& bandwidth, double sample_interval_s) {
  if (!(bandwidth.time_constant_s > 0.0)) return 0.0;
  return std::exp(-sample_interval_s / bandwidth.time_constant_s);
}

double white_allan_factor(const SensorBandwidth& bandwidth, double tau_s,
                          double sample_interval_s) {
  if (!bandwidth.any() || !(sample_interval_s > 0.0)) return 1.0;
  const double rho = filtered_lag1(bandwidth, sample_interval_s);
  const double m = tau_s / sample_interval_s;
  // 1 - rho^m and 1 - rho^2 by expm1, which keeps them exact for rho near 1.
  const double one_minus_rho_m = -std::expm1(-m * sample_interval_s / bandwidth.time_constant_s);
  const double one_minus_rho2 = -std::expm1(-2.0 * sample_interval_s / bandwidth.time_constant_s);
  const double correction = rho * one_minus_rho_m * (2.0 + one_minus_rho_m) / (m * one_minus_rho2);
  return 1.0 - bandwidth.filtered_fraction * correction;
}

double white_lag1_correlation(const SensorBandwidth& bandwidth, double sample_interval_s) {
  if (!bandwidth.any()) return 0.0;
  // White level S = phi S + (1 - phi) S; the filtered part's variance is
  // phi S (1 - rho) / (1 + rho), its lag-1 covariance rho times that; the
  // unfiltered part's variance is (1 - phi) S.
  const double rho = filtered_lag1(bandwidth, sample_interval_s);
  const double phi = bandwidth.filtered_fraction;
  const double filtered = phi * (1.0 - rho) / (1.0 + rho);
  return rho * filtered / (filtered + (1.0 - phi));
}

}  // namespace foglab
