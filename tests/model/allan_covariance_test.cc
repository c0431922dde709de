// The covariance of overlapping Allan variance estimates across tau (the
// noise fit's sandwich intervals): exact for white rate noise at m = 1,
// Greenhall's edf for power-law noise, and the scatter and correlation of
// the estimates over many generated records (Monte Carlo).
#include "../../src/model/allan_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <vector>

#include "foglab/model/noise_fit.h"
#include "foglab/sim/generator.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/edf.h"

namespace foglab::model {
namespace {

using detail::allan_variance_covariance;

// Octave factors down to 3 clusters, as the noise fit uses.
std::vector<std::int64_t> octave_factors(std::int64_t phase_points) {
  std::vector<std::int64_t> m;
  for (std::int64_t k = 1; (phase_points - 1) / k >= 3; k *= 2) m.push_back(k);
  return m;
}

TEST(AllanCovariance, WhiteRateNoiseAtTheSampleIntervalIsExact) {
  // m = 1: d_k = x_{k+2} - 2 x_{k+1} + x_k = tau0 (y_{k+1} - y_k), whose
  // lag-one correlation is -1/2, so for n = N - 2 terms the sum of d^2 has
  // variance (12 n - 4) s^4 and mean 2 n s^2: edf = 2 n^2/(3 n - 1).
  const std::int64_t phase_points = 5000;
  const NoiseModel white{.N = 0.7};
  const std::vector<std::int64_t> m{1};
  const Eigen::MatrixXd c = allan_variance_covariance(white, 0.1, m, phase_points);
  const double avar = allan_variance(white, 0.1), n = phase_points - 2.0;
  EXPECT_NEAR(2.0 * avar * avar / c(0, 0), 2.0 * n * n / (3.0 * n - 1.0), 1e-9 * n);
}

// Greenhall's edf algorithm (stats/edf.h) is exact for power-law noise at
// large factors; the covariance's diagonal must agree there, both where
// the lag sum is done term by term and where it is an integral.
TEST(AllanCovariance, VarianceIsGreenhallsForPowerLawNoise) {
  const std::int64_t phase_points = 200001;
  const double tau0 = 0.1;
  const std::vector<std::int64_t> m = octave_factors(phase_points);
  struct Case {
    NoiseModel model;
    int alpha;
  };
  for (const Case& c :
       {Case{{.N = 1.0}, 0}, Case{{.B = 1.0}, -1}, Case{{.K = 1.0}, -2}, Case{{.Q = 1.0}, 2}}) {
    const Eigen::MatrixXd cov = allan_variance_covariance(c.model, tau0, m, phase_points);
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m[i] < 64) continue;
      const double avar = allan_variance(c.model, static_cast<double>(m[i]) * tau0);
      const auto k = static_cast<Eigen::Index>(i);
      const double edf = 2.0 * avar * avar / cov(k, k);
      const double greenhall = stats::greenhall_edf(c.alpha, m[i], phase_points);
      EXPECT_NEAR(edf, greenhall, 0.01 * greenhall) << "alpha " << c.alpha << ", m " << m[i];
    }
  }
}

// Over 1000 generated records of 8192 samples the estimates' variance and
// the correlation of neighbouring octaves match the computed ones (points
// with at least 8 clusters; standard errors about 5 % and 0.03). Flicker
// noise is checked against Greenhall's edf above (its generator is slow).
TEST(AllanCovariance, ScatterAcrossTauMatchesMonteCarlo) {
  struct Case {
    sim::ErrorModel truth;
    NoiseModel model;
  };
  sim::ErrorModel walk, hump;
  walk.noise.N = 1.0;
  walk.noise.K = 0.02;
  hump.noise.N = 1.0;
  hump.noise.gm_sigma = 1.0;
  hump.noise.gm_tc = 30.0;
  const Case cases[] = {{walk, {.N = 1.0, .K = 0.02}},
                        {hump, {.N = 1.0, .gm_sigma = 1.0, .gm_tc = 30.0}}};
  const double fs = 10.0;
  const int runs = 1000;
  for (const Case& c : cases) {
    std::vector<std::vector<double>> avar;
    stats::AllanResult last;
    for (int run = 0; run < runs; ++run) {
      sim::GeneratorOptions o;
      o.sample_rate_hz = fs;
      o.duration_s = 8192 / fs;
      o.seed = static_cast<std::uint64_t>(run + 1);
      const sim::Recording rec = sim::generate(c.truth, sim::TemperatureProfile{}, o);
      stats::AllanOptions a;
      a.grid.min_clusters = 8;
      last = stats::allan_deviation(rec.rate_deg_h, fs, InputKind::rate, a);
      std::vector<double> v;
      for (double d : last.dev) v.push_back(d * d);
      avar.push_back(v);
    }
    const auto n = static_cast<Eigen::Index>(last.m.size());
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);
    for (const auto& v : avar) mean += Eigen::Map<const Eigen::VectorXd>(v.data(), n) / runs;
    Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(n, n);
    for (const auto& v : avar) {
      const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(v.data(), n) - mean;
      scatter += d * d.transpose() / (runs - 1);
    }
    const Eigen::MatrixXd cov =
        allan_variance_covariance(c.model, 1.0 / fs, last.m, last.phase_points);
    for (Eigen::Index i = 0; i < n; ++i) {
      EXPECT_NEAR(scatter(i, i) / cov(i, i), 1.0, 0.2) << "m " << last.m[i];
      if (i + 1 == n) continue;
      const double mc = scatter(i, i + 1) / std::sqrt(scatter(i, i) * scatter(i + 1, i + 1));
      const double computed = cov(i, i + 1) / std::sqrt(cov(i, i) * cov(i + 1, i + 1));
      EXPECT_NEAR(mc, computed, 0.1) << "m " << last.m[i];
    }
  }
}

}  // namespace
}  // namespace foglab::model
