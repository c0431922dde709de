// The lab's graphical readings on generated records of known truth.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/model/readings.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/lab2_variants.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/psd.h"

namespace foglab::model {
namespace {

struct Curves {
  stats::AllanResult adev;
  stats::PsdResult psd;
};

Curves curves(const sim::ErrorModel& m, double fs_hz, double hours, std::uint64_t seed) {
  sim::GeneratorOptions o;
  o.sample_rate_hz = fs_hz;
  o.duration_s = hours * 3600.0;
  o.seed = seed;
  const sim::Recording r = sim::generate(m, sim::TemperatureProfile{}, o);
  stats::AllanOptions a;
  a.confidence = false;
  return {stats::allan_deviation(r.rate_deg_h, fs_hz, InputKind::rate, a),
          stats::log_smooth(stats::welch_psd(r.rate_deg_h, fs_hz), 10.0)};
}

TEST(Readings, WhiteNoiseGivesNAtOneSecondAndNoRandomWalk) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    sim::ErrorModel m;
    m.noise.N = 0.3;
    const Curves c = curves(m, 100.0, 2.0, seed);
    const AdevReadings a = read_adev(c.adev.tau_s, c.adev.dev);
    ASSERT_TRUE(a.N.has_value());
    EXPECT_NEAR(*a.N / 0.3, 1.0, 0.03) << seed;
    EXPECT_FALSE(a.K.has_value()) << seed << " K " << a.K.value_or(0);
    const PsdReadings p = read_psd(c.psd.frequency_hz, c.psd.psd);
    ASSERT_TRUE(p.N.has_value());
    EXPECT_NEAR(*p.N / 0.3, 1.0, 0.05) << seed;
    EXPECT_FALSE(p.K.has_value()) << seed;
  }
}

TEST(Readings, WienerProcessGivesKAtThreeSecondsAndOnThePsdAtOneHertz) {
  for (const std::uint64_t seed : {4, 5, 6}) {
    sim::ErrorModel m;
    m.noise.N = 0.3;
    m.noise.K = 0.05;
    const Curves c = curves(m, 10.0, 6.0, seed);
    const AdevReadings a = read_adev(c.adev.tau_s, c.adev.dev);
    ASSERT_TRUE(a.N.has_value() && a.K.has_value()) << seed;
    EXPECT_NEAR(*a.N / 0.3, 1.0, 0.05) << seed;
    EXPECT_NEAR(*a.K / 0.05, 1.0, 0.3) << seed;
    EXPECT_FALSE(a.minimum_at_edge);
    // The minimum lies where the two lines cross, near tau = sqrt(3) N/K.
    EXPECT_GT(a.bias_instability_tau_s, 3.0);
    EXPECT_LT(a.bias_instability_tau_s, 40.0);
    const PsdReadings p = read_psd(c.psd.frequency_hz, c.psd.psd);
    ASSERT_TRUE(p.K.has_value()) << seed;
    EXPECT_NEAR(*p.K / 0.05, 1.0, 0.3) << seed;
  }
}

TEST(Readings, BiasInstabilityIsTheMinimumOfTheDeviation) {
  sim::ErrorModel m;
  m.noise.N = 0.05;
  m.noise.B = 0.1;
  m.noise.K = 0.002;
  const Curves c = curves(m, 10.0, 8.0, 7);
  const AdevReadings a = read_adev(c.adev.tau_s, c.adev.dev);
  const double theory = adev_minimum(m.noise, c.adev.tau_s.front(), c.adev.tau_s.back()).adev_deg_h;
  EXPECT_NEAR(a.bias_instability_deg_h / theory, 1.0, 0.1);
  EXPECT_NEAR(a.bias_instability_deg_h / (0.6643 * m.noise.B), 1.0, 0.25);
}

TEST(Readings, TheMinimumIsReadFromTheFilterMemorysEndOn) {
  // A filtered first tau under the floor (0.07 at 1 s), the floor 0.105 at 32 s.
  const std::vector<double> tau = {1, 2, 4, 8, 16, 32, 64, 128};
  const std::vector<double> dev = {0.07, 0.104, 0.122, 0.115, 0.107, 0.105, 0.12, 0.15};
  const AdevReadings all = read_adev(tau, dev);
  EXPECT_EQ(all.bias_instability_tau_s, 1.0);
  EXPECT_TRUE(all.minimum_at_edge);
  EXPECT_TRUE(std::isnan(all.lower_inside_filter_deg_h));

  const AdevReadings beyond = read_adev(tau, dev, 6.0);  // the memory ends at 6 s
  EXPECT_EQ(beyond.bias_instability_deg_h, 0.105);
  EXPECT_EQ(beyond.bias_instability_tau_s, 32.0);
  EXPECT_FALSE(beyond.minimum_at_edge);
  EXPECT_EQ(beyond.lower_inside_filter_deg_h, 0.07);
  EXPECT_EQ(beyond.lower_inside_filter_tau_s, 1.0);
  EXPECT_EQ(beyond.from_tau_s, 6.0);
  EXPECT_TRUE(minimum_inside_filter_note(all).empty());
  EXPECT_EQ(minimum_inside_filter_note(beyond).text(),
            "the Allan deviation is lower inside the output filter's memory (0.07 deg/h at 1 s; "
            "the memory ends near 6 s), where the filter, not the gyro's noise, lowers it: the "
            "bias instability is read beyond it, 0.105 deg/h at 32 s");

  // a tau at the memory's end itself (to rounding) is read
  const std::vector<double> rising = {0.2, 0.09, 0.1, 0.11, 0.12, 0.13, 0.14, 0.15};
  const AdevReadings at = read_adev(tau, rising, 4.0 * (1.0 + 1e-12));
  EXPECT_EQ(at.bias_instability_tau_s, 4.0);
  EXPECT_TRUE(at.minimum_at_edge);  // the first tau read
  EXPECT_EQ(at.lower_inside_filter_tau_s, 2.0);

  // a memory longer than every tau: the whole range, as without one
  const AdevReadings longer = read_adev(tau, dev, 1000.0);
  EXPECT_EQ(longer.bias_instability_tau_s, 1.0);
  EXPECT_TRUE(std::isnan(longer.lower_inside_filter_deg_h));
  EXPECT_EQ(longer.from_tau_s, 0.0);
}

TEST(Readings, BadCurvesAreUsageErrors) {
  const std::vector<double> one = {1.0}, two = {1.0, 2.0};
  EXPECT_THROW(read_adev(one, one), UsageError);
  EXPECT_THROW(read_psd(two, one), UsageError);
  const std::vector<double> flat_tau = {1, 2, 4, 8}, rising = {1, 2, 4, 8};
  const AdevReadings r = read_adev(flat_tau, rising);  // slope +1: a ramp, no N, no K
  EXPECT_FALSE(r.N.has_value());
  EXPECT_FALSE(r.K.has_value());
  EXPECT_TRUE(r.minimum_at_edge);
}

}  // namespace
}  // namespace foglab::model
