// Tests of placing jittered time stamps on their sampling grid (src/io/stamp_grid.h), the
// method the ROS bag reader and the text and MAT readers share: heavy jitter with samples
// lost here and there and a logger's clock running fast, and stamps that have no grid.
#include "../../src/io/stamp_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace foglab::io::internal {
namespace {

struct Stamps {
  std::vector<std::int64_t> ns;
  std::vector<Gap> gaps;  // the truth, among the stamps kept
};

// `count` samples at 100 Hz on a logger's clock `ppm` fast, each stamp moved by a uniform draw
// of +-`jitter` of a step, each sample lost with probability `loss`.
Stamps stamps(std::size_t count, double jitter, double loss, double ppm, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::uniform_real_distribution<double> p(0.0, 1.0);
  Stamps s;
  std::int64_t lost = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double t_s = (static_cast<double>(k) * (1.0 + ppm * 1e-6) + u(random)) / 100.0;
    if (k > 0 && p(random) < loss) {
      ++lost;
      continue;
    }
    if (lost > 0) s.gaps.push_back({static_cast<std::int64_t>(s.ns.size()), lost});
    lost = 0;
    s.ns.push_back(std::llround(t_s * 1e9));
  }
  return s;
}

TEST(StampGrid, HeavyJitterWithSamplesLostHereAndThereIsPlacedExactly) {
  // +-40 % jitter with 1 % of the samples lost: the phase differences of single stamps had
  // put the step 0.2 % off here, and a tenth of the stamps in the wrong slots
  for (const double ppm : {0.0, 50.0}) {
    SCOPED_TRACE(ppm);
    const Stamps s = stamps(200000, 0.4, 0.01, ppm, 21);
    const StampGrid grid = fit_stamp_grid(s.ns, median_step_s(s.ns));
    EXPECT_TRUE(grid.dropped.empty());
    ASSERT_EQ(grid.gaps.size(), s.gaps.size());
    for (std::size_t g = 0; g < s.gaps.size(); ++g) {
      ASSERT_EQ(grid.gaps[g].before_sample, s.gaps[g].before_sample) << g;
      ASSERT_EQ(grid.gaps[g].missing_samples, s.gaps[g].missing_samples) << g;
    }
    EXPECT_NEAR(grid.step_s / (0.01 * (1.0 + ppm * 1e-6)), 1.0, 1e-6);
    // uniform +-0.4 of a step: rms 0.4 / sqrt(3) = 0.231 steps about the grid and the line
    EXPECT_NEAR(grid.scatter_rms_steps, 0.4 / std::sqrt(3.0), 0.005);
    EXPECT_NEAR(grid.jitter_rms_s / (0.004 / std::sqrt(3.0)), 1.0, 0.02);
  }
}

TEST(StampGrid, AStampOnTheSlotBeforeItIsDropped) {
  Stamps s = stamps(5000, 0.2, 0.0, 0.0, 4);
  s.ns.insert(s.ns.begin() + 1000, s.ns[999] + 1000000);  // 1 ms after the stamp before it
  const StampGrid grid = fit_stamp_grid(s.ns, median_step_s(s.ns));
  ASSERT_EQ(grid.dropped.size(), 1u);
  EXPECT_EQ(grid.dropped[0], 1000u);
  EXPECT_TRUE(grid.gaps.empty());
  std::vector<double> values(s.ns.size());
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = static_cast<double>(k);
  drop_entries(values, grid.dropped);
  ASSERT_EQ(values.size(), 5000u);
  EXPECT_EQ(values[999], 999.0);
  EXPECT_EQ(values[1000], 1001.0);
}

TEST(StampGrid, StampsWithoutAGridScatterOverTheWholeStep) {
  // a Poisson process: no grid, so its phases fill the step (rms 1/sqrt(12) = 0.289)
  std::mt19937_64 random(6);
  std::exponential_distribution<double> step_s(100.0);
  std::vector<std::int64_t> ns;
  double t_s = 0.0;
  for (int k = 0; k < 20000; ++k) {
    t_s += step_s(random);
    ns.push_back(std::llround(t_s * 1e9));
  }
  EXPECT_GT(fit_stamp_grid(ns, median_step_s(ns)).scatter_rms_steps, 0.27);
}

}  // namespace
}  // namespace foglab::io::internal
