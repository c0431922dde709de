// The sensor bandwidth's Allan-variance factor (core/sensor_bandwidth.h)
// against the Allan variance computed from the process's autocovariance by
// direct summation, and its limits.
#include "foglab/core/sensor_bandwidth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace foglab {
namespace {

// The sampled process: (1 - phi) of the white level unfiltered (variance
// (1 - phi) S at lag 0) and phi of it through the first-order filter (an
// AR(1) sequence with lag-1 correlation rho and variance phi S (1 - rho) /
// (1 + rho)); S = 1 per sample.
double autocovariance(double phi, double rho, int lag) {
  const double filtered = phi * (1.0 - rho) / (1.0 + rho) * std::pow(rho, std::abs(lag));
  return filtered + (lag == 0 ? 1.0 - phi : 0.0);
}

// Half the mean square difference of two neighbouring m-averages, summed
// sample by sample: (Var(a) + Var(b) - 2 Cov(a, b)) / 2.
double allan_variance_by_sums(double phi, double rho, int m) {
  double var = 0.0, cov = 0.0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      var += autocovariance(phi, rho, i - j);
      cov += autocovariance(phi, rho, m + j - i);
    }
  }
  return (var - cov) / (static_cast<double>(m) * m);
}

TEST(SensorBandwidth, AllanFactorEqualsTheSumOverTheAutocovariance) {
  const double tau0 = 0.01;
  for (double phi : {0.3, 1.0}) {
    for (double t_over_tau0 : {0.2, 0.54, 1.0, 3.0, 9.0}) {
      const SensorBandwidth bw{phi, t_over_tau0 * tau0};
      const double rho = std::exp(-1.0 / t_over_tau0);
      EXPECT_NEAR(filtered_lag1(bw, tau0), rho, 1e-15);
      for (int m : {1, 2, 3, 5, 16, 100}) {
        // White level S = 1 per sample: N^2 / tau = 1 / m in these units.
        const double expected = allan_variance_by_sums(phi, rho, m) * m;
        EXPECT_NEAR(white_allan_factor(bw, m * tau0, tau0), expected, 1e-12)
            << "phi " << phi << ", T " << t_over_tau0 << " tau0, m " << m;
      }
      // Lag-1 autocorrelation of the samples.
      EXPECT_NEAR(white_lag1_correlation(bw, tau0),
                  autocovariance(phi, rho, 1) / autocovariance(phi, rho, 0), 1e-14);
    }
  }
}

// The moving average over k samples of white noise (unit white level), by
// brute force: the m-averages of the k-averages, as weights on the white
// samples, and the variance of the difference of two neighbouring ones.
double moving_average_allan_by_weights(int k, int m) {
  // Output y_i = (x_i + ... + x_(i-k+1)) / k; block a = y_0..y_(m-1), b = y_m..y_(2m-1).
  std::vector<double> w(static_cast<std::size_t>(2 * m + k), 0.0);  // weight on x_(j - k + 1)
  for (int i = 0; i < 2 * m; ++i) {
    const double sign = i < m ? -1.0 : 1.0;
    for (int j = 0; j < k; ++j) w[static_cast<std::size_t>(i - j + k - 1)] += sign / (k * m);
  }
  double ss = 0.0;
  for (double v : w) ss += v * v;
  return 0.5 * ss;  // unit-variance white samples
}

