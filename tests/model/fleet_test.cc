// The fleet's statistics: robust centre and spread on log10, and the units that stand out,
// on fleets drawn from a known lognormal spread with planted outliers.
#include "foglab/model/fleet.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "foglab/core/error.h"

namespace foglab::model {
namespace {

using ::testing::HasSubstr;

// A fleet of `n` units whose N is lognormal about `median` with a sigma of `sigma_log10` in
// log10; the units named in `planted` get N times `factor`.
std::vector<FleetUnit> lognormal_fleet(std::size_t n, double median, double sigma_log10,
                                       std::uint64_t seed, const std::vector<std::size_t>& planted,
                                       double factor) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma_log10);
  std::vector<FleetUnit> units(n);
  for (std::size_t k = 0; k < n; ++k) {
    units[k].name = "unit" + std::to_string(k);
    units[k].values["N"] = median * std::pow(10.0, normal(rng));
    units[k].values["K"] = NAN;  // not resolved anywhere
    units[k].accuracy_class = k % 4 == 0 ? "intermediate" : "tactical";
  }
  for (const std::size_t k : planted) units[k].values["N"] *= factor;
  return units;
}

TEST(Fleet, PlantedOutliersAreFoundAndFalseAlarmsAreRare) {
  // 20 fleets of 200 with three units at 3x (0.48 in log10: 9.5 sigma of the fleet's 0.05).
  // The rule's false-alarm rate is about 5e-4 a unit: 2 expected in 4000 units.
  const std::vector<std::size_t> planted = {17, 88, 150};
  std::size_t false_alarms = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const FleetSummary s =
        summarize_fleet(lognormal_fleet(200, 5.0, 0.05, seed, planted, 3.0), {"N", "K"});
    std::vector<std::string> found;
    for (const FleetOutlier& o : s.outliers) {
      EXPECT_EQ(o.parameter, "N");
      found.push_back(o.unit);
      if (o.unit == "unit17" || o.unit == "unit88" || o.unit == "unit150") {
        EXPECT_GT(o.modified_z, 3.5);
        // 3 times the unit's own draw: within 4 of the fleet's sigmas (0.05 in log10) of 3.
        EXPECT_NEAR(std::log10(o.times_median / 3.0), 0.0, 4 * 0.05);
      } else {
        ++false_alarms;
      }
    }
    for (const char* name : {"unit17", "unit88", "unit150"}) {
      EXPECT_NE(std::find(found.begin(), found.end(), name), found.end())
          << name << " not found, seed " << seed;
    }
  }
  EXPECT_LE(false_alarms, 10u);  // Poisson(2): P(> 10) < 1e-5
}

TEST(Fleet, AUnitStandsOutOnlyWhenItsWholeIntervalIsBeyondTheLimit) {
  // Estimates with their own errors, as a fit gives them: most units' are small (0.03 in
  // log10), every fifth unit's large (0.3: a flicker coefficient from a short record), each
  // with the 95 % interval that goes with it. The estimates of the fleet then have heavy
  // tails that a robust spread cannot follow. The planted three are 30x.
  const std::vector<std::size_t> planted = {6, 61, 121};
  std::mt19937_64 rng(9);
  std::normal_distribution<double> standard(0.0, 1.0);
  std::size_t false_alarms = 0, flagged_without_intervals = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::vector<FleetUnit> units = lognormal_fleet(200, 5.0, 0.05, seed, planted, 30.0);
    for (std::size_t k = 0; k < units.size(); ++k) {
      const double sd = k % 5 == 0 ? 0.3 : 0.03;
      const double estimate = units[k].values["N"] * std::pow(10.0, sd * standard(rng));
      units[k].values["N"] = estimate;
      units[k].ci95["N"] = {estimate / std::pow(10.0, 1.96 * sd),
                            estimate * std::pow(10.0, 1.96 * sd)};
    }
    std::vector<FleetUnit> bare = units;
    for (FleetUnit& u : bare) u.ci95.clear();
    flagged_without_intervals += summarize_fleet(bare, {"N"}).outliers.size() - 3;
    const FleetSummary s = summarize_fleet(units, {"N"});
    std::size_t found = 0;
    for (const FleetOutlier& o : s.outliers) {
      if (o.unit == "unit6" || o.unit == "unit61" || o.unit == "unit121") {
        ++found;
      } else {
        ++false_alarms;
      }
    }
    EXPECT_EQ(found, 3u) << "seed " << seed;
  }
  // About 17 false alarms a fleet without the intervals (the wide units beyond 3.5 robust
  // sigmas of the rest); with them a wide unit must stray by 2.7 of its own sigmas
  // (P = 0.006): about 5 in the 20 fleets' 800 wide units.
  EXPECT_GT(flagged_without_intervals, 20u * 8u);
  EXPECT_LE(false_alarms, 15u);
  // An interval open towards the fleet (NaN end) never stands out.
  std::vector<FleetUnit> units = lognormal_fleet(50, 5.0, 0.05, 3, {7}, 10.0);
  units[7].ci95["N"] = {NAN, 100.0};
  EXPECT_TRUE(summarize_fleet(units, {"N"}).outliers.empty());
}

