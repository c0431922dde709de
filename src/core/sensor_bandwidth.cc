// foglab — a sensor's output bandwidth in the Allan variance (sensor_bandwidth.h).
#include "foglab/core/sensor_bandwidth.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace foglab {

namespace {

// The moving average over k samples of unit white level: r_j = (k - |j|) / k^2.
double ma_autocovariance(int k, std::int64_t lag) {
  const std::int64_t a = lag < 0 ? -lag : lag;
  return a < k ? static_cast<double>(k - a) / (static_cast<double>(k) * k) : 0.0;
}

// m AVAR(m) of the moving average's samples with unit white level: the
// variance of an m-average less the covariance of two neighbouring ones.
double ma_allan_factor(int k, std::int64_t m) {
  double var = 0.0, cov = 0.0;
  const std::int64_t reach = std::min<std::int64_t>(m - 1, k - 1);  // r_j = 0 beyond k - 1
  for (std::int64_t j = -reach; j <= reach; ++j) {
    var += static_cast<double>(m - (j < 0 ? -j : j)) * ma_autocovariance(k, j);
  }
  for (std::int64_t j = 1; j <= 2 * m - 1 && j < k; ++j) {
    const std::int64_t d = j - m;
    cov += static_cast<double>(m - (d < 0 ? -d : d)) * ma_autocovariance(k, j);
  }
  return (var - cov) / static_cast<double>(m);
}

// L(a) = a^2 ln|a| (0 at a = 0): flicker noise's semivariogram between
// interval averages j samples apart is (L(j + 1) - 2 L(j) + L(j - 1)) / 4
// times the plateau / ln 2 (from S(f) = h / f and the averages' sinc^2).
double l_of(double a) {
  a = std::fabs(a);
  return a > 1.0 ? a * a * std::log(a) : 0.0;
}

// The quadratic form of the Allan kernel at factor m (two neighbouring
// m-sample averages, differenced) over the flicker semivariogram, at a
// shift of j samples between the two copies: the fourth difference of L at
// step m, (4 L(j + m) + 4 L(j - m) - 6 L(j) - L(j + 2m) - L(j - 2m)) / 4.
// At j = 0 it is -2 m^2 ln 2 (the unfiltered plateau).
double flicker_kernel_form(double m, double j) {
  return 0.25 * (4.0 * l_of(j + m) + 4.0 * l_of(j - m) - 6.0 * l_of(j) - l_of(j + 2.0 * m) -
                 l_of(j - 2.0 * m));
}

// The filtered flicker's Allan variance at factor m over the unfiltered
// plateau: the kernel form weighted by the filter's autocorrelation a_j
// (which sums to 1, the filter's unit gain at zero frequency).
template <class Autocorrelation>
double flicker_ratio(std::int64_t m, std::int64_t reach, Autocorrelation a) {
  const double md = static_cast<double>(m);
  double sum = a(0) * flicker_kernel_form(md, 0.0);
  for (std::int64_t j = 1; j <= reach; ++j) {
    sum += 2.0 * a(j) * flicker_kernel_form(md, static_cast<double>(j));
  }
  return sum / (-2.0 * md * md * std::numbers::ln2);
}

}  // namespace

double flicker_allan_factor(const SensorBandwidth& bandwidth, double tau_s,
                            double sample_interval_s) {
  if (!bandwidth.any() || !(sample_interval_s > 0.0)) return 1.0;
  const auto m = std::max<std::int64_t>(1, std::llround(tau_s / sample_interval_s));
  double g = 1.0;
  if (bandwidth.moving_average()) {
    const int k = bandwidth.moving_average_samples;
    // 1 - g falls as (k / m)^2: beyond 4096 k it is below 1e-7.
    if (m > 4096 * static_cast<std::int64_t>(k)) return 1.0;
    g = flicker_ratio(m, k - 1, [k](std::int64_t j) { return ma_autocovariance(k, j); });
  } else {
    const double rho = filtered_lag1(bandwidth, sample_interval_s);
    const double samples = bandwidth.time_constant_s / sample_interval_s;
    if (static_cast<double>(m) > 4096.0 * (samples + 1.0)) return 1.0;
    // The AR(1) autocorrelation (1 - rho) / (1 + rho) rho^|j|, to rho^j < 1e-16.
    const auto reach =
        static_cast<std::int64_t>(std::ceil(std::log(1e-16) / std::min(std::log(rho), -1e-3)));
    const double scale = (1.0 - rho) / (1.0 + rho);
    g = flicker_ratio(m, reach, [&](std::int64_t j) { return scale * std::pow(rho, j); });
  }
  return 1.0 - bandwidth.filtered_fraction * (1.0 - g);
}

double cutoff_hz(const SensorBandwidth& bandwidth, double sample_interval_s) {
  if (bandwidth.moving_average()) {
    if (!(sample_interval_s > 0.0)) return std::numeric_limits<double>::infinity();
    // |sin(pi f k tau0) / (k sin(pi f tau0))| = 1/sqrt(2), by bisection on f.
    const int k = bandwidth.moving_average_samples;
    auto gain = [&](double f) {
      const double x = std::numbers::pi * f * sample_interval_s;
      return std::fabs(std::sin(k * x) / (k * std::sin(x)));
    };
    double lo = 0.0, hi = 1.0 / (k * sample_interval_s);  // the first zero
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (gain(mid) > std::numbers::sqrt2 / 2.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
  if (!(bandwidth.time_constant_s > 0.0)) return std::numeric_limits<double>::infinity();
  return 1.0 / (2.0 * std::numbers::pi * bandwidth.time_constant_s);
}

double filtered_lag1(const SensorBandwidth& bandwidth, double sample_interval_s) {
  if (bandwidth.moving_average()) {
    return static_cast<double>(bandwidth.moving_average_samples - 1) /
           bandwidth.moving_average_samples;
  }
  if (!(bandwidth.time_constant_s > 0.0)) return 0.0;
  return std::exp(-sample_interval_s / bandwidth.time_constant_s);
}

double white_allan_factor(const SensorBandwidth& bandwidth, double tau_s,
                          double sample_interval_s) {
  if (!bandwidth.any() || !(sample_interval_s > 0.0)) return 1.0;
  if (bandwidth.moving_average()) {
    const auto m = std::max<std::int64_t>(1, std::llround(tau_s / sample_interval_s));
    const double g = ma_allan_factor(bandwidth.moving_average_samples, m);
    return 1.0 - bandwidth.filtered_fraction * (1.0 - g);
  }
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
  if (bandwidth.moving_average()) {
    const int k = bandwidth.moving_average_samples;
    const double phi = bandwidth.filtered_fraction;
    return phi * ma_autocovariance(k, 1) / ((1.0 - phi) + phi * ma_autocovariance(k, 0));
  }
  // White level S = phi S + (1 - phi) S; the filtered part's variance is
  // phi S (1 - rho) / (1 + rho), its lag-1 covariance rho times that; the
  // unfiltered part's variance is (1 - phi) S.
  const double rho = filtered_lag1(bandwidth, sample_interval_s);
  const double phi = bandwidth.filtered_fraction;
  const double filtered = phi * (1.0 - rho) / (1.0 + rho);
  return rho * filtered / (filtered + (1.0 - phi));
}

}  // namespace foglab
