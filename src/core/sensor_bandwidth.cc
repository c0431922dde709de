// foglab — a sensor's output bandwidth in the Allan variance (sensor_bandwidth.h).
#include "foglab/core/sensor_bandwidth.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace foglab {

namespace {

// The moving average over k samples of unit white level: r_j = (k - |j|) / k^2.
double ma_autocovariance(int k, std::int64_t lag) {
  const std::int64_t a = lag < 0 ? -lag : lag;
  return a < k ? static_cast<double>(k - a) / (static_cast<double>(k) * k) : 0.0;
}

// m AVAR(m) of a filtered white sequence of unit level whose samples have
// the autocorrelation a(j) (zero beyond lag `reach`): the variance of an
// m-average less the covariance of two neighbouring ones. The white
// noise's counterpart of flicker_ratio().
template <class Autocorrelation>
double white_ratio(std::int64_t m, std::int64_t reach, Autocorrelation a) {
  double var = 0.0, cov = 0.0;
  const std::int64_t inside = std::min(m - 1, reach);
  for (std::int64_t j = -inside; j <= inside; ++j) {
    var += static_cast<double>(m - (j < 0 ? -j : j)) * a(j < 0 ? -j : j);
  }
  for (std::int64_t j = 1; j <= 2 * m - 1 && j <= reach; ++j) {
    const std::int64_t d = j - m;
    cov += static_cast<double>(m - (d < 0 ? -d : d)) * a(j);
  }
  return (var - cov) / static_cast<double>(m);
}

// The lag-1 autocorrelation of the samples when a fraction phi of the white
// noise passes a filter whose samples have autocovariance r0, r1 (per unit
// white level) and the rest does not.
double mixed_lag1(double phi, double r0, double r1) { return phi * r1 / ((1.0 - phi) + phi * r0); }

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

// The Butterworth's samples' autocorrelation a_j, j = 0 .. R, for unit
// white level per sample (sum over all j of a_j = 1, the unit DC gain):
// its impulse response h, run until it stays below 1e-16 of its largest
// magnitude, correlated with itself. The bandwidth search asks for the
// same few cut-offs many times, so the last ones are kept.
const std::vector<double>& butterworth_autocorrelation(double cutoff_hz, double tau0) {
  thread_local std::vector<std::pair<double, std::vector<double>>> cache;
  const double key = cutoff_hz * tau0;
  for (const auto& [k, a] : cache) {
    if (k == key) return a;
  }
  const auto [b0, b1, b2, a1, a2] = butterworth_coefficients(cutoff_hz, tau0);
  std::vector<double> h;
  double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0, largest = 0.0;
  for (int n = 0, quiet = 0; quiet < 64 && n < 1000000; ++n) {
    const double x = n == 0 ? 1.0 : 0.0;
    const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
    x2 = x1, x1 = x, y2 = y1, y1 = y;
    h.push_back(y);
    largest = std::max(largest, std::fabs(y));
    quiet = std::fabs(y) < 1e-16 * largest ? quiet + 1 : 0;
  }
  std::vector<double> a(h.size(), 0.0);
  for (std::size_t j = 0; j < h.size(); ++j) {
    for (std::size_t n = 0; n + j < h.size(); ++n) a[j] += h[n] * h[n + j];
  }
  if (cache.size() >= 64) cache.erase(cache.begin());
  cache.emplace_back(key, std::move(a));
  return cache.back().second;
}

}  // namespace

std::array<double, 5> butterworth_coefficients(double cutoff_hz, double sample_interval_s) {
  const double k = std::tan(std::numbers::pi * cutoff_hz * sample_interval_s);
  const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
  const double b0 = k * k * norm;
  return {b0, 2.0 * b0, b0, 2.0 * (k * k - 1.0) * norm,
          (1.0 - std::numbers::sqrt2 * k + k * k) * norm};
}

SensorBandwidth first_order_with_memory(double memory_constant_samples, double sample_interval_s) {
  const double c = memory_constant_samples;
  if (!(c > 0.0) || !(sample_interval_s > 0.0)) return {};
  // c rho^2 + 3 rho - c = 0, its root in (0, 1), as 2 c / (3 + sqrt(9 + 4 c^2))
  // (no cancellation for small c).
  const double rho = 2.0 * c / (3.0 + std::sqrt(9.0 + 4.0 * c * c));
  return SensorBandwidth{1.0, -sample_interval_s / std::log(rho)};
}

namespace {

// The first-order stand-in for a filter known beyond its memory, on the
// same fraction of the output.
SensorBandwidth stand_in(const SensorBandwidth& bandwidth, double sample_interval_s) {
  SensorBandwidth b = first_order_with_memory(bandwidth.memory_constant_samples, sample_interval_s);
  b.filtered_fraction = bandwidth.filtered_fraction;
  return b;
}

}  // namespace

