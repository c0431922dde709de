// Power-law noise identification on simulated noise of known type.
#include <gtest/gtest.h>

#include <vector>

#include "foglab/stats/allan.h"
#include "foglab/stats/noise_id.h"
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

}  // namespace
}  // namespace foglab::stats
