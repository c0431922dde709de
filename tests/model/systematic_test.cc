// The temperature polynomial: exact recovery, the lab's number, the
// thermostat fallback, and standard errors that match the scatter of the
// coefficients over many noisy records (Monte Carlo).
#include "foglab/model/systematic.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/sim/generator.h"
#include "foglab/stats/allan.h"
#include "support/expect.h"

namespace foglab::model {
namespace {

sim::Recording record(const sim::ErrorModel& m, const std::string& temperature, double hours,
                      std::uint64_t seed, double fs = 10.0) {
  sim::GeneratorOptions o;
  o.sample_rate_hz = fs;
  o.duration_s = hours * 3600.0;
  o.seed = seed;
  return sim::generate(m, sim::parse_temperature(temperature), o);
}

TEST(Systematic, NoiselessPolynomialIsRecoveredAndTheLabConstantMatchesPolyfit) {
  sim::ErrorModel m;
  m.bias = 3.0;
  m.temp_coefs = {0.4, -0.02};
  const sim::Recording r = record(m, "ramp:10@20", 2.0, 1);
  SystematicOptions o;
  o.degree = 2;
  const SystematicFit fit = fit_temperature(r.rate_deg_h, r.temperature_c, 10.0, o);
  ASSERT_EQ(fit.degree, 2);
  // The generator's polynomial is about the profile's nominal mean (25 degC);
  // the fit's about the samples' mean: compare the curves.
  for (double t : {20.0, 23.0, 27.5, 30.0}) {
    const double u = t - fit.t_ref_c, v = t - 25.0;
    EXPECT_NEAR(fit.coefficients[0] + fit.coefficients[1] * u + fit.coefficients[2] * u * u,
                3.0 + 0.4 * v - 0.02 * v * v, 1e-9);
  }
  // polyfit(T, Y, 2) in raw degC, independently by least squares on raw T.
  Eigen::MatrixXd x(static_cast<Eigen::Index>(r.temperature_c.size()), 3);
  Eigen::VectorXd y(x.rows());
  for (Eigen::Index k = 0; k < x.rows(); ++k) {
    const double t = r.temperature_c[static_cast<std::size_t>(k)];
    x(k, 0) = t * t;
    x(k, 1) = t;
    x(k, 2) = 1.0;
    y(k) = r.rate_deg_h[static_cast<std::size_t>(k)];
  }
  const Eigen::VectorXd p = x.colPivHouseholderQr().solve(y);
  EXPECT_NEAR(fit.lab_constant_term_deg_h, p(2), 1e-6 * std::fabs(p(2)));
  EXPECT_NEAR(fit.lab_polyfit[0], p(0), 1e-9);
  EXPECT_NEAR(fit.residual_rms_deg_h, 0.0, 1e-6);
  EXPECT_TRUE(fit.lab_constant_meaningful);
}

TEST(Systematic, CriterionChoosesTheDegreeTheDataShow) {
  // A clear quadratic under white noise: degree 2, not 1 (too little) or 3.
  sim::ErrorModel m;
  m.noise.N = 1.0;
  m.temp_coefs = {0.5, 0.05};
  int right = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const sim::Recording r = record(m, "ramp:10@20", 2.0, 40 + seed);
    const SystematicFit first = fit_temperature(r.rate_deg_h, r.temperature_c, 10.0);
    EXPECT_TRUE(first.degree_chosen);
    const SystematicFit fit = finish_temperature_fit(first, r.rate_deg_h, r.temperature_c, 10.0,
                                                     {.N = 1.0});
    right += fit.degree == 2;
    ASSERT_EQ(fit.criterion.size(), 4u);
    EXPECT_NEAR(fit.coefficients[1], 0.5, 4.0 * fit.standard_errors[1]);
  }
  // A spurious cubic enters at the 1 % level.
  EXPECT_GE(right, 4);
}

TEST(Systematic, AForcedQuadraticCarriesTheCriterionsVerdict) {
  // The lab's quadratic is removed whatever the data show; beside it the
  // criterion says which degree the data alone keep, from 0 up: 1 for a
  // clear slope, 0 where the bias does not follow the temperature (under a
  // random walk, the lab's FOG1; there the slope's standard error is 0.18
  // deg/h/degC, so 1.5 stands out by 8 of them). The fit itself is left
  // as forced.
  const NoiseModel noise{.N = 1.0, .K = 0.02};
  int slope_kept = 0, nothing_kept = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    for (const double c1 : {1.5, 0.0}) {
      sim::ErrorModel m;
      m.noise.N = noise.N;
      m.noise.K = noise.K;
      m.temp_coefs = {c1};
      const sim::Recording r = record(m, "ramp:10@20", 2.0, 70 + seed);
      const TemperatureRecord rec(r.rate_deg_h, r.temperature_c, 10.0);
      SystematicFit fit = fit_temperature(rec, {.degree = 2});
      const SystematicFit forced = fit;
      set_standard_errors(fit, rec, noise);
      set_criterion_verdict(fit, rec, noise, {.degree = 2});
      EXPECT_EQ(fit.degree, 2);
      EXPECT_EQ(fit.coefficients, forced.coefficients);
      ASSERT_EQ(fit.criterion.size(), 4u);
      const auto best = std::min_element(fit.criterion.begin(), fit.criterion.end());
      EXPECT_EQ(fit.criterion_degree, best - fit.criterion.begin());
      if (c1 > 0.0) {
        slope_kept += fit.criterion_degree == 1;
      } else {
        nothing_kept += fit.criterion_degree == 0;
      }
    }
  }
  // Each spurious term enters at the 1 % level.
  EXPECT_GE(slope_kept, 4);
  EXPECT_GE(nothing_kept, 4);
}

