// Tests of the short taus' stationarity check (allan_drift.h): no call on
// stationary noise of several kinds, over independent records (the
// Mann–Kendall z then follows N(0, 1)); a call with the right size on a
// white level that rises over the record; blocks and gaps.
#include "foglab/stats/allan_drift.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "foglab/core/error.h"
#include "support/noise.h"

namespace foglab::stats {
namespace {

constexpr double kTau0S = 0.01;

TEST(AllanDrift, StationaryNoiseRaisesNoCallAndItsZIsStandardNormal) {
  // White noise; white noise through a 3-sample moving average with a
  // random walk; white noise with a strong sine line (a resonance that
  // stays put). 2^17 samples, 32 blocks of 4096: taus of 1 to 16 samples.
  constexpr std::size_t kSamples = 1 << 17;
  double sum_z2 = 0.0;
  int count = 0, calls = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    std::vector<double> x = test::white(kSamples, seed, 1.0);
    if (seed % 3 == 1) {
      const std::vector<double> walk = test::random_walk(kSamples, seed + 1000, 0.01);
      std::vector<double> y(kSamples);
      for (std::size_t i = 0; i < kSamples; ++i) {
        y[i] = (x[i] + x[(i + 1) % kSamples] + x[(i + 2) % kSamples]) / 3.0 + walk[i];
      }
      x = y;
    } else if (seed % 3 == 2) {
      for (std::size_t i = 0; i < kSamples; ++i) x[i] += 3.0 * std::sin(0.4 * 3.1 * i);
    }
    const AllanDrift d = allan_drift(x, kTau0S);
    ASSERT_EQ(d.blocks, 32);
    ASSERT_EQ(d.tau_s.size(), 5u);  // 1, 2, 4, 8, 16 samples: 4096 / 256 = 16
    EXPECT_DOUBLE_EQ(d.tau_s[4], 16 * kTau0S);
    for (std::size_t k = 0; k < d.tau_s.size(); ++k) {
      sum_z2 += d.trend_z[k] * d.trend_z[k];
      ++count;
      calls += d.drifting[k];
    }
    EXPECT_FALSE(d.any()) << "seed " << seed;
  }
  EXPECT_EQ(calls, 0);
  // 150 values of z (the taus of one record are correlated, so fewer are
  // independent): the mean square of N(0, 1) with room for that.
  const double mean_square = sum_z2 / count;
  EXPECT_GT(mean_square, 0.6);
  EXPECT_LT(mean_square, 1.6);
}

TEST(AllanDrift, AWhiteLevelThatRisesOverTheRecordIsCalledWithItsSize) {
  // The variance rises linearly by 10 % from the first sample to the last:
  // the first eighth's mean is 1 + 0.1 / 16 of the start's, the last
  // eighth's 1 + 0.1 * 15 / 16: a ratio of 1.0870.
  constexpr std::size_t kSamples = 1 << 20;
  std::vector<double> x = test::white(kSamples, 7, 1.0);
  for (std::size_t i = 0; i < kSamples; ++i) {
    x[i] *= std::sqrt(1.0 + 0.1 * static_cast<double>(i) / kSamples);
  }
  const AllanDrift d = allan_drift(x, kTau0S);
  ASSERT_EQ(d.tau_s.size(), 8u);  // 32768 / 256 = 128 samples
  ASSERT_TRUE(d.any());
  for (std::size_t k = 0; k < 4; ++k) {  // 1 to 8 samples, where blocks scatter by under 2 %
    EXPECT_TRUE(d.drifting[k]) << d.tau_s[k];
    EXPECT_GT(d.trend_z[k], 0.0);
    // A block's Allan variance at m samples scatters by about
    // sqrt(3 m / 32768) (1 % at m = 1): four blocks' mean by half that.
    EXPECT_NEAR(d.last_to_first[k], 1.0870, 0.03) << d.tau_s[k];
  }
  // Block by block (the report's drift plot): at one sample a block's
  // Allan variance is the white variance at its middle, 1 + 0.1 (b + 1/2)
  // / 32, within its scatter of about 1 % (4 sd allowed).
  ASSERT_EQ(d.block_time_s.size(), 32u);
  ASSERT_EQ(d.block_adev.size(), d.tau_s.size());
  for (std::size_t b = 0; b < 32; ++b) {
    EXPECT_DOUBLE_EQ(d.block_time_s[b], static_cast<double>(32768 * b + 16384) * kTau0S);
    ASSERT_EQ(d.block_adev[0].size(), 32u);
    const double truth = 1.0 + 0.1 * (static_cast<double>(b) + 0.5) / 32.0;
    EXPECT_NEAR(d.block_adev[0][b] * d.block_adev[0][b] / truth, 1.0, 0.04) << "block " << b;
  }
}

TEST(AllanDrift, AStepOrABurstInOneBlockMovesOneRankOnly) {
  constexpr std::size_t kSamples = 1 << 17;
  std::vector<double> x = test::white(kSamples, 11, 1.0);
  for (std::size_t i = 70000; i < 70100; ++i) x[i] += 40.0 * ((i % 2) ? 1.0 : -1.0);
  for (std::size_t i = 90000; i < kSamples; ++i) x[i] += 25.0;  // a bias step
  const AllanDrift d = allan_drift(x, kTau0S);
  EXPECT_FALSE(d.any());
}

TEST(AllanDriftGaps, BlocksTheGapsEmptyAreLeftOutAndTheCheckStillSeesADrift) {
  constexpr std::size_t kSamples = 1 << 20;
  std::vector<double> x = test::white(kSamples, 13, 1.0);
  for (std::size_t i = 0; i < kSamples; ++i) {
    x[i] *= std::sqrt(1.0 + 0.1 * static_cast<double>(i) / kSamples);
  }
  // Gaps: a sample lost every 100 in the first two blocks (stretches of
  // 100 samples hold no term at 64 samples and more, and those blocks are
  // left out there), and a long one further on.
  std::vector<Gap> gaps;
  for (std::int64_t at = 100; at < 65536; at += 100) gaps.push_back({at, 1});
  gaps.push_back({600000, 50000});
  const AllanDrift d = allan_drift(x, kTau0S, gaps);
  ASSERT_EQ(d.tau_s.size(), 8u);
  EXPECT_EQ(d.blocks_used[0], 32);
  EXPECT_EQ(d.blocks_used[5], 32);  // 32 samples: 37 terms of 100 a stretch, over a quarter
  EXPECT_EQ(d.blocks_used[6], 30);  // 64 samples: none
  EXPECT_EQ(d.blocks_used[7], 30);
  EXPECT_TRUE(d.drifting[0]);
  EXPECT_NEAR(d.last_to_first[0], 1.0870, 0.03);
  // The blocks left out have no value there; the blocks' times count the
  // samples the gaps dropped before their middles (655 single samples in
  // the first two blocks, 50,000 at sample 600,000).
  EXPECT_TRUE(std::isnan(d.block_adev[6][0]));
  EXPECT_TRUE(std::isnan(d.block_adev[6][1]));
  EXPECT_TRUE(std::isfinite(d.block_adev[6][2]));
  EXPECT_DOUBLE_EQ(d.block_time_s[0], (16384.0 + 163.0) * kTau0S);
  EXPECT_DOUBLE_EQ(d.block_time_s[2], (2 * 32768 + 16384.0 + 655.0) * kTau0S);
  EXPECT_DOUBLE_EQ(d.block_time_s[31], (31 * 32768 + 16384.0 + 655.0 + 50000.0) * kTau0S);
  // The same white noise, stationary, with those gaps: no call.
  const std::vector<double> y = test::white(kSamples, 13, 1.0);
  EXPECT_FALSE(allan_drift(y, kTau0S, gaps).any());
}

TEST(AllanDrift, ARecordTooShortForTheBlocksIsNotChecked) {
  const std::vector<double> x = test::white(8000, 3, 1.0);  // 32 x 256 = 8192 needed
  const AllanDrift d = allan_drift(x, kTau0S);
  EXPECT_EQ(d.blocks, 0);
  EXPECT_TRUE(d.tau_s.empty());
  EXPECT_FALSE(d.any());
  EXPECT_THROW(allan_drift(x, 0.0), UsageError);
  EXPECT_THROW(allan_drift(x, kTau0S, {}, {.blocks = 8}), UsageError);
}

}  // namespace
}  // namespace foglab::stats
