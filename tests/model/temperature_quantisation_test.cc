// A quantised temperature channel: its step found from the readings, and the
// temperature between the steps (model/temperature_quantisation.h).
#include "foglab/model/temperature_quantisation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/noise.h"

namespace foglab::model {
namespace {

// A 10 degC ramp from 20.03 degC over n samples, with sensor noise of sd
// `noise_c`, read in steps of `q` (0: not rounded).
struct Channel {
  std::vector<double> truth, read;
};
Channel ramp(std::size_t n, double q, double noise_c, std::uint64_t seed) {
  Channel c{std::vector<double>(n), test::mt_normal(n, seed, 0.0, noise_c)};
  for (std::size_t k = 0; k < n; ++k) {
    c.truth[k] = 20.03 + 10.0 * static_cast<double>(k) / static_cast<double>(n);
    c.read[k] += c.truth[k];
    if (q > 0) c.read[k] = std::round(c.read[k] / q) * q;
  }
  return c;
}

double rms_error(const std::vector<double>& a, const std::vector<double>& b) {
  double ss = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) ss += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(ss / static_cast<double>(a.size()));
}

TEST(TemperatureQuantisation, FindsTheStepOfAStaircase) {
  const Channel c = ramp(720000, 0.0625, 0.0, 1);  // 2 h at 100 Hz
  const TemperatureQuantisation t = find_temperature_quantisation(c.read, 100.0);
  ASSERT_TRUE(t.detected);
  EXPECT_NEAR(t.lsb_c, 0.0625, 1e-12);
  EXPECT_EQ(t.changes, 160);
  EXPECT_EQ(t.distinct_values, 161);
  EXPECT_NEAR(t.mean_hold_s, 7200.0 / 161.0, 1e-9);
}

TEST(TemperatureQuantisation, NotAChannelThatMovesOnMostSamples) {
  // Not rounded; or rounded finer than its noise (the reading changes on
  // most samples); or held between irregular readings (a slow sensor, no
  // grid): none is a staircase of steps.
  EXPECT_FALSE(find_temperature_quantisation(ramp(100000, 0.0, 0.0, 2).read, 100.0).detected);
  EXPECT_FALSE(find_temperature_quantisation(ramp(100000, 0.001, 0.01, 3).read, 100.0).detected);
  std::vector<double> held = ramp(100000, 0.0, 0.01, 4).read;
  for (std::size_t k = 0; k < held.size(); ++k) held[k] = held[k / 100 * 100];
  EXPECT_FALSE(find_temperature_quantisation(held, 100.0).detected);
}

TEST(TemperatureQuantisation, AStaircaseComesBackAsTheRamp) {
  const Channel c = ramp(200000, 0.25, 0.0, 5);
  const std::vector<double> t = reconstruct_quantised_temperature(c.read, 0.25);
  double worst = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) worst = std::max(worst, std::fabs(t[k] - c.truth[k]));
  EXPECT_LT(worst, 1e-4);                       // half a sample's change
  EXPECT_GT(rms_error(c.read, c.truth), 0.07);  // the staircase: q / sqrt(12)
}

TEST(TemperatureQuantisation, ASensorsNoiseAtTheStepsIsOneCrossing) {
  // Noise of 0.1 q: the reading flickers between neighbours for a while at
  // each step. Taken one change at a time, the temperature would stay at
  // the boundary through the flicker; taken as one crossing, it follows
  // the ramp to a fraction of the step.
  const double q = 0.5;
  const Channel c = ramp(720000, q, 0.05, 6);
  const TemperatureQuantisation found = find_temperature_quantisation(c.read, 100.0);
  ASSERT_TRUE(found.detected);
  EXPECT_NEAR(found.lsb_c, q, 1e-12);
  EXPECT_GT(found.changes, 200);  // the flicker: 20 steps in all
  const std::vector<double> t = reconstruct_quantised_temperature(c.read, q);
  EXPECT_LT(rms_error(t, c.truth), 0.02 * q);
  EXPECT_GT(rms_error(c.read, c.truth), 0.25 * q);
}

TEST(TemperatureQuantisation, AFlickerAtAConstantTemperatureIsTheBoundary) {
  std::vector<double> read = test::mt_normal(100000, 7, 25.125, 0.03);
  for (double& v : read) v = std::round(v / 0.25) * 0.25;
  const std::vector<double> t = reconstruct_quantised_temperature(read, 0.25);
  for (std::size_t k = 0; k < t.size(); k += 997) EXPECT_DOUBLE_EQ(t[k], 25.125);
}

}  // namespace
}  // namespace foglab::model