double power_response(const SensorBandwidth& bandwidth, double frequency_hz,
                      double sample_interval_s) {
  if (!bandwidth.any() || !(sample_interval_s > 0.0)) return 1.0;
  if (bandwidth.beyond_memory()) {
    return power_response(stand_in(bandwidth, sample_interval_s), frequency_hz, sample_interval_s);
  }
  const double w = 2.0 * std::numbers::pi * frequency_hz * sample_interval_s;  // [rad/sample]
  double h2 = 1.0;
  if (bandwidth.moving_average()) {
    const double k = bandwidth.moving_average_samples;
    const double s = std::sin(0.5 * w);
    h2 = std::fabs(s) < 1e-300 ? 1.0 : std::pow(std::sin(0.5 * w * k) / (k * s), 2);
  } else if (bandwidth.butterworth()) {
    const auto [b0, b1, b2, a1, a2] =
        butterworth_coefficients(bandwidth.butterworth_cutoff_hz, sample_interval_s);
    const std::complex<double> z1 = std::polar(1.0, -w);  // z^-1
    const std::complex<double> h = (b0 + b1 * z1 + b2 * z1 * z1) / (1.0 + a1 * z1 + a2 * z1 * z1);
    h2 = std::norm(h);
  } else {
    const double rho = filtered_lag1(bandwidth, sample_interval_s);
    h2 = (1.0 - rho) * (1.0 - rho) / (1.0 - 2.0 * rho * std::cos(w) + rho * rho);
  }
  const double phi = bandwidth.filtered_fraction;
  return (1.0 - phi) + phi * h2;
}

double flicker_allan_factor(const SensorBandwidth& bandwidth, double tau_s,
                            double sample_interval_s) {
  if (!bandwidth.any() || !(sample_interval_s > 0.0)) return 1.0;
  if (bandwidth.beyond_memory()) {
    return flicker_allan_factor(stand_in(bandwidth, sample_interval_s), tau_s, sample_interval_s);
  }
  const auto m = std::max<std::int64_t>(1, std::llround(tau_s / sample_interval_s));
  double g = 1.0;
  if (bandwidth.moving_average()) {
    const int k = bandwidth.moving_average_samples;
    // 1 - g falls as (k / m)^2: beyond 4096 k it is below 1e-7.
    if (m > 4096 * static_cast<std::int64_t>(k)) return 1.0;
    g = flicker_ratio(m, k - 1, [k](std::int64_t j) { return ma_autocovariance(k, j); });
  } else if (bandwidth.butterworth()) {
    const std::vector<double>& a =
        butterworth_autocorrelation(bandwidth.butterworth_cutoff_hz, sample_interval_s);
    const auto reach = static_cast<std::int64_t>(a.size()) - 1;
    if (m > 4096 * (reach + 1)) return 1.0;
    g = flicker_ratio(m, reach, [&a](std::int64_t j) { return a[static_cast<std::size_t>(j)]; });
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
  if (bandwidth.butterworth()) return bandwidth.butterworth_cutoff_hz;
  if (bandwidth.beyond_memory()) {
    if (!(sample_interval_s > 0.0)) return std::numeric_limits<double>::infinity();
    return cutoff_hz(first_order_with_memory(bandwidth.memory_constant_samples, sample_interval_s));
  }
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
  if (bandwidth.beyond_memory()) {
    return filtered_lag1(
        first_order_with_memory(bandwidth.memory_constant_samples, sample_interval_s),
        sample_interval_s);
  }
  if (bandwidth.butterworth()) {
    if (!(sample_interval_s > 0.0)) return 0.0;
    const std::vector<double>& a =
        butterworth_autocorrelation(bandwidth.butterworth_cutoff_hz, sample_interval_s);
    return a.size() > 1 ? a[1] / a[0] : 0.0;
  }
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
  if (bandwidth.beyond_memory()) {
    const double c = bandwidth.memory_constant_samples;
    const double m = tau_s / sample_interval_s;
    if (m >= 2.0 * c) return 1.0 - bandwidth.filtered_fraction * c / m;
    return white_allan_factor(stand_in(bandwidth, sample_interval_s), tau_s, sample_interval_s);
  }
  if (bandwidth.moving_average()) {
    const auto m = std::max<std::int64_t>(1, std::llround(tau_s / sample_interval_s));
    const int k = bandwidth.moving_average_samples;
    const double g = white_ratio(m, k - 1, [k](std::int64_t j) { return ma_autocovariance(k, j); });
    return 1.0 - bandwidth.filtered_fraction * (1.0 - g);
  }
  if (bandwidth.butterworth()) {
    const auto m = std::max<std::int64_t>(1, std::llround(tau_s / sample_interval_s));
    const std::vector<double>& a =
        butterworth_autocorrelation(bandwidth.butterworth_cutoff_hz, sample_interval_s);
    const double g = white_ratio(m, static_cast<std::int64_t>(a.size()) - 1,
                                 [&a](std::int64_t j) { return a[static_cast<std::size_t>(j)]; });
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
  if (bandwidth.beyond_memory()) return std::numeric_limits<double>::quiet_NaN();
  if (bandwidth.moving_average()) {
    const int k = bandwidth.moving_average_samples;
    return mixed_lag1(bandwidth.filtered_fraction, ma_autocovariance(k, 0),
                      ma_autocovariance(k, 1));
  }
  if (bandwidth.butterworth()) {
    const std::vector<double>& a =
        butterworth_autocorrelation(bandwidth.butterworth_cutoff_hz, sample_interval_s);
    return a.size() > 1 ? mixed_lag1(bandwidth.filtered_fraction, a[0], a[1]) : 0.0;
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
