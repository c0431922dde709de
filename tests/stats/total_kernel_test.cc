// The fast sums of the total and Theo family against their direct
// definitions, on the three phase-noise shapes that stress cancellation
// (white PM, white FM, random-walk FM) with a large offset and slope added.
#include "../../src/stats/total_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "../../src/stats/theo1_kernel.h"
#include "foglab/core/error.h"
#include "support/noise.h"

namespace foglab::stats::detail {
namespace {

struct Shape {
  std::string name;
  std::vector<double> x;
};

// Phase records of n points: white PM, its integral (white FM) and double
// integral (random-walk FM), each with an offset of 1e6 and a slope of 1e2
// per sample, which every term of these statistics cancels.
std::vector<Shape> shapes(std::size_t n, std::uint64_t seed) {
  const std::vector<double> w = test::white(n, seed, 1.0);
  std::vector<double> wfm(n), rwfm(n);
  double a = 0.0, b = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    a += w[i];
    b += a;
    wfm[i] = a;
    rwfm[i] = b;
  }
  std::vector<Shape> out = {{"white PM", w}, {"white FM", wfm}, {"random-walk FM", rwfm}};
  for (Shape& s : out) {
    for (std::size_t i = 0; i < n; ++i) s.x[i] += 1e6 + 1e2 * static_cast<double>(i);
  }
  return out;
}

TEST(Theo1Kernel, BlockedFftSumsEqualTheDirectSums) {
  // Factors on both sides of the direct/FFT switch, odd halves (m/2 = 33),
  // and factors close to N, where only a few positions remain.
  constexpr std::size_t kN = 5001;
  const std::vector<std::int64_t> factors = {2, 10, 66, 130, 400, 1000, 2500, 4000, 4998, 5000};
  for (const Shape& s : shapes(kN, 71)) {
    for (const std::int64_t m : factors) {
      const double direct = theo1_sum_direct(s.x, m);
      EXPECT_NEAR(theo1_sum_blocked(s.x, m) / direct, 1.0, 1e-9) << s.name << " m " << m;
    }
    const std::vector<double> chosen = theo1_sums(s.x, factors);
    for (std::size_t k = 0; k < factors.size(); ++k) {
      EXPECT_NEAR(chosen[k] / theo1_sum_direct(s.x, factors[k]), 1.0, 1e-9)
          << s.name << " m " << factors[k];
    }
  }
}

TEST(TotalKernel, BlockedSumsEqualTheDirectSums) {
  // Odd and even 3m (the half-mean slope differs), factors on both sides of
  // the direct/blocked switch (m <= 5), and up to L/3 where one subsequence
  // remains; on phase-like and rate-like records alike.
  constexpr std::size_t kL = 6001;
  const std::vector<std::int64_t> factors = {1, 2, 3, 5, 7, 8, 16, 33, 100, 1999, 2000};
  for (const Shape& s : shapes(kL, 72)) {
    for (const std::int64_t m : factors) {
      const double direct = total_modified_sum_direct(s.x, m);
      EXPECT_NEAR(total_modified_sum_blocked(s.x, m) / direct, 1.0, 1e-9) << s.name << " m " << m;
      EXPECT_NEAR(total_modified_sum(s.x, m) / direct, 1.0, 1e-9) << s.name << " m " << m;
    }
  }
}

TEST(TotalKernel, TheDirectSumIsTheDefinitionTermByTerm) {
  // The definition written out (reflected 9m-point copy, window sums by
  // hand) on a short record, against the reference used above.
  const std::vector<double> z = test::white(40, 73, 1.0);
  for (std::int64_t m = 1; m <= 13; ++m) {
    double total = 0.0;
    const std::int64_t n3 = 3 * m;
    for (std::size_t i = 0; i + n3 <= z.size(); ++i) {
      const std::int64_t h1 = n3 / 2, h2 = (n3 + 1) / 2;
      double mean1 = 0.0, mean2 = 0.0;
      for (std::int64_t k = 0; k < h1; ++k) mean1 += z[i + k] / static_cast<double>(h1);
      for (std::int64_t k = h2; k < n3; ++k) mean2 += z[i + k] / static_cast<double>(n3 - h2);
      const double slope = (mean2 - mean1) / static_cast<double>(h2);
      std::vector<double> x(static_cast<std::size_t>(n3)), star;
      for (std::int64_t k = 0; k < n3; ++k) x[k] = z[i + k] - slope * static_cast<double>(k);
      star.insert(star.end(), x.rbegin(), x.rend());
      star.insert(star.end(), x.begin(), x.end());
      star.insert(star.end(), x.rbegin(), x.rend());
      auto window = [&](std::int64_t j) {
        double w = 0.0;
        for (std::int64_t t = j; t < j + m; ++t) w += star[t];
        return w;
      };
      for (std::int64_t j = 0; j < 6 * m; ++j) {
        const double d = window(j) - 2.0 * window(j + m) + window(j + 2 * m);
        total += d * d;
      }
    }
    EXPECT_NEAR(total_modified_sum_direct(z, m) / total, 1.0, 1e-12) << "m " << m;
    EXPECT_NEAR(total_modified_sum_blocked(z, m) / total, 1.0, 1e-12) << "m " << m;
  }
  const std::vector<double> short_record(5, 1.0);
  EXPECT_THROW(total_modified_sum(short_record, 2), UsageError);
  EXPECT_THROW(total_modified_sum(short_record, 0), UsageError);
}

TEST(Theo1Kernel, OddOrOutOfRangeFactorsAreRefused) {
  const std::vector<double> x = test::white(100, 3, 1.0);
  for (const std::int64_t m : {0L, 3L, 100L, 101L}) {
    const std::vector<std::int64_t> factors = {m};
    EXPECT_THROW(theo1_sums(x, factors), UsageError) << "m " << m;
  }
}

}  // namespace
}  // namespace foglab::stats::detail
