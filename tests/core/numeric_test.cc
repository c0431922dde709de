#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

#include "foglab/core/numeric.h"

namespace foglab {
namespace {

TEST(CompensatedSum, KeepsSmallTermsNextToLargeOnes) {
  // 1e16 + 1 + 1 + ... - 1e16: a plain double sum loses every 1.
  CompensatedSum s;
  s.add(1e16);
  for (int i = 0; i < 1000; ++i) s.add(1.0);
  s.add(-1e16);
  EXPECT_DOUBLE_EQ(s.value(), 1000.0);
}

TEST(CompensatedMean, IsExactForAMillionLargeEqualValuesPlusNoiseFreePattern) {
  std::vector<double> v(1 << 20);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 1e6 + (i % 2 == 0 ? 1e-3 : -1e-3);
  EXPECT_NEAR(compensated_mean(v) - 1e6, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(compensated_mean(std::vector<double>{}), 0.0);
}

TEST(CompensatedSum, IsIndependentOfTheNumberOfThreads) {
  std::vector<double> v(300000);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 1.0 / static_cast<double>(i + 1);
  omp_set_num_threads(1);
  const double one = compensated_sum(v);
  omp_set_num_threads(2);
  const double two = compensated_sum(v);
  EXPECT_EQ(one, two);
  EXPECT_GE(worker_threads(), 1);
}

}  // namespace
}  // namespace foglab

namespace foglab {
namespace {

TEST(RobustSpread, MedianAndScaledMadIgnoreAFewOutliers) {
  std::vector<double> odd = {5.0, 1.0, 4.0, 2.0, 3.0};
  EXPECT_EQ(median_in_place(odd), 3.0);
  std::vector<double> even = {4.0, 1.0, 3.0, 2.0};
  EXPECT_EQ(median_in_place(even), 3.0);  // the upper middle
  // 1..9 with one wild value: median 5, deviations 0,1,1,2,2,3,3,4,1e6-5 -> MAD 2.
  const std::vector<double> v = {1, 2, 3, 4, 5, 6, 7, 8, 1e6};
  const RobustSpread r = robust_spread(v);
  EXPECT_EQ(r.centre, 5.0);
  EXPECT_DOUBLE_EQ(r.spread, 1.4826 * 2.0);
  EXPECT_EQ(robust_spread(std::vector<double>{2, 2, 2, 7}).spread, 0.0);
}

}  // namespace
}  // namespace foglab
