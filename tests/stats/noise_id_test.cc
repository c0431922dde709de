// Power-law noise identification on simulated noise of known type.
#include "foglab/stats/noise_id.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "foglab/stats/allan.h"
#include "support/noise.h"

namespace foglab::stats {
namespace {

std::vector<double> phase_of_rate(const std::vector<double>& rate) {
  return detail::to_phase(rate, 1.0, InputKind::rate);
}

TEST(NoiseId, Lag1AutocorrelationOfAnAlternatingSeriesIsMinusOne) {
  const std::vector<double> alternating = {1, -1, 1, -1, 1, -1, 1, -1};
  EXPECT_NEAR(lag1_autocorrelation(alternating), -7.0 / 8.0, 1e-12);
  const std::vector<double> ramp = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_GT(lag1_autocorrelation(ramp), 0.6);
}

TEST(NoiseId, WhiteRateNoiseIsWhiteFm) {
  const auto phase = phase_of_rate(test::white(100000, 21, 1.0));
  for (const std::int64_t m : {1, 10, 100, 1000}) {
    const NoiseId id = identify_noise(phase, m, 2);
    EXPECT_EQ(id.alpha, 0) << "m " << m;
    EXPECT_EQ(id.method, NoiseIdMethod::lag1_acf);
    EXPECT_EQ(id.differences, 1);  // the phase is a random walk: one difference
  }
}

TEST(NoiseId, RateRandomWalkIsRandomWalkFm) {
  const auto phase = phase_of_rate(test::random_walk(100000, 22, 1.0));
  for (const std::int64_t m : {1, 10, 100}) {
    EXPECT_EQ(identify_noise(phase, m, 2).alpha, -2) << "m " << m;
  }
}

TEST(NoiseId, WhiteAngleNoiseIsWhitePm) {
  // Angle (phase) white noise, as angle quantisation looks at short tau.
  const std::vector<double> angle = test::white(100000, 23, 1.0);
  const auto phase = detail::to_phase(angle, 1.0, InputKind::phase);
  for (const std::int64_t m : {1, 10, 100}) {
    EXPECT_EQ(identify_noise(phase, m, 2).alpha, 2) << "m " << m;
  }
}

TEST(NoiseId, HadamardRangeReachesRandomRunFm) {
  // Integrated random walk of rate: S_y ~ f^-4, visible to the Hadamard family.
  std::vector<double> rate = test::random_walk(200000, 24, 1.0);
  for (std::size_t i = 1; i < rate.size(); ++i) rate[i] += rate[i - 1];
  const auto phase = phase_of_rate(rate);
  EXPECT_EQ(identify_noise(phase, 10, 3).alpha, -4);
  EXPECT_EQ(identify_noise(phase, 10, 2).alpha, -2);  // clamped for Allan
}

TEST(NoiseId, FewAveragesUseTheB1Ratio) {
  // 20 averages: too few for the lag-1 method.
  int white_fm = 0, rw_fm = 0;
  for (int s = 0; s < 20; ++s) {
    const auto white = phase_of_rate(test::white(20000, 100 + s, 1.0));
    const NoiseId a = identify_noise(white, 1000, 2);
    EXPECT_TRUE(a.method == NoiseIdMethod::b1 || a.method == NoiseIdMethod::b1_rn)
        << to_string(a.method);
    if (a.alpha == 0) ++white_fm;
    const auto walk = phase_of_rate(test::random_walk(20000, 200 + s, 1.0));
    if (identify_noise(walk, 1000, 2).alpha == -2) ++rw_fm;
  }
  // B1 is a coarse test with 20 averages; it must still be right most times.
  EXPECT_GE(white_fm, 14);
  EXPECT_GE(rw_fm, 14);
}

// Riley & Greenhall's lag-1 method done the textbook way, one factor at a
// time: decimate, fit and remove a quadratic (least squares), then difference
// until rho = r1 / (1 + r1) < 0.25 or d = d_max.
NoiseId textbook_lag1(const std::vector<double>& phase, std::int64_t m, int d_max) {
  const auto count = static_cast<std::int64_t>((phase.size() - 1) / m + 1);
  Eigen::MatrixXd basis(count, 3);
  Eigen::VectorXd points(count);
  for (std::int64_t k = 0; k < count; ++k) {
    const double u = 2.0 * static_cast<double>(k) / static_cast<double>(count - 1) - 1.0;
    basis.row(k) << 1.0, u, u * u;
    points(k) = phase[static_cast<std::size_t>(k * m)];
  }
  const Eigen::VectorXd fit = basis.colPivHouseholderQr().solve(points);
  const Eigen::VectorXd residual = points - basis * fit;
  std::vector<double> z(residual.data(), residual.data() + residual.size());
  NoiseId id;
  for (int d = 0;; ++d) {
    const double r1 = lag1_autocorrelation(z);
    id.rho = r1 / (1.0 + r1);
    id.differences = d;
    if (id.rho < 0.25 || d == d_max) break;
    for (std::size_t k = 0; k + 1 < z.size(); ++k) z[k] = z[k + 1] - z[k];
    z.pop_back();
  }
  id.alpha = 2 - 2 * id.differences - static_cast<int>(std::nearbyint(2.0 * id.rho));
  return id;
}

TEST(NoiseId, AllFactorsAtOnceGiveTheTextbookRhoOfEachFactor) {
  // Records of more than one chunk, so that chunk boundaries, the first
  // points (where a difference or its lag is missing) and every order of
  // difference are exercised: white rate (one difference), random-walk rate
  // (two), and its integral (three, with the Hadamard d_max). The last is
  // shorter: its angle record, a third integral, grows as n^2.5, and the
  // residual after the fit keeps fewer of rho's digits, in either
  // computation (up to 1.0e-6 apart with clang at n = 150001; at 70001, 3e-8
  // with GCC and 7e-8 with clang, the white and walk records 5e-12).
  const std::size_t n = 150001;
  std::vector<double> white = test::white(n, 31, 1.0);
  std::vector<double> walk = test::random_walk(n, 32, 1.0);
  std::vector<double> run(walk.begin(), walk.begin() + 70001);
  for (std::size_t i = 1; i < run.size(); ++i) run[i] += run[i - 1];
  const std::vector<std::int64_t> factors = {1, 2, 3, 4, 5, 8, 16, 100, 1000};
  for (const auto& [name, rate] : {std::pair{"white", white}, {"walk", walk}, {"run", run}}) {
    const auto phase = phase_of_rate(rate);
    for (const int d_max : {2, 3}) {
      const std::vector<NoiseId> ids = identify_noise(phase, factors, d_max);
      for (std::size_t q = 0; q < factors.size(); ++q) {
        const NoiseId expected = textbook_lag1(phase, factors[q], d_max);
        SCOPED_TRACE(std::string(name) + " m " + std::to_string(factors[q]) + " d_max " +
                     std::to_string(d_max));
        EXPECT_EQ(ids[q].method, NoiseIdMethod::lag1_acf);
        EXPECT_EQ(ids[q].differences, expected.differences);
        EXPECT_NEAR(ids[q].rho, expected.rho, std::string(name) == "run" ? 1e-6 : 1e-10);
        EXPECT_EQ(ids[q].alpha, std::clamp(expected.alpha, d_max == 3 ? -4 : -2, 2));
      }
    }
  }
}

}  // namespace
}  // namespace foglab::stats