TEST(Fleet, CentreAndSpreadMatchTheDrawingDistribution) {
  // Over 20 fleets of 200, the median and the robust sigma of log10 against the truth: the
  // median's standard error is 1.2533 sigma / sqrt(n) (0.0044 in log10 here), the MAD's
  // sigma estimate has a relative standard error of about 1.17 / sqrt(n) (8 %).
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const FleetSummary s = summarize_fleet(lognormal_fleet(200, 5.0, 0.05, seed, {}, 1.0), {"N"});
    ASSERT_EQ(s.parameters.size(), 1u);
    const ParameterSpread& p = s.parameters[0];
    EXPECT_EQ(p.units, 200u);
    EXPECT_NEAR(std::log10(p.median / 5.0), 0.0, 4 * 0.0044) << "seed " << seed;
    EXPECT_NEAR(p.spread_log10 / 0.05, 1.0, 4 * 0.083) << "seed " << seed;
    EXPECT_NEAR(p.spread_factor, std::pow(10.0, p.spread_log10), 1e-12);
    EXPECT_LT(p.minimum, p.p05);
    EXPECT_LT(p.p05, p.median);
    EXPECT_LT(p.median, p.p95);
    EXPECT_LT(p.p95, p.maximum);
  }
}

TEST(Fleet, OutliersDoNotWidenTheSpread) {
  // Ten units at 100x move the robust spread by little; a standard deviation would triple.
  const FleetSummary clean = summarize_fleet(lognormal_fleet(200, 5.0, 0.05, 3, {}, 1.0), {"N"});
  std::vector<std::size_t> planted;
  for (std::size_t k = 0; k < 10; ++k) planted.push_back(20 * k);
  const FleetSummary dirty =
      summarize_fleet(lognormal_fleet(200, 5.0, 0.05, 3, planted, 100.0), {"N"});
  EXPECT_NEAR(dirty.parameters[0].spread_log10 / clean.parameters[0].spread_log10, 1.0, 0.15);
  EXPECT_EQ(dirty.outliers.size(), 10u);
}

TEST(Fleet, UnresolvedValuesCountNowhereAndClassesAreCounted) {
  const FleetSummary s = summarize_fleet(lognormal_fleet(8, 5.0, 0.05, 1, {}, 1.0), {"N", "K"});
  EXPECT_EQ(s.units, 8u);
  EXPECT_EQ(s.parameters[0].units, 8u);
  EXPECT_EQ(s.parameters[1].units, 0u);
  EXPECT_TRUE(std::isnan(s.parameters[1].median));
  EXPECT_EQ(s.classes.at("intermediate"), 2u);
  EXPECT_EQ(s.classes.at("tactical"), 6u);

  // Half the units equal: MAD 0, nothing flagged; one value only: its median, no spread.
  std::vector<FleetUnit> same(6);
  for (std::size_t k = 0; k < 6; ++k) {
    same[k].name = "u" + std::to_string(k);
    same[k].values["N"] = k < 4 ? 2.0 : 50.0;
    same[k].values["B"] = k == 0 ? 0.3 : -1.0;
  }
  const FleetSummary t = summarize_fleet(same, {"N", "B"});
  EXPECT_TRUE(t.outliers.empty());
  EXPECT_EQ(t.parameters[0].median, 2.0);
  EXPECT_EQ(t.parameters[0].spread_log10, 0.0);
  EXPECT_EQ(t.parameters[1].units, 1u);
  EXPECT_EQ(t.parameters[1].median, 0.3);
  EXPECT_TRUE(std::isnan(t.parameters[1].spread_log10));
}

TEST(Fleet, BadThresholdIsAUsageError) {
  FleetOptions o;
  o.outlier_z = 0.0;
  try {
    summarize_fleet({}, {"N"}, o);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr("outlier_z"));
  }
}

}  // namespace
}  // namespace foglab::model
