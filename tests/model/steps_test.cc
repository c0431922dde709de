// Bias steps (model/steps.h): found where they are, levelled, and not
// invented by drift or random walk.
#include "foglab/model/steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/model/spikes.h"
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

TEST(Steps, AShortPulseIsTwoStepsOfItsHeight) {
  // The bias up by 2 sample sd for 3,000 samples and back (a transient, or
  // one level of a telegraph bias): at the window that finds an edge best
  // the 4 W either side span both, and the size had been a fraction of the
  // height (0.21 of 2 on a telegraph record), then the same sample was
  // found again with sizes of 1e-15. Each edge is found with its height.
  std::vector<double> y = test::mt_normal(400000, 4, 0.0, 1.0);
  for (std::size_t k = 200000; k < 203000; ++k) y[k] += 2.0;
  const BiasSteps s = find_steps(y);
  ASSERT_EQ(s.indices.size(), 2u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 200000.0, 50.0);
  EXPECT_NEAR(static_cast<double>(s.indices[1]), 203000.0, 50.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 2.0, 0.15);
  EXPECT_NEAR(s.sizes_deg_h[1], -2.0, 0.15);
  EXPECT_TRUE(s.removed);
  EXPECT_FALSE(s.left_as_noise());
}

// White noise of unit sd with a random telegraph bias of +-amplitude (a
// popcorn noise: it switches with probability 1 / dwell at each sample).
std::vector<double> telegraph(std::size_t n, std::uint64_t seed, double amplitude, double dwell) {
  std::vector<double> y = test::mt_normal(n, seed, 0.0, 1.0);
  std::mt19937_64 engine(seed + 1000);
  std::bernoulli_distribution flip(1.0 / dwell);
  double level = amplitude;
  for (double& v : y) {
    if (flip(engine)) level = -level;
    v += level;
  }
  return y;
}

TEST(Steps, ATelegraphBiasIsLeftInAsTheProcessItIs) {
  // 720,000 samples of a telegraph bias. Levelling the jumps the search
  // finds (at most 20) had left the rest as a random walk: the analysis
  // then took the bounded process for a Wiener bias. None is levelled, the
  // record is as it was, and the reason is the one that holds: about 70
  // jumps of 2 (beyond the limit); about 70 of 0.2, of which a few stand
  // out (levelling them makes the record wander); about 14 of 0.6, all
  // found (back and forth between two levels, levelling them all leaves
  // the record calm).
  using AsNoise = BiasSteps::AsNoise;
  const struct {
    double amplitude, dwell;
    AsNoise why;
  } cases[] = {{1.0, 10000.0, AsNoise::beyond_limit},
               {0.1, 10000.0, AsNoise::wander},
               {0.3, 50000.0, AsNoise::two_levels}};
  for (const auto& c : cases) {
    std::vector<double> y = telegraph(720000, 7, c.amplitude, c.dwell);
    const std::vector<double> before = y;
    const BiasSteps s = find_steps(y);
    EXPECT_GE(s.indices.size(), 2u) << c.amplitude;
    EXPECT_TRUE(s.left_as_noise()) << c.amplitude;
    EXPECT_EQ(s.left_as_noise_because, c.why) << c.amplitude;
    EXPECT_FALSE(s.removed) << c.amplitude;
    for (std::size_t k = 0; k < y.size(); k += 1000) ASSERT_NEAR(y[k], before[k], 1e-9);
  }
}

TEST(Steps, ASteepDriftNeitherSizesNorRepeatsAStep) {
  // A drift of 40 sample sd over the record (a temperature ramp with no
  // temperature channel, a rate ramp): the step's size had taken the
  // drift over the 4 W either side (+30 % here), and the search found the
  // step again and again, with sizes near 0, up to the limit.
  std::vector<double> y = test::mt_normal(400000, 4, 0.0, 1.0);
  for (std::size_t k = 0; k < y.size(); ++k) {
    y[k] += 1e-4 * static_cast<double>(k) + (k >= 150000 ? 0.5 : 0.0);
  }
  const BiasSteps s = find_steps(y);
  ASSERT_EQ(s.indices.size(), 1u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 150000.0, 200.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 0.5, 0.05);
}

