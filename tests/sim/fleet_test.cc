// sim/fleet.h: a fleet drawn about a nominal model follows its spec.
#include "foglab/sim/fleet.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "foglab/core/error.h"

namespace foglab::sim {
namespace {

using ::testing::HasSubstr;

ErrorModel nominal() {
  ErrorModel m;
  m.noise.N = 0.06;
  m.noise.B = 0.02;
  m.noise.gm_tc = 100.0;  // not scattered
  return m;
}

TEST(FleetDraw, EachCoefficientIsLogNormalAboutTheNominalWithTheSpreadAsked) {
  FleetSpec spec;
  spec.units = 20000;
  spec.spread_log10 = 0.15;
  spec.seed = 3;
  const std::vector<FleetMember> fleet = draw_fleet(nominal(), spec);
  ASSERT_EQ(fleet.size(), spec.units);
  for (const auto& [field, value] :
       {std::pair{&NoiseModel::N, 0.06}, std::pair{&NoiseModel::B, 0.02}}) {
    double sum = 0.0, sum_sq = 0.0;
    std::vector<double> logs;
    for (const FleetMember& m : fleet) logs.push_back(std::log10(m.model.noise.*field / value));
    for (const double l : logs) {
      sum += l;
      sum_sq += l * l;
    }
    const double n = static_cast<double>(logs.size());
    const double mean = sum / n, sd = std::sqrt(sum_sq / n - mean * mean);
    // 4 standard errors: sd/sqrt(n) for the mean, sd/sqrt(2n) for the sd.
    EXPECT_NEAR(mean, 0.0, 4.0 * spec.spread_log10 / std::sqrt(n));
    EXPECT_NEAR(sd, spec.spread_log10, 4.0 * spec.spread_log10 / std::sqrt(2.0 * n));
    std::sort(logs.begin(), logs.end());  // normal, not uniform: the tails are there
    EXPECT_LT(logs.front(), -3.0 * spec.spread_log10);
    EXPECT_GT(logs.back(), 3.0 * spec.spread_log10);
  }
  // N and B are drawn independently.
  double cross = 0.0;
  for (const FleetMember& m : fleet) {
    cross += std::log10(m.model.noise.N / 0.06) * std::log10(m.model.noise.B / 0.02);
  }
  const double correlation =
      cross / static_cast<double>(fleet.size()) / (spec.spread_log10 * spec.spread_log10);
  EXPECT_NEAR(correlation, 0.0, 4.0 / std::sqrt(static_cast<double>(fleet.size())));
  for (const FleetMember& m : fleet) {
    EXPECT_EQ(m.model.noise.K, 0.0);  // a term the nominal model lacks stays out
    EXPECT_EQ(m.model.noise.gm_tc, 100.0);
  }
}

TEST(FleetDraw, OutliersAreDistinctUnitsTakingTurnsOverTheTermsPresent) {
  FleetSpec spec;
  spec.units = 50;
  spec.outliers = 5;
  spec.outlier_factor = 4.0;
  spec.spread_log10 = 0.0;
  const std::vector<FleetMember> fleet = draw_fleet(nominal(), spec);
  std::multiset<std::string> terms;
  for (const FleetMember& m : fleet) {
    if (m.outlier_parameter.empty()) {
      EXPECT_EQ(m.model.noise.N, 0.06);
      EXPECT_EQ(m.model.noise.B, 0.02);
      continue;
    }
    terms.insert(m.outlier_parameter);
    const bool n = m.outlier_parameter == "N";
    EXPECT_DOUBLE_EQ(m.model.noise.N, n ? 0.24 : 0.06);
    EXPECT_DOUBLE_EQ(m.model.noise.B, n ? 0.02 : 0.08);
  }
  EXPECT_EQ(terms.count("N"), 3u);
  EXPECT_EQ(terms.count("B"), 2u);
  EXPECT_EQ(terms.count("K"), 0u);  // the nominal model has no K
}

TEST(FleetDraw, TheSameSpecGivesTheSameFleetAndAnotherSeedAnother) {
  FleetSpec spec;
  spec.units = 30;
  spec.outliers = 2;
  const auto a = draw_fleet(nominal(), spec), b = draw_fleet(nominal(), spec);
  spec.seed = 2;
  const auto c = draw_fleet(nominal(), spec);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].model.noise.N, b[k].model.noise.N);
    EXPECT_EQ(a[k].outlier_parameter, b[k].outlier_parameter);
  }
  EXPECT_NE(a[0].model.noise.N, c[0].model.noise.N);
}

TEST(FleetDraw, ASpecOutOfRangeIsAUsageError) {
  FleetSpec spec;
  EXPECT_THROW(draw_fleet(nominal(), spec), UsageError);  // no units
  spec.units = 10;
  spec.outliers = 2;
  EXPECT_THROW(draw_fleet(nominal(), spec), UsageError);
  spec.outliers = 1;
  spec.outlier_factor = 1.0;
  EXPECT_THROW(draw_fleet(nominal(), spec), UsageError);
  spec.outlier_factor = 5.0;
  spec.spread_log10 = -0.1;
  EXPECT_THROW(draw_fleet(nominal(), spec), UsageError);
  spec.spread_log10 = 0.1;
  ErrorModel none;
  none.noise.R = 1.0;
  try {
    draw_fleet(none, spec);
    FAIL() << "no N, B, K";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr("none of N, B, K"));
  }
}

}  // namespace
}  // namespace foglab::sim