TEST(Systematic, ThermostatRunFallsBackToAConstantAndSaysSo) {
  sim::ErrorModel m;
  m.noise.N = 0.5;
  m.bias = 2.0;
  m.temp_coefs = {0.3};
  const sim::Recording r = record(m, "const:25", 1.0, 2);
  SystematicOptions o;
  o.degree = 2;  // even when asked for
  const SystematicFit fit = fit_temperature(r.rate_deg_h, r.temperature_c, 10.0, o);
  EXPECT_EQ(fit.degree, 0);
  EXPECT_TRUE(fit.constant_fallback);
  EXPECT_FALSE(fit.lab_constant_meaningful);
  EXPECT_NE(fit.note.text().find("degC"), std::string::npos);
  EXPECT_NE(fit.note.text().find("degree 2 was asked"), std::string::npos);
  EXPECT_NEAR(fit.bias_deg_h, 2.0, 0.05);
  // White rate noise of density N has a per-sample sd of N sqrt(fs).
  EXPECT_NEAR(fit.residual_rms_deg_h, 0.5 * std::sqrt(10.0), 0.02 * 0.5 * std::sqrt(10.0));
}

// Standard deviation of c1..c3 of cubic fits over many records, against the
// noise-model covariance: each process with a temperature ramp.
void expect_errors_match_scatter(const sim::ErrorModel& m, const NoiseModel& noise) {
  const int records = 120;
  std::vector<Eigen::Vector3d> c;
  std::vector<double> predicted;
  for (int seed = 1; seed <= records; ++seed) {
    const sim::Recording r = record(m, "ramp:10@20", 1.0, static_cast<std::uint64_t>(seed));
    SystematicOptions o;
    o.degree = 3;
    const SystematicFit fit = fit_temperature(r.rate_deg_h, r.temperature_c, 10.0, o);
    c.emplace_back(fit.coefficients[1], fit.coefficients[2], fit.coefficients[3]);
    if (seed == 1) {
      const std::vector<double> cov =
          coefficient_covariance(r.temperature_c, 10.0, fit.t_ref_c, 3, noise);
      for (int j = 1; j <= 3; ++j) predicted.push_back(std::sqrt(cov[j * 4 + j]));
    }
  }
  for (int j = 0; j < 3; ++j) {
    double s = 0, ss = 0;
    for (const auto& v : c) {
      s += v(j);
      ss += v(j) * v(j);
    }
    const double mean = s / records;
    const double sd = std::sqrt(ss / records - mean * mean);
    // The sample sd of 120 draws scatters by 1/sqrt(240) = 6.5 %: 3 sigma.
    EXPECT_NEAR(sd / predicted[static_cast<std::size_t>(j)], 1.0, 0.2) << "c" << j + 1;
  }
}

TEST(Systematic, StandardErrorsMatchTheScatterUnderWhiteNoise) {
  sim::ErrorModel m;
  m.noise.N = 1.0;
  expect_errors_match_scatter(m, {.N = 1.0});
}

TEST(Systematic, StandardErrorsMatchTheScatterUnderARandomWalkBias) {
  // The case where residual-scatter errors are ~20x too small.
  sim::ErrorModel m;
  m.noise.N = 0.1;
  m.noise.K = 0.01;
  expect_errors_match_scatter(m, {.N = 0.1, .K = 0.01});
}

