// Spikes (model/spikes.h): found, replaced, and not invented.
#include "foglab/model/spikes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "support/noise.h"

namespace foglab::model {
namespace {

std::vector<double> white(std::size_t n, std::uint64_t seed) {
  return test::mt_normal(n, seed, 5.0, 1.0);
}

// An output word whose step is ten times the noise: almost every sample
// reads 0, one in about 700 reads one step up.
std::vector<double> coarse_word(std::size_t n, std::uint64_t seed) {
  std::vector<double> y = test::mt_normal(n, seed, 2.0, 1.0);
  for (double& v : y) v = std::round(v / 10.0) * 10.0;
  return y;
}

// Student's t noise of unit variance: a heavy tail of power `dof`.
std::vector<double> student(std::size_t n, double dof, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::student_t_distribution<double> t(dof);
  std::vector<double> y(n);
  for (double& v : y) v = t(engine) * std::sqrt((dof - 2.0) / dof);
  return y;
}

TEST(Spikes, AHeavyTailedNoiseKeepsItsOutliers) {
  // t with 3 degrees of freedom: at 8 robust standard deviations the fixed
  // threshold took about 750 of 7.2 x 10^5 samples for spikes (its tail
  // holds 17 % of the variance).
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    std::vector<double> y = student(720000, 3.0, seed);
    const std::vector<double> before = y;
    const Spikes s = find_spikes(y);
    EXPECT_TRUE(s.heavy_tailed) << seed;
    EXPECT_GT(s.shoulder_count, 1000) << seed;
    EXPECT_LT(s.shoulder_expected, 1.0) << seed;
    EXPECT_NEAR(s.tail_index, 3.0, 0.6) << seed;
    EXPECT_EQ(s.count, 0) << seed;
    EXPECT_EQ(y, before) << seed;
    // A departure far beyond the tail is a spike still.
    y[4321] += 50.0 * s.threshold_deg_h;
    const Spikes again = find_spikes(y);
    ASSERT_EQ(again.count, 1) << seed;
    EXPECT_EQ(again.indices[0], 4321) << seed;
  }
}

TEST(Spikes, AHeavyTailedNoisesKurtosisIsMeasuredFromItsDifferences) {
  // t with 10 degrees of freedom: excess kurtosis 6 / (10 - 4) = 1; the
  // difference of two samples has half of it.
  for (std::uint64_t seed = 4; seed <= 6; ++seed) {
    std::vector<double> y = student(720000, 10.0, seed);
    const Spikes s = find_spikes(y);
    ASSERT_TRUE(s.heavy_tailed) << seed;
    EXPECT_NEAR(s.excess_kurtosis, 1.0, 0.35) << seed;
  }
  std::vector<double> g = white(720000, 7);
  EXPECT_EQ(find_spikes(g).excess_kurtosis, 0.0);  // not heavy-tailed: not measured
}

TEST(Spikes, ManySpikesInGaussianNoiseAreNotATail) {
  // 200 spikes of 9 to 30 robust standard deviations: their neighbours
  // depart by half of them, into the 4-8 band, and are not outlier
  // centres; nothing of Gaussian noise is in the 5-8 band.
  std::vector<double> y = white(720000, 8);
  std::mt19937_64 engine(9);
  std::uniform_real_distribution<double> size(9.0, 30.0);
  const double sd_h = std::sqrt(1.5);
  for (std::size_t i = 0; i < 200; ++i)
    y[1000 + 3500 * i] += (i % 2 ? 1.0 : -1.0) * size(engine) * sd_h;
  const Spikes s = find_spikes(y);
  EXPECT_FALSE(s.heavy_tailed);
  EXPECT_LE(s.shoulder_count, 5);
  EXPECT_EQ(s.count, 200);
  EXPECT_NEAR(s.threshold_deg_h, 8.0 * sd_h, 0.2);
}

TEST(Spikes, OneStepExcursionsOfACoarseOutputWordAreNone) {
  // The robust scale collapses there (most h are 0), and every one-step
  // excursion had passed for a spike; given the output's step, a spike
  // must depart by four of them.
  std::vector<double> y = coarse_word(200000, 5);
  std::vector<double> z = y;
  EXPECT_GT(find_spikes(z).count, 100);  // without the step: the failure
  EXPECT_EQ(find_spikes(y, {}, 10.0).count, 0);
  y[1000] += 80.0;  // eight steps: a spike still
  const Spikes s = find_spikes(y, {}, 10.0);
  ASSERT_EQ(s.count, 1);
  EXPECT_EQ(s.indices[0], 1000);
}

TEST(Spikes, IsolatedOutliersAreReplacedByTheirNeighboursMean) {
  std::vector<double> y = white(200000, 1);
  const std::vector<std::size_t> at = {10, 5000, 123456, 199990};
  for (std::size_t k : at) y[k] += (k % 2 ? -1.0 : 1.0) * 30.0;
  const std::vector<double> before = y;
  const Spikes s = find_spikes(y);
  ASSERT_EQ(s.count, 4);
  for (std::size_t i = 0; i < at.size(); ++i) {
    EXPECT_EQ(s.indices[i], static_cast<std::int64_t>(at[i]));
    EXPECT_NEAR(std::fabs(s.sizes_deg_h[i]), 30.0, 6.0);
    EXPECT_DOUBLE_EQ(y[at[i]], 0.5 * (before[at[i] - 1] + before[at[i] + 1]));
  }
  // The robust scale is that of h = y_k - (y_(k-1) + y_(k+1)) / 2: sqrt(1.5).
  EXPECT_NEAR(s.robust_sd_deg_h, std::sqrt(1.5), 0.02);
  EXPECT_TRUE(s.removed);
}

TEST(Spikes, NoneInGaussianNoiseAndAStepIsNotASpike) {
  std::vector<double> y = white(1000000, 2);
  for (std::size_t k = 500000; k < y.size(); ++k) y[k] += 40.0;  // a bias step
  const std::vector<double> before = y;
  const Spikes s = find_spikes(y);
  EXPECT_EQ(s.count, 0);
  EXPECT_FALSE(s.heavy_tailed);
  EXPECT_LT(s.shoulder_count, 10);  // expected 0.57 in 10^6 samples
  EXPECT_EQ(y, before);
}

TEST(Spikes, ReportOnlyLeavesTheRecord) {
  std::vector<double> y = white(10000, 3);
  y[77] += 50.0;
  const std::vector<double> before = y;
  SpikeOptions o;
  o.remove = false;
  const Spikes s = find_spikes(y, o);
  EXPECT_EQ(s.count, 1);
  EXPECT_FALSE(s.removed);
  EXPECT_EQ(y, before);
}

}  // namespace
}  // namespace foglab::model
