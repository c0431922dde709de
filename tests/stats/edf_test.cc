// Greenhall's EDF against independent closed forms, and the chi-square
// intervals against their definition.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "foglab/stats/confidence.h"
#include "foglab/stats/edf.h"

namespace foglab::stats {
namespace {

// NIST SP 1065 Table 5 (simple approximations, white FM, overlapping ADEV).
double sp1065_white_fm_edf(double n, double m) {
  return (3.0 * (n - 1.0) / (2.0 * m) - 2.0 * (n - 2.0) / n) * (4.0 * m * m) / (4.0 * m * m + 5.0);
}

TEST(GreenhallEdf, AgreesWithSp1065SimpleFormulaForWhiteFmAtLongTau) {
  // The simple formula is an approximation; at short tau Greenhall's
  // algorithm (and Stable32, see allan_reference_test) differs by up to 17 %
  // because it models the phase as averaged over tau0. At m >= 32 they agree.
  for (const std::int64_t m : {32, 64, 128, 256, 1024}) {
    const double greenhall = greenhall_edf(0, m, 10001);
    EXPECT_NEAR(greenhall / sp1065_white_fm_edf(10001, m), 1.0, 0.03) << "m " << m;
  }
}

TEST(GreenhallEdf, UnitFactorIsTheSameOverlappedOrNot) {
  // At m = 1 the overlapping and non-overlapping estimators are one estimator.
  for (const int alpha : {2, 1, 0, -1, -2}) {
    EXPECT_DOUBLE_EQ(greenhall_edf(alpha, 1, 1001, {.stride = Stride::non_overlapping}),
                     greenhall_edf(alpha, 1, 1001))
        << "alpha " << alpha;
  }
}

TEST(GreenhallEdf, OverlappingEstimatesHaveMoreDegreesOfFreedom) {
  for (const int alpha : {2, 1, 0, -1, -2}) {
    for (const std::int64_t m : {2, 8, 32}) {
      EXPECT_GT(greenhall_edf(alpha, m, 4097),
                greenhall_edf(alpha, m, 4097, {.stride = Stride::non_overlapping}))
          << "alpha " << alpha << " m " << m;
      // Fewer degrees of freedom at longer tau.
      EXPECT_GT(greenhall_edf(alpha, m, 4097), greenhall_edf(alpha, 2 * m, 4097));
    }
  }
}

TEST(GreenhallEdf, AsymptoticTablesJoinTheExactSum) {
  // Just below and above J = 100 the exact and tabulated branches must agree.
  for (const int alpha : {0, -1, -2}) {
    const double exact = greenhall_edf(alpha, 33, 100001);  // J = 99
    const double table = greenhall_edf(alpha, 34, 100001);  // J = 102
    EXPECT_NEAR(table / exact, 33.0 / 34.0, 0.05) << "alpha " << alpha;
  }
  const double exact_mod = greenhall_edf(0, 33, 100001, {.filter = Filter::modified});
  const double table_mod = greenhall_edf(0, 34, 100001, {.filter = Filter::modified});
  EXPECT_NEAR(table_mod / exact_mod, 33.0 / 34.0, 0.05);
}

TEST(GreenhallEdf, OutsideTheDomainIsNaN) {
  EXPECT_TRUE(std::isnan(greenhall_edf(-3, 4, 1000)));   // alpha + 2d <= 1
  EXPECT_TRUE(std::isnan(greenhall_edf(0, 600, 1000)));  // no terms
  EXPECT_FALSE(std::isnan(greenhall_edf(-4, 4, 1000, {.order = 3})));
}

TEST(TotdevEdf, IsSp1065Table12) {
  EXPECT_DOUBLE_EQ(totdev_edf(0, 10, 1001), 1.5 * 100.1);
  EXPECT_DOUBLE_EQ(totdev_edf(-1, 10, 1001), 1.17 * 100.1 - 0.22);
  EXPECT_DOUBLE_EQ(totdev_edf(-2, 10, 1001), 0.93 * 100.1 - 0.36);
}

TEST(ChiSquareInterval, BoundsSolveTheChiSquareQuantileEquations) {
  const double dev = 2.0, edf = 17.5;
  const Interval i = chi2_interval(dev, edf, 0.95);
  const boost::math::chi_squared_distribution<double> chi2(edf);
  EXPECT_NEAR(boost::math::cdf(chi2, edf * dev * dev / (i.low * i.low)), 0.975, 1e-12);
  EXPECT_NEAR(boost::math::cdf(chi2, edf * dev * dev / (i.high * i.high)), 0.025, 1e-12);
  EXPECT_LT(i.low, dev);
  EXPECT_GT(i.high, dev);
  const Interval narrow = chi2_interval(dev, edf, kConfidence68);
  EXPECT_GT(narrow.low, i.low);
  EXPECT_LT(narrow.high, i.high);
  EXPECT_TRUE(std::isnan(chi2_interval(dev, 0.0, 0.95).low));
  EXPECT_TRUE(std::isnan(chi2_interval(dev, std::nan(""), 0.95).high));
}

}  // namespace
}  // namespace foglab::stats