TEST(SensorBandwidth, MovingAverageFactorEqualsTheWeightsSum) {
  const double tau0 = 0.01;
  for (int k : {2, 3, 8}) {
    for (double phi : {0.5, 1.0}) {
      const SensorBandwidth bw{phi, 0.0, k};
      for (int m : {1, 2, 3, 7, 8, 9, 40}) {
        const double filtered = moving_average_allan_by_weights(k, m) * m;
        EXPECT_NEAR(white_allan_factor(bw, m * tau0, tau0), 1.0 - phi * (1.0 - filtered), 1e-12)
            << "k " << k << ", phi " << phi << ", m " << m;
      }
      // Lag 1: (k - 1) / k^2 over the sample variance (1 - phi) + phi / k.
      EXPECT_NEAR(white_lag1_correlation(bw, tau0),
                  phi * (k - 1.0) / (k * k) / ((1.0 - phi) + phi / k), 1e-14);
    }
  }
  // The response of a 4-sample boxcar at 100 Hz is 1/sqrt(2) at the cut-off,
  // 11.385 Hz (below the first zero, 25 Hz).
  const double fc = cutoff_hz(SensorBandwidth{1.0, 0.0, 4}, tau0);
  const double x = std::numbers::pi * fc * tau0;
  EXPECT_NEAR(std::fabs(std::sin(4.0 * x) / (4.0 * std::sin(x))), std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(fc, 11.385, 0.001);
}

// Flicker noise sampled as interval averages of a 1/f process: half the
// mean square difference of samples j apart, in units of the Allan plateau
// over ln 2 (L(a) = a^2 ln|a|).
double flicker_semivariogram(int j) {
  auto l = [](double a) { return std::fabs(a) > 1.0 ? a * a * std::log(std::fabs(a)) : 0.0; };
  return 0.25 * (l(j + 1.0) - 2.0 * l(j) + l(j - 1.0));
}

// The Allan variance at factor m of the flicker samples passed through the
// filter with impulse response h, by brute force: the weights of the two
// neighbouring m-averages on the input samples, and the variance of their
// difference from the semivariogram (-sum w_a w_b gamma(a - b), the
// weights summing to 0), over 2 m^2; in units of the plateau (ln 2).
double filtered_flicker_allan(const std::vector<double>& h, int m) {
  std::vector<double> w(2 * static_cast<std::size_t>(m) + h.size() - 1, 0.0);
  for (int i = 0; i < 2 * m; ++i) {
    for (std::size_t j = 0; j < h.size(); ++j) w[i + j] += (i < m ? -1.0 : 1.0) * h[j];
  }
  double sum = 0.0;
  for (std::size_t a = 0; a < w.size(); ++a) {
    for (std::size_t b = 0; b < w.size(); ++b) {
      sum -= w[a] * w[b] * flicker_semivariogram(static_cast<int>(a) - static_cast<int>(b));
    }
  }
  return sum / (2.0 * m * m) / std::numbers::ln2;
}

TEST(SensorBandwidth, FlickerFactorEqualsTheBruteForceSumOverTheSemivariogram) {
  const double tau0 = 0.01;
  // Unfiltered, the semivariogram gives the plateau at every m (the
  // continuous Allan variance of 1/f noise does not depend on tau).
  for (int m : {1, 2, 3, 10, 33}) EXPECT_NEAR(filtered_flicker_allan({1.0}, m), 1.0, 1e-12) << m;
  for (double phi : {0.4, 1.0}) {
    for (int k : {2, 4, 7}) {
      const std::vector<double> h(static_cast<std::size_t>(k), 1.0 / k);
      for (int m : {1, 2, 3, 5, 8, 21}) {
        const double expected = 1.0 - phi * (1.0 - filtered_flicker_allan(h, m));
        EXPECT_NEAR(flicker_allan_factor(SensorBandwidth{phi, 0.0, k}, m * tau0, tau0), expected,
                    1e-10)
            << "k " << k << ", phi " << phi << ", m " << m;
      }
    }
    for (double t_over_tau0 : {0.54, 3.0}) {
      const double rho = std::exp(-1.0 / t_over_tau0);
      std::vector<double> h;
      for (int j = 0; j < 300; ++j) h.push_back((1.0 - rho) * std::pow(rho, j));
      for (int m : {1, 2, 5, 16}) {
        const double expected = 1.0 - phi * (1.0 - filtered_flicker_allan(h, m));
        EXPECT_NEAR(flicker_allan_factor(SensorBandwidth{phi, t_over_tau0 * tau0}, m * tau0, tau0),
                    expected, 1e-10)
            << "T " << t_over_tau0 << " tau0, phi " << phi << ", m " << m;
      }
    }
  }
  // A 4-sample moving average keeps 13 % of the flicker plateau at the
  // first tau; far out it keeps all of it.
  EXPECT_NEAR(flicker_allan_factor(SensorBandwidth{1.0, 0.0, 4}, tau0, tau0), 0.12989, 1e-5);
  EXPECT_NEAR(flicker_allan_factor(SensorBandwidth{1.0, 0.0, 4}, 1e4 * tau0, tau0), 1.0, 1e-6);
  EXPECT_EQ(flicker_allan_factor(SensorBandwidth{}, tau0, tau0), 1.0);
}

// The second-order Butterworth low-pass from Bristow-Johnson's "Audio EQ
// Cookbook" (its LPF with Q = 1/sqrt(2): w0 = 2 pi f_c tau0, alpha =
// sin(w0) / (2 Q), b = ((1 - cos w0) / 2, 1 - cos w0, (1 - cos w0) / 2),
// a = (1 + alpha, -2 cos w0, 1 - alpha)), a derivation independent of
// butterworth_coefficients(): its impulse response, `taps` long.
std::vector<double> cookbook_butterworth_response(double fc_tau0, int taps) {
  const double w0 = 2.0 * std::numbers::pi * fc_tau0, alpha = std::sin(w0) / std::sqrt(2.0);
  const double a0 = 1.0 + alpha;
  const double b0 = (1.0 - std::cos(w0)) / 2.0 / a0, b1 = 2.0 * b0, b2 = b0;
  const double a1 = -2.0 * std::cos(w0) / a0, a2 = (1.0 - alpha) / a0;
  std::vector<double> h;
  double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0;
  for (int n = 0; n < taps; ++n) {
    const double x = n == 0 ? 1.0 : 0.0;
    const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
    x2 = x1, x1 = x, y2 = y1, y1 = y;
    h.push_back(y);
  }
  return h;
}

// m AVAR(m) of unit white noise through the filter h, by brute force: the
// weights of two neighbouring m-averages on the white samples.
double filtered_white_allan_by_weights(const std::vector<double>& h, int m) {
  std::vector<double> w(2 * static_cast<std::size_t>(m) + h.size() - 1, 0.0);
  for (int i = 0; i < 2 * m; ++i) {
    for (std::size_t j = 0; j < h.size(); ++j) w[i + j] += (i < m ? -1.0 : 1.0) * h[j] / m;
  }
  double ss = 0.0;
  for (double v : w) ss += v * v;
  return 0.5 * ss * m;
}

TEST(SensorBandwidth, ButterworthFactorsEqualTheCookbookFiltersBruteForceSums) {
  const double tau0 = 0.01;
  for (double fc_tau0 : {0.05, 0.2, 0.4}) {
    const std::vector<double> h = cookbook_butterworth_response(fc_tau0, 600);
    const auto [b0, b1, b2, a1, a2] = butterworth_coefficients(fc_tau0 / tau0, tau0);
    // Unit gain at DC; -3 dB at the cut-off.
    double sum = 0.0;
    std::complex<double> response = 0.0;
    for (std::size_t n = 0; n < h.size(); ++n) {
      sum += h[n];
      response += h[n] * std::polar(1.0, -2.0 * std::numbers::pi * fc_tau0 * n);
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR(std::abs(response), std::sqrt(0.5), 1e-9);
    EXPECT_NEAR(b0, h[0], 1e-15);
    for (double phi : {0.5, 1.0}) {
      const SensorBandwidth bw{phi, 0.0, 1, fc_tau0 / tau0};
      EXPECT_DOUBLE_EQ(cutoff_hz(bw, tau0), fc_tau0 / tau0);
      for (int m : {1, 2, 3, 7, 20, 64}) {
        const double white = filtered_white_allan_by_weights(h, m);
        EXPECT_NEAR(white_allan_factor(bw, m * tau0, tau0), 1.0 - phi * (1.0 - white), 1e-10)
            << "f_c " << fc_tau0 << " / tau0, phi " << phi << ", m " << m;
        const double flicker = filtered_flicker_allan(h, m);
        EXPECT_NEAR(flicker_allan_factor(bw, m * tau0, tau0), 1.0 - phi * (1.0 - flicker), 1e-9)
            << "f_c " << fc_tau0 << " / tau0, phi " << phi << ", m " << m;
      }
      // Far beyond the response (the sums end at its reach) against the
      // brute force.
      EXPECT_NEAR(white_allan_factor(bw, 700 * tau0, tau0),
                  1.0 - phi * (1.0 - filtered_white_allan_by_weights(h, 700)), 1e-10);
      // Lag 1 of the samples: phi a_1 / ((1 - phi) + phi a_0).
      double a0 = 0.0, a1 = 0.0;
      for (std::size_t n = 0; n + 1 < h.size(); ++n) a0 += h[n] * h[n], a1 += h[n] * h[n + 1];
      EXPECT_NEAR(white_lag1_correlation(bw, tau0), phi * a1 / ((1.0 - phi) + phi * a0), 1e-12);
    }
  }
}

TEST(SensorBandwidth, FactorTendsToTheContinuousFilterAndToOne) {
  const double tau0 = 0.01;
  const SensorBandwidth bw{1.0, 20.0 * tau0};
  // tau >> T >> tau0: 1 - 1.5 T / tau (the continuous first-order filter).
  const double tau = 2000.0 * tau0;
  EXPECT_NEAR(1.0 - white_allan_factor(bw, tau, tau0), 1.5 * bw.time_constant_s / tau, 2e-5);
  EXPECT_EQ(white_allan_factor(SensorBandwidth{}, tau0, tau0), 1.0);
  EXPECT_EQ(white_allan_factor(SensorBandwidth{0.0, 1.0}, tau0, tau0), 1.0);
  EXPECT_NEAR(cutoff_hz(bw), 1.0 / (2.0 * std::numbers::pi * 0.2), 1e-12);
  EXPECT_TRUE(std::isinf(cutoff_hz(SensorBandwidth{})));
}

// Any filter, known beyond its memory: a cascade of a k-sample moving
// average and a first-order low-pass (rho), its impulse response by
// convolution, its autocorrelation and Allan variance by direct sums, and
// c = 1.5 sum |j| r_j / sum r_j from that autocorrelation. Past the
// memory the factor 1 - c / m is the Allan variance's.
TEST(SensorBandwidth, BeyondItsMemoryAnyFilterFollowsOneConstant) {
  const double tau0 = 0.01;
  for (int k : {1, 3, 8}) {
    for (double rho : {0.0, std::exp(-1.0), 0.8}) {
      // h = moving average * (1 - rho) rho^i, to rho^i < 1e-18.
      std::vector<double> h(static_cast<std::size_t>(k) + 200, 0.0);
      for (int i = 0; i < k; ++i) {
        double tail = (1.0 - rho) / k;
        for (std::size_t j = static_cast<std::size_t>(i); j < h.size(); ++j, tail *= rho) {
          h[j] += tail;
        }
      }
      const auto reach = static_cast<int>(h.size());
      auto r = [&](int lag) {
        double sum = 0.0;
        for (int i = 0; i + std::abs(lag) < reach; ++i) {
          sum += h[static_cast<std::size_t>(i)] * h[static_cast<std::size_t>(i + std::abs(lag))];
        }
        return sum;
      };
      double total = 0.0, moment = 0.0;
      for (int j = -reach + 1; j < reach; ++j) total += r(j), moment += std::abs(j) * r(j);
      const double c = 1.5 * moment / total;
      if (k == 1 && rho == 0.0) continue;  // no filter: c = 0
      const SensorBandwidth bw{.filtered_fraction = 1.0, .memory_constant_samples = c};
      SCOPED_TRACE(::testing::Message() << "k " << k << ", rho " << rho << ", c " << c);
      ASSERT_TRUE(bw.any());
      for (int m : {k + 160, 256, 1000}) {
        double var = 0.0, cov = 0.0;  // sums over the lags, weighted by their counts
        for (int j = -m + 1; j < m; ++j) var += (m - std::abs(j)) * r(j);
        for (int j = 1; j < 2 * m; ++j) cov += (m - std::abs(j - m)) * r(j);
        const double expected = (var - cov) / m / total;  // over S / m
        EXPECT_NEAR(white_allan_factor(bw, m * tau0, tau0), expected, 1e-12) << "m " << m;
      }
    }
  }
  // The moving average alone: c = (k^2 - 1) / (2 k), exact from m = k.
  for (int k : {2, 4, 11}) {
    const SensorBandwidth ma{1.0, 0.0, k};
    const SensorBandwidth memory{.filtered_fraction = 1.0,
                                 .memory_constant_samples = (k * k - 1.0) / (2.0 * k)};
    for (int m = k; m <= 4 * k; ++m) {
      EXPECT_NEAR(white_allan_factor(memory, m * tau0, tau0),
                  white_allan_factor(ma, m * tau0, tau0), 1e-13)
          << "k " << k << ", m " << m;
    }
  }
}

TEST(SensorBandwidth, BeyondMemoryStandInIsTheFirstOrderFilterWithTheSameConstant) {
  const double tau0 = 0.01;
  for (double c : {0.05, 1.0, 2.5, 40.0}) {
    const SensorBandwidth memory{.filtered_fraction = 1.0, .memory_constant_samples = c};
    const SensorBandwidth stand_in = first_order_with_memory(c, tau0);
    const double rho = filtered_lag1(stand_in, tau0);
    EXPECT_NEAR(3.0 * rho / (1.0 - rho * rho), c, 1e-12 * c) << c;
    EXPECT_DOUBLE_EQ(stand_in.filtered_fraction, 1.0);
    EXPECT_DOUBLE_EQ(filtered_lag1(memory, tau0), rho);
    EXPECT_DOUBLE_EQ(cutoff_hz(memory, tau0), cutoff_hz(stand_in, tau0));
    EXPECT_TRUE(std::isnan(white_lag1_correlation(memory, tau0)));
    for (double f : {0.1, 10.0, 49.0}) {
      EXPECT_DOUBLE_EQ(power_response(memory, f, tau0), power_response(stand_in, f, tau0));
    }
    // Inside 2 c samples the stand-in's factor (positive, below 1), then 1 - c / m.
    for (int m : {1, 2, 3, 5, 8, 100, 1000}) {
      const double factor = white_allan_factor(memory, m * tau0, tau0);
      if (m >= 2.0 * c) {
        EXPECT_DOUBLE_EQ(factor, 1.0 - c / m);
      } else {
        EXPECT_DOUBLE_EQ(factor, white_allan_factor(stand_in, m * tau0, tau0));
        EXPECT_GT(factor, 0.0);
      }
      EXPECT_LT(factor, 1.0);
      EXPECT_DOUBLE_EQ(flicker_allan_factor(memory, m * tau0, tau0),
                       flicker_allan_factor(stand_in, m * tau0, tau0));
    }
  }
}

}  // namespace
}  // namespace foglab