TEST(Systematic, StandardErrorsMatchTheScatterUnderFlickerAndGaussMarkov) {
  sim::ErrorModel m;
  m.noise.B = 0.5;
  m.noise.gm_sigma = 0.5;
  m.noise.gm_tc = 200.0;
  expect_errors_match_scatter(m, {.B = 0.5, .gm_sigma = 0.5, .gm_tc = 200.0});
}

TEST(Systematic, DetrendFactorsPredictTheResidualAllanVariance) {
  // A random walk with a quadratic in temperature removed over a ramp: the
  // mean residual Allan variance at the long taus against K^2 tau/3 x factor.
  sim::ErrorModel m;
  m.noise.K = 0.01;
  const int records = 60;
  std::vector<double> tau, sum;
  DetrendFactors f;
  for (int seed = 1; seed <= records; ++seed) {
    sim::Recording r = record(m, "ramp:10@20", 1.0, static_cast<std::uint64_t>(500 + seed), 2.0);
    SystematicOptions o;
    o.degree = 2;
    const SystematicFit fit = fit_temperature(r.rate_deg_h, r.temperature_c, 2.0, o);
    subtract_temperature_fit(fit, r.rate_deg_h, r.temperature_c);
    stats::AllanOptions a;
    a.confidence = false;
    a.grid.min_clusters = 3;
    const stats::AllanResult allan =
        stats::allan_deviation(r.rate_deg_h, 2.0, InputKind::rate, a);
    if (seed == 1) {
      tau = allan.tau_s;
      sum.assign(tau.size(), 0.0);
      f = detrend_factors(r.temperature_c, 2.0, fit.t_ref_c, 2, tau);
    }
    for (std::size_t i = 0; i < tau.size(); ++i) sum[i] += allan.dev[i] * allan.dev[i];
  }
  const std::size_t last = tau.size() - 1;
  // The factor matters at the long end (well below 1) ...
  EXPECT_LT(f.factor(NoiseTerm::random_walk, last, 0.0), 0.6);
  // ... and predicts the mean: 60 records at tau = T/4 (edf ~ 3 each, ~180
  // in all) scatter by sqrt(2/180) = 11 %: 3.5 sigma.
  for (std::size_t i = last - 2; i <= last; ++i) {
    const double expected = 0.01 * 0.01 * tau[i] / 3.0 * f.factor(NoiseTerm::random_walk, i, 0.0);
    EXPECT_NEAR(sum[i] / records / expected, 1.0, 0.35) << "tau " << tau[i];
  }
  // Short taus are untouched.
  EXPECT_NEAR(f.factor(NoiseTerm::random_walk, 0, 0.0), 1.0, 1e-3);
}

TEST(Systematic, MismatchedLengthsAreAUsageErrorNamingBothCounts) {
  const std::vector<double> rate(100, 1.0), temperature(99, 25.0);
  const std::string message =
      test::message_of<UsageError>([&] { fit_temperature(rate, temperature, 10.0); });
  EXPECT_NE(message.find("100"), std::string::npos);
  EXPECT_NE(message.find("99"), std::string::npos);
}

TEST(Systematic, NonFiniteTemperatureIsADataErrorNamingTheSample) {
  std::vector<double> rate(100, 1.0), temperature(100, 25.0);
  temperature[41] = std::nan("");
  EXPECT_NE(test::message_of<DataError>([&] { fit_temperature(rate, temperature, 10.0); })
                .find("sample 42"),
            std::string::npos);
}

// A temperature below absolute zero is no temperature in degC: a wrong
// channel, or one in another unit. -273.15 itself is the limit, not past it.
TEST(Systematic, ATemperatureBelowAbsoluteZeroIsADataErrorNamingTheSample) {
  std::vector<double> rate(100), temperature(100, 25.0);
  for (std::size_t k = 0; k < rate.size(); ++k) rate[k] = std::sin(0.3 * static_cast<double>(k));
  temperature[6] = -400.0;
  const std::string why =
      test::message_of<DataError>([&] { fit_temperature(rate, temperature, 10.0); });
  EXPECT_NE(why.find("temperature sample 7 is -400 degC, below absolute zero"), std::string::npos)
      << why;
  temperature[6] = -273.15;
  EXPECT_NO_THROW(fit_temperature(rate, temperature, 10.0));
}

}  // namespace
}  // namespace foglab::model
