// Two analyses of one gyro compared: the verdicts the lab-2 report states.
#include "foglab/model/run_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "foglab/sim/generator.h"

namespace foglab::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(RunComparison, IntervalsThatOverlapMeanUnchanged) {
  const ValueChange moved = compare_values(1.0, 0.9, 1.1, 1.5, 1.3, 1.7);
  EXPECT_EQ(moved.verdict, Change::changed);
  EXPECT_DOUBLE_EQ(moved.relative, 0.5);
  EXPECT_EQ(compare_values(1.0, 0.9, 1.1, 1.15, 1.1, 1.2).verdict, Change::unchanged);  // touch
  EXPECT_EQ(compare_values(1.0, 0.9, 1.1, 1.5, kNaN, 1.7).verdict, Change::not_comparable);
  EXPECT_EQ(to_string(Change::not_comparable), "not_comparable");
}

TEST(RunComparison, IntervalOfTheAdevAtTheNearestTau) {
  stats::AllanResult a;
  a.tau_s = {1.0, 2.0, 4.0};
  a.ci95_low = {0.5, 0.4, 0.3};
  a.ci95_high = {1.5, 1.4, 1.3};
  EXPECT_EQ(adev_interval_at(a, 2.7), std::make_pair(0.4, 1.4));  // ln 2.7/2 < ln 4/2.7
  EXPECT_EQ(adev_interval_at(a, 100.0), std::make_pair(0.3, 1.3));
  a.ci95_low.clear();
  EXPECT_TRUE(std::isnan(adev_interval_at(a, 2.0).first));
}

AnalysisResult analysed(const sim::ErrorModel& m, const char* temperature, std::uint64_t stream) {
  sim::GeneratorOptions o;
  o.sample_rate_hz = 10.0;
  o.duration_s = 2.0 * 3600.0;
  o.seed = 41;
  o.stream = stream;
  sim::Recording rec = sim::generate(m, sim::parse_temperature(temperature), o);
  return analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
}

// The same gyro at constant temperature and under a 10 degC ramp with a
// strong linear law: the polynomial takes the ramp, and the random error is
// the same (the verdicts are statistical; 95 % intervals of two independent
// runs of one N overlap with probability well above 99 %).
TEST(RunComparison, ARampThatOnlyMovesTheBiasChangesNothingRandom) {
  sim::ErrorModel m;
  m.noise = {.N = 0.5, .B = 0.05};
  m.bias = 3.0;
  m.temp_coefs = {2.0};  // deg/h per degC: 20 deg/h over the ramp
  const AnalysisResult constant = analysed(m, "const:25", 1);
  const AnalysisResult ramp = analysed(m, "ramp:10@20", 2);
  const RunComparison c = compare_runs(constant, ramp);
  ASSERT_TRUE(c.systematic.has_value());
  EXPECT_GE(c.systematic->degree_after, 1);
  EXPECT_NEAR(c.systematic->polynomial_range_deg_h, 20.0, 1.0);
  EXPECT_NEAR(c.systematic->span_after_c, 10.0, 0.1);
  // the bias at each run's mean temperature (25 degC both), not the lab's
  // polyfit constant (the bias extrapolated to 0 degC: -47 deg/h)
  EXPECT_NEAR(c.systematic->bias_before_deg_h, 3.0, 0.5);
  EXPECT_NEAR(c.systematic->bias_after_deg_h, 3.0, 0.5);
  EXPECT_DOUBLE_EQ(c.systematic->bias_difference_deg_h,
                   std::abs(c.systematic->bias_after_deg_h - c.systematic->bias_before_deg_h));
  EXPECT_GT(c.systematic->wander_deg_h, 0.0);
  ASSERT_TRUE(c.white_noise.has_value());
  EXPECT_EQ(c.white_noise->verdict, Change::unchanged);
  EXPECT_NEAR(c.white_noise->relative, 0.0, 0.05);
  EXPECT_EQ(c.process_before, c.process_after);
  EXPECT_EQ(c.class_before, c.class_after);
  EXPECT_TRUE(c.changed.empty());
}

// A gyro whose white noise doubles during the second run: the one change.
TEST(RunComparison, DoubledWhiteNoiseIsTheChangeReported) {
  sim::ErrorModel quiet;
  quiet.noise = {.N = 0.5, .B = 0.05};
  sim::ErrorModel loud = quiet;
  loud.noise.N = 1.0;
  const RunComparison c =
      compare_runs(analysed(quiet, "const:25", 3), analysed(loud, "const:25", 4));
  ASSERT_TRUE(c.white_noise.has_value());
  EXPECT_EQ(c.white_noise->verdict, Change::changed);
  EXPECT_NEAR(c.white_noise->relative, 1.0, 0.1);
  ASSERT_FALSE(c.changed.empty());
  EXPECT_EQ(c.changed.front(), ChangedItem::white_noise);
}

}  // namespace
}  // namespace foglab::model
