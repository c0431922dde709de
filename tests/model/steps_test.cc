// Bias steps (model/steps.h): found where they are, levelled, and not
// invented by drift or random walk.
#include "foglab/model/steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "support/noise.h"

namespace foglab::model {
namespace {

TEST(Steps, ACoarseOutputWordGivesNoEmptyOrRepeatedSteps) {
  // An output word whose step is ten times the noise (almost every sample
  // 0): no step of size 0, none repeated, none below the output's step (a
  // step of size 0 had been found again and again, up to the limit).
  std::vector<double> y = test::mt_normal(400000, 6, 2.0, 1.0);
  for (double& v : y) v = std::round(v / 10.0) * 10.0;
  for (const double lsb : {0.0, 10.0}) {
    std::vector<double> z = y;
    const BiasSteps s = find_steps(z, {}, lsb);
    for (std::size_t i = 0; i < s.indices.size(); ++i) {
      EXPECT_GT(std::fabs(s.sizes_deg_h[i]), std::max(0.0, lsb - 1e-12));
      for (std::size_t j = 0; j < i; ++j) EXPECT_NE(s.indices[i], s.indices[j]);
    }
  }
  // A real step of 30 (three output steps) is still found.
  for (std::size_t k = 200000; k < y.size(); ++k) y[k] += 30.0;
  const BiasSteps s = find_steps(y, {}, 10.0);
  ASSERT_EQ(s.indices.size(), 1u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 200000.0, 200.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 30.0, 1.0);
}

TEST(Steps, TwoStepsAreFoundAndLevelled) {
  std::vector<double> y = test::mt_normal(400000, 1, 5.0, 1.0);
  for (std::size_t k = 100000; k < y.size(); ++k) y[k] += 0.3;  // 0.3 sample sd
  for (std::size_t k = 300000; k < y.size(); ++k) y[k] -= 0.5;
  const BiasSteps s = find_steps(y);
  ASSERT_EQ(s.indices.size(), 2u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 100000.0, 200.0);
  EXPECT_NEAR(static_cast<double>(s.indices[1]), 300000.0, 200.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 0.3, 0.05);
  EXPECT_NEAR(s.sizes_deg_h[1], -0.5, 0.05);
  EXPECT_TRUE(s.removed);
  // Levelled: the mean of the last quarter is the first quarter's again.
  double a = 0.0, b = 0.0;
  for (std::size_t k = 0; k < 100000; ++k) a += y[k], b += y[300000 + k];
  EXPECT_NEAR(a / 1e5, b / 1e5, 0.05);
}

TEST(Steps, NoneInWhiteNoiseADriftOrARandomWalk) {
  std::vector<double> y = test::mt_normal(1000000, 2, 5.0, 1.0);
  std::mt19937_64 engine(3);
  std::normal_distribution<double> normal;
  double walk = 0.0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    walk += 0.002 * normal(engine);                // a random walk
    y[k] += walk + 1e-6 * static_cast<double>(k);  // and a drift
  }
  const std::vector<double> before = y;
  const BiasSteps s = find_steps(y);
  EXPECT_TRUE(s.indices.empty()) << s.indices.size() << " at " << s.indices.front();
  EXPECT_EQ(y, before);
}

}  // namespace
}  // namespace foglab::model
