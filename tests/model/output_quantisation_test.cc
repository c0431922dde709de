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

std::vector<double> rounded(std::vector<double> y, double lsb) {
  for (double& v : y) v = std::round(v / lsb) * lsb;
  return y;
}

TEST(OutputQuantisation, RoundingIsNoiseLikeUpToTwoSampleSpreads) {
  // Widrow: the rounding error of Gaussian noise of sd 1 is white and
  // uniform to within exp(-2 pi^2 / q^2); noise-like up to q = 2.
  for (const double lsb : {0.5, 1.3, 1.8}) {
    const OutputQuantisation q =
        find_output_quantisation(rounded(noise(100000, 1.0, 4), lsb), 10.0);
    ASSERT_TRUE(q.detected) << lsb;
    EXPECT_NEAR(q.step_sd_deg_h, 1.0, 0.02) << lsb;  // the rounding's q^2/12 taken out
    EXPECT_TRUE(q.noise_like) << lsb;
    // 4 exp(-2 pi^2 sd^2 / q^2) with sd within the 2 % asserted above.
    auto departure = [lsb](double sd) {
      return 4.0 * std::exp(-2.0 * M_PI * M_PI * sd * sd / (lsb * lsb));
    };
    EXPECT_GE(q.white_variance_departure, departure(1.02)) << lsb;
    EXPECT_LE(q.white_variance_departure, departure(0.98)) << lsb;
  }
  for (const double lsb : {2.5, 4.0}) {
    const OutputQuantisation q =
        find_output_quantisation(rounded(noise(100000, 1.0, 5), lsb), 10.0);
    ASSERT_TRUE(q.detected) << lsb;
    EXPECT_FALSE(q.noise_like) << lsb;
  }
}

TEST(OutputQuantisation, ADriftDoesNotMakeACoarseWordNoiseLike) {
  // White noise of sd 1 on a slow ramp over 40 LSBs: the samples' sd is
  // about 12 LSBs, but from one sample to the next the signal moves by a
  // third of one; the rounding follows the ramp, not noise.
  std::vector<double> y = noise(100000, 1.0, 6);
  for (std::size_t k = 0; k < y.size(); ++k) y[k] += 120.0 * static_cast<double>(k) / 1e5;
  const OutputQuantisation q = find_output_quantisation(rounded(y, 3.0), 10.0);
  ASSERT_TRUE(q.detected);
  EXPECT_GT(q.sample_sd_deg_h, 10.0 * 3.0);
  EXPECT_LT(q.step_sd_deg_h, 1.2);
  EXPECT_FALSE(q.noise_like);
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