TEST(Steps, AJumpAcrossAGapIsNoStep) {
  // The bias moved while nothing was recorded: the stretches either side
  // of the gap differ by 2 sample sd, which is no step; a real step of 0.5
  // in the later stretch is still found, and levelled from there on.
  std::vector<double> y = test::mt_normal(400000, 5, 0.0, 1.0);
  for (std::size_t k = 200000; k < y.size(); ++k) y[k] += 2.0;
  for (std::size_t k = 300000; k < y.size(); ++k) y[k] += 0.5;
  const std::vector<Gap> gaps = {{200000, 5000}};
  const std::vector<double> before = y;
  const BiasSteps s = find_steps(y, {}, 0.0, gaps);
  ASSERT_EQ(s.indices.size(), 1u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 300000.0, 200.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 0.5, 0.05);
  EXPECT_EQ(y[250000], before[250000]);
  EXPECT_NEAR(y[350000], before[350000] - s.sizes_deg_h[0], 1e-12);
  // Taken as one stretch, the jump is a step.
  std::vector<double> z = before;
  EXPECT_EQ(find_steps(z).indices.size(), 2u);
  // Measured on its own: 2 sample sd, over 4 windows of up to 6,250
  // samples either side (the size's sd about 0.009).
  ASSERT_EQ(s.across_gaps.size(), 1u);
  EXPECT_EQ(s.across_gaps[0].before_sample, 200000);
  EXPECT_NEAR(s.across_gaps[0].size_deg_h, 2.0, 0.04);
  EXPECT_TRUE(s.across_gaps[0].significant);
  EXPECT_GT(s.across_gaps[0].significance, 20.0);
}

TEST(Steps, ADriftThroughAGapIsNoJumpAcrossIt) {
  // A drift of 1e-4 sample sd per sample goes on through three gaps (1,
  // 5,000 and 40,000 samples: the last moves the bias by 4 sd): no jump,
  // each size within 0.1 of 0 (its noise's sd 0.009, the drift's slope
  // estimated to about 5e-7 per sample over up to 65,000 samples; the
  // drift over the last gap and its windows is 6.5); then a jump of 0.3
  // added after the second gap is measured there and nowhere else.
  const std::vector<Gap> gaps = {{100000, 1}, {200000, 5000}, {300000, 40000}};
  std::vector<double> y = test::mt_normal(400000, 8, 0.0, 1.0);
  for (std::size_t k = 0; k < y.size(); ++k) {
    std::int64_t missing = 0;
    for (const Gap& g : gaps)
      missing += static_cast<std::int64_t>(k) >= g.before_sample ? g.missing_samples : 0;
    y[k] += 1e-4 * static_cast<double>(static_cast<std::int64_t>(k) + missing);
  }
  std::vector<double> a = y;
  const BiasSteps none = find_steps(a, {}, 0.0, gaps);
  EXPECT_TRUE(none.indices.empty());
  ASSERT_EQ(none.across_gaps.size(), 3u);
  for (const GapJump& j : none.across_gaps) {
    SCOPED_TRACE(j.before_sample);
    EXPECT_LT(std::fabs(j.size_deg_h), 0.1) << j.window_samples << " z " << j.significance;
    EXPECT_FALSE(j.significant);
  }
  for (std::size_t k = 200000; k < y.size(); ++k) y[k] += 0.3;
  const BiasSteps one = find_steps(y, {}, 0.0, gaps);
  EXPECT_TRUE(one.indices.empty());
  ASSERT_EQ(one.across_gaps.size(), 3u);
  EXPECT_FALSE(one.across_gaps[0].significant);
  EXPECT_TRUE(one.across_gaps[1].significant);
  EXPECT_NEAR(one.across_gaps[1].size_deg_h, 0.3, 0.05);
  EXPECT_FALSE(one.across_gaps[2].significant);
}

