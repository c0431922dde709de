// The sensor's output chain (sim/sensor_output.h) on its own: each effect
// against its definition.
#include "foglab/sim/sensor_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/sim/generator.h"

namespace foglab::sim {
namespace {

std::vector<double> white(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(n);
  for (double& v : y) v = normal(engine);
  return y;
}

double lag1(const std::vector<double>& y) {
  double mean = 0.0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    c0 += (y[k] - mean) * (y[k] - mean);
    if (k > 0) c1 += (y[k] - mean) * (y[k - 1] - mean);
  }
  return c1 / c0;
}

TEST(SensorOutput, LowPassGivesTheLagOneCorrelationItsTimeConstantImplies) {
  SensorOutput o;
  o.filter_time_constant_s = 0.0054;
  const double fs = 100.0;
  std::vector<double> y = white(400000, 1);
  OutputChain chain(o, fs, 1, 0);
  // In two blocks: the state carries across.
  chain.apply(0, y.data(), 150000);
  chain.apply(150000, y.data() + 150000, y.size() - 150000);
  const double rho = std::exp(-1.0 / (fs * o.filter_time_constant_s));
  EXPECT_NEAR(lag1(y), rho, 4.0 / std::sqrt(400000.0));
}

TEST(SensorOutput, MovingAverageIsTheMeanOfTheLastKSamples) {
  SensorOutput o;
  o.moving_average_samples = 4;
  std::vector<double> x = white(1000, 2), y = x;
  OutputChain chain(o, 10.0, 1, 0);
  chain.apply(0, y.data(), 500);
  chain.apply(500, y.data() + 500, 500);
  for (std::size_t k = 3; k < x.size(); ++k) {
    EXPECT_NEAR(y[k], (x[k] + x[k - 1] + x[k - 2] + x[k - 3]) / 4.0, 1e-12) << k;
  }
  EXPECT_NEAR(y[1], (x[0] + x[1]) / 2.0, 1e-12);
}

TEST(SensorOutput, SinusoidStepsSpikesAndTheOutputWord) {
  SensorOutput o;
  o.sinusoids = {{2.5, 3.0, 0.4}};
  o.steps = {{50.0, 7.0}};
  o.spike_rate_per_hour = 360.0;  // 0.1 per second
  o.spike_size_deg_h = 1000.0;
  o.lsb_deg_h = 0.25;
  const double fs = 20.0;
  const std::size_t n = 4000;  // 200 s
  std::vector<double> y(n, 0.0);
  OutputChain chain(o, fs, 5, 2);
  chain.apply(0, y.data(), n);
  const std::vector<double> spikes = spike_times_s(o, fs, 5, 2, static_cast<std::int64_t>(n));
  ASSERT_EQ(spikes.size(), chain.spike_indices().size());
  // About 20 spikes in 200 s (Poisson: within 4 sd).
  EXPECT_NEAR(static_cast<double>(spikes.size()), 20.0, 4.0 * std::sqrt(20.0));
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / fs;
    double expected =
        3.0 * std::sin(2.0 * std::numbers::pi * 2.5 * t + 0.4) + (t >= 50.0 ? 7.0 : 0.0);
    for (double s : spikes) {
      if (std::fabs(s - t) < 1e-9) expected += (y[k] > expected ? 1000.0 : -1000.0);
    }
    EXPECT_NEAR(y[k], std::round(expected / 0.25) * 0.25, 1e-9) << "t " << t;
    EXPECT_NEAR(std::remainder(y[k], 0.25), 0.0, 1e-9);
  }
}

TEST(SensorOutput, ASquareWaveIsItsAmplitudeWithTheSineSign) {
  SensorOutput o;
  o.square_waves = {{0.5, 2.0, 0.3}};  // 0.5 Hz, +-2 deg/h
  const double fs = 20.0;
  const std::size_t n = 400;  // 10 periods
  std::vector<double> y(n, 1.0);
  OutputChain chain(o, fs, 5, 2);
  chain.apply(0, y.data(), n);
  int high = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / fs;
    const bool up = std::sin(2.0 * std::numbers::pi * 0.5 * t + 0.3) >= 0.0;
    EXPECT_EQ(y[k], up ? 3.0 : -1.0) << "t " << t;
    high += up;
  }
  EXPECT_NEAR(high, 200, 2);  // half of each period
  o.square_waves = {{10.0, 2.0, 0.0}};
  try {
    validate(o, fs);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("SensorOutput::square_waves[].frequency_hz"),
              std::string::npos);
  }
}

TEST(SensorOutput, ASpikeInADroppedStretchIsNotListed) {
  // The truth lists the spikes the file holds: those in the samples a
  // dropout loses are gone with them (analyze cannot find them).
  SensorOutput o;
  o.spike_rate_per_hour = 360.0;
  o.spike_size_deg_h = 1000.0;
  const double fs = 20.0;
  const std::int64_t n = 20000;  // 1000 s
  const std::vector<double> all = spike_times_s(o, fs, 5, 2, n);
  o.dropouts = {{200.0, 300.0}};
  const std::vector<double> kept = spike_times_s(o, fs, 5, 2, n);
  std::vector<double> expected;
  for (double t : all) {
    if (t < 200.0 || t >= 500.0) expected.push_back(t);
  }
  ASSERT_LT(expected.size(), all.size());  // some did fall in the dropout
  EXPECT_EQ(kept, expected);
}

