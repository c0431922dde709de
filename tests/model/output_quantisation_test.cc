// The output word's LSB found from the samples (model/output_quantisation.h).
#include "foglab/model/output_quantisation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/noise.h"

namespace foglab::model {
namespace {

std::vector<double> noise(std::size_t n, double sd, std::uint64_t seed) {
  return test::mt_normal(n, seed, 3.7, sd);
}

TEST(OutputQuantisation, FindsTheLsbThroughAUnitConversion) {
  // A word of 0.05 deg/s LSB, read in deg/s and converted to deg/h (the
  // ADIS16405's): 0.05 * 3600 = 180 deg/h, the products uneven in the last bits.
  std::vector<double> y = noise(50000, 0.3, 1);  // [deg/s]
  for (double& v : y) v = std::round(v / 0.05) * 0.05 * 3600.0;
  const OutputQuantisation q = find_output_quantisation(y, 100.0);
  ASSERT_TRUE(q.detected);
  EXPECT_NEAR(q.lsb_deg_h, 180.0, 1e-6);
  EXPECT_NEAR(q.white_level_deg_h_sqrt_hz, 180.0 / std::sqrt(12.0 * 100.0), 1e-6);
  EXPECT_LT(q.lsb_deg_h, q.sample_sd_deg_h);
}

TEST(OutputQuantisation, NoneInUnroundedNoiseOrWithMissingCodes) {
  EXPECT_FALSE(find_output_quantisation(noise(50000, 1.0, 2), 10.0).detected);
  // Rounded to 0.1, but a tenth of the samples off the grid: not a word.
  std::vector<double> y = noise(50000, 1.0, 3);
  for (std::size_t k = 0; k < y.size(); ++k) {
    if (k % 10 != 0) y[k] = std::round(y[k] / 0.1) * 0.1;
  }
  EXPECT_FALSE(find_output_quantisation(y, 10.0).detected);
}

}  // namespace
}  // namespace foglab::model