TEST(Steps, AJumpAcrossAGapLongerThanTheStretchesIsMeasuredNotJudged) {
  // No stretch holds two windows 300,000 samples apart: nothing to judge
  // the jump by (its significance is NaN, it is not significant), but its
  // size is still measured, over the longest windows.
  std::vector<double> y = test::mt_normal(200000, 9, 0.0, 1.0);
  for (std::size_t k = 100000; k < y.size(); ++k) y[k] += 5.0;
  const std::vector<Gap> gaps = {{100000, 300000}};
  const BiasSteps s = find_steps(y, {}, 0.0, gaps);
  EXPECT_TRUE(s.indices.empty());
  ASSERT_EQ(s.across_gaps.size(), 1u);
  EXPECT_TRUE(std::isnan(s.across_gaps[0].significance));
  EXPECT_FALSE(s.across_gaps[0].significant);
  EXPECT_EQ(s.across_gaps[0].window_samples, 2048);  // the longest: 64 W <= 200,000
  EXPECT_NEAR(s.across_gaps[0].size_deg_h, 5.0, 0.1);
}

TEST(Steps, AreFoundOnTopOfACurvedBaseline) {
  // A temperature law with curvature (a parabola of 30 sample sd): with
  // it as the baseline the two steps are found with their sizes, and the
  // record keeps the law (only the steps are levelled).
  const std::size_t n = 400000;
  std::vector<double> law(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(n) - 0.5;
    law[k] = 120.0 * u * u;
  }
  std::vector<double> y = test::mt_normal(n, 6, 0.0, 1.0);
  for (std::size_t k = 0; k < n; ++k) {
    y[k] += law[k] + (k >= 100000 ? 0.4 : 0.0) + (k >= 250000 ? -0.6 : 0.0);
  }
  const BiasSteps s = find_steps(y, {}, 0.0, {}, law);
  ASSERT_EQ(s.indices.size(), 2u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 100000.0, 300.0);
  EXPECT_NEAR(static_cast<double>(s.indices[1]), 250000.0, 300.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 0.4, 0.06);
  EXPECT_NEAR(s.sizes_deg_h[1], -0.6, 0.06);
  double end = 0.0;  // the last 10,000 samples still carry the law
  for (std::size_t k = n - 10000; k < n; ++k) end += y[k] - law[k];
  EXPECT_NEAR(end / 1e4, 0.0, 0.1);
}

TEST(Steps, AHeavyTailedNoisesOutliersAreNoSteps) {
  // t with 3 degrees of freedom (unit variance): a single sample of 60
  // sd moves a 64-sample window's mean by a step of 6 spreads of D, and
  // the search had found up to 20 steps about such samples. Pulled in to 5
  // robust spreads of h for the search, they are none, and a real step of
  // 0.3 sd is still found once.
  std::mt19937_64 engine(11);
  std::student_t_distribution<double> t(3.0);
  std::vector<double> y(720000);
  for (double& v : y) v = t(engine) / std::sqrt(3.0);
  std::vector<double> z = y;
  StepOptions heavy;
  heavy.outlier_clip_deg_h = 5.0 * find_spikes(z, {.remove = false}).robust_sd_deg_h;
  EXPECT_GE(find_steps(z).indices.size(), 2u);  // without: the failure
  z = y;
  EXPECT_TRUE(find_steps(z, heavy).indices.empty());
  for (std::size_t k = 400000; k < y.size(); ++k) y[k] += 0.3;
  const std::vector<double> before = y;
  const BiasSteps s = find_steps(y, heavy);
  ASSERT_EQ(s.indices.size(), 1u);
  EXPECT_NEAR(static_cast<double>(s.indices[0]), 400000.0, 500.0);
  EXPECT_NEAR(s.sizes_deg_h[0], 0.3, 0.05);
  // Levelled in the record itself, the outliers kept.
  for (std::size_t k = 0; k < y.size(); ++k) {
    ASSERT_NEAR(
        y[k],
        k >= static_cast<std::size_t>(s.indices[0]) ? before[k] - s.sizes_deg_h[0] : before[k],
        1e-12);
  }
}

TEST(Steps, ABadBaselineOrGapIsAUsageError) {
  std::vector<double> y(1000, 0.0);
  const std::vector<double> short_law(999, 0.0);
  EXPECT_THROW(find_steps(y, {}, 0.0, {}, short_law), UsageError);
  const std::vector<Gap> outside = {{1000, 5}};
  EXPECT_THROW(find_steps(y, {}, 0.0, outside), UsageError);
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