TEST(SensorOutput, FilterGainAtTheLineFrequency) {
  SensorOutput o;
  o.filter_time_constant_s = 0.0054;
  o.moving_average_samples = 3;
  const double fs = 100.0, f = 20.0;
  const std::size_t n = 20000;
  std::vector<double> y(n);
  for (std::size_t k = 0; k < n; ++k) {
    y[k] = std::sin(2.0 * std::numbers::pi * f * static_cast<double>(k) / fs);
  }
  OutputChain chain(o, fs, 1, 0);
  chain.apply(0, y.data(), n);
  double ss = 0.0;
  for (std::size_t k = 1000; k < n; ++k) ss += y[k] * y[k];
  const double rms = std::sqrt(ss / static_cast<double>(n - 1000));
  EXPECT_NEAR(rms * std::sqrt(2.0), output_filter_gain(o, f, fs), 1e-3);
}

TEST(SensorOutput, BadFieldsAreNamed) {
  SensorOutput o;
  o.sinusoids = {{60.0, 1.0, 0.0}};
  try {
    validate(o, 100.0);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("SensorOutput::sinusoids[].frequency_hz"),
              std::string::npos);
  }
  o = {};
  o.moving_average_samples = 0;
  EXPECT_THROW(validate(o, 100.0), UsageError);
}

TEST(SensorOutput, DropoutsLeaveGapsAndKeepTheOtherSamplesAsTheyWere) {
  Recording rec;
  rec.sample_rate_hz = 10.0;
  for (int k = 0; k < 100; ++k) {
    rec.time_s.push_back(k / 10.0);
    rec.rate_deg_h.push_back(k);
    rec.temperature_c.push_back(-k);
  }
  SensorOutput o;
  // 2.0 <= t < 2.5 and 2.3 <= t < 3.0 merge (samples 20-29); 9.85 s on
  // shortens the record (sample 99); 5.01 s for 0.01 s holds no sample time
  o.dropouts = {{2.3, 0.7}, {2.0, 0.5}, {9.85, 1.0}, {5.01, 0.01}};
  const std::vector<Gap> gaps = remove_dropouts(rec, o);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].before_sample, 20);
  EXPECT_EQ(gaps[0].missing_samples, 10);
  ASSERT_EQ(rec.rate_deg_h.size(), 89u);  // 10 in the gap, 1 at the end
  EXPECT_EQ(rec.time_s.back(), 9.8);
  EXPECT_EQ(rec.rate_deg_h[19], 19.0);
  EXPECT_EQ(rec.rate_deg_h[20], 30.0);
  EXPECT_EQ(rec.time_s[20], 3.0);
  EXPECT_EQ(rec.temperature_c[20], -30.0);
  EXPECT_EQ(dropout_gaps(o, 10.0, 100).size(), 1u);
  o.dropouts = {{0.0, 100.0}};
  EXPECT_THROW(remove_dropouts(rec, o), UsageError);
  o.dropouts = {{1.0, 0.0}};
  EXPECT_THROW(validate(o, 10.0), UsageError);
}

TEST(SensorOutput, StampJitterIsUniformPerSampleAndTheSameInAnyBlocks) {
  const double fs = 100.0;
  const double jitter_s = 0.003;
  SensorOutput o;
  o.time_jitter_s = jitter_s;
  constexpr std::size_t n = 100000;
  std::vector<double> t(n);
  for (std::size_t k = 0; k < n; ++k) t[k] = static_cast<double>(k) / fs;
  std::vector<double> whole = t;
  jitter_times(whole, 0, o, fs, 7, 2);
  double sum_squares = 0.0;
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = whole[k] - t[k];
    sum_squares += u * u;
    largest = std::max(largest, std::abs(u));
  }
  // uniform on +-j: rms j / sqrt(3), within 4 standard errors (sd of u^2: j^2 * 0.298)
  const double rms = std::sqrt(sum_squares / n);
  EXPECT_NEAR(rms * rms / (jitter_s * jitter_s / 3.0), 1.0, 4.0 * 0.298 * 3.0 / std::sqrt(n));
  EXPECT_LE(largest, jitter_s);
  EXPECT_GT(largest, 0.999 * jitter_s);
  // the draws are a function of the sample index: the record in two blocks is the same
  std::vector<double> blocks = t;
  jitter_times(std::span<double>(blocks).first(40000), 0, o, fs, 7, 2);
  jitter_times(std::span<double>(blocks).subspan(40000), 40000, o, fs, 7, 2);
  EXPECT_EQ(blocks, whole);
  // another stream draws otherwise; no jitter leaves the times exact
  std::vector<double> other = t;
  jitter_times(other, 0, o, fs, 7, 3);
  EXPECT_NE(other, whole);
  std::vector<double> exact = t;
  jitter_times(exact, 0, SensorOutput{}, fs, 7, 2);
  EXPECT_EQ(exact, t);
  // 0.4 of a step or more is refused, naming the field
  o.time_jitter_s = 0.004;
  EXPECT_THROW(validate(o, fs), UsageError);
}

}  // namespace
}  // namespace foglab::sim
