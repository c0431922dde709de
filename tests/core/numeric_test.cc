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
