// Spikes (model/spikes.h): found, replaced, and not invented.
#include "foglab/model/spikes.h"

#include <gtest/gtest.h>

#include <cmath>
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
