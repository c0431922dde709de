// The noise model's theory (core/noise_model.h), each formula checked
// against another one it must agree with: the Allan variance of each term
// against its PSD through the Allan transfer function (IEEE Std 952,
// Annex C) and against its structure function, the Gauss-Markov series
// against the closed form in long double, and the datasheet conversions.
#include "foglab/core/noise_model.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "foglab/core/error.h"
#include "support/expect.h"

namespace foglab {
namespace {

constexpr double kPi = std::numbers::pi;

// 4 int_0^inf S(f) sin^4(pi f tau) / (pi f tau)^2 df, with x = pi f tau:
// (4 / (pi tau)) int_0^inf S(x / (pi tau)) sin^4(x) / x^2 dx, summed over
// half periods up to x = X and the tail (S slowly varying there) with the
// mean of sin^4, 3/8.
double allan_variance_from_psd(const NoiseModel& m, NoiseTerm t, double tau) {
  auto s = [&](double x) { return rate_psd(m, t, x / (kPi * tau), 0.0); };
  auto integrand = [&](double x) {
    const double sx = std::sin(x);
    return s(x) * sx * sx * sx * sx / (x * x);
  };
  constexpr int kHalfPeriods = 4000;
  double sum = 0.0;
  for (int k = 0; k < kHalfPeriods; ++k) {
    sum += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
        integrand, k * kPi / 2.0, (k + 1) * kPi / 2.0, 15, 1e-13);
  }
  const double x_end = kHalfPeriods * kPi / 2.0;
  sum += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
      [&](double u) {  // x = x_end / u, dx = x_end / u^2 du
        const double x = x_end / u;
        return 0.375 * s(x) / (x * x) * x_end / (u * u);
      },
      0.0, 1.0, 15, 1e-13);
  return 4.0 / (kPi * tau) * sum;
}

TEST(NoiseModel, EachTermsAllanVarianceIsItsPsdThroughTheAllanTransferFunction) {
  const NoiseModel m{.N = 0.7, .B = 0.3, .K = 0.02, .gm_sigma = 1.5, .gm_tc = 40.0};
  for (const NoiseTerm t :
       {NoiseTerm::white, NoiseTerm::flicker, NoiseTerm::random_walk, NoiseTerm::gauss_markov}) {
    for (const double tau : {0.1, 3.0, 40.0, 900.0}) {
      const double expected = allan_variance(m, t, tau);
      EXPECT_NEAR(allan_variance_from_psd(m, t, tau) / expected, 1.0, 1e-6)
          << to_string(t) << " at tau " << tau << " s";
    }
  }
}

TEST(NoiseModel, EachTermsAllanVarianceFollowsFromItsStructureFunction) {
  // AVAR(tau) = (4 D(tau) - D(2 tau)) / (2 tau^2): Greenhall's D up to a
  // straight line, which that combination cancels.
  const NoiseModel m{.N = 0.7, .B = 0.3, .K = 0.02, .Q = 0.05, .gm_sigma = 1.5, .gm_tc = 40.0};
  for (const NoiseTerm t : {NoiseTerm::white, NoiseTerm::flicker, NoiseTerm::random_walk,
                            NoiseTerm::quantisation, NoiseTerm::gauss_markov}) {
    for (const double tau : {1e-3, 0.1, 3.0, 40.0, 900.0, 1e5}) {
      const double d1 = angle_structure_function(m, t, tau);
      const double d2 = angle_structure_function(m, t, 2.0 * tau);
      const double expected = allan_variance(m, t, tau);
      EXPECT_NEAR((4.0 * d1 - d2) / (2.0 * tau * tau) / expected, 1.0, 1e-7)
          << to_string(t) << " at tau " << tau << " s";
    }
  }
  EXPECT_EQ(angle_structure_function(m, NoiseTerm::ramp, 10.0), 0.0);
  EXPECT_EQ(angle_structure_function(m, NoiseTerm::white, 0.0), 0.0);
}

TEST(NoiseModel, TermsHaveTheirIeee952AllanVariances) {
  EXPECT_DOUBLE_EQ(std::sqrt(allan_variance(NoiseModel{.N = 2.0}, 1.0)), 2.0);
  EXPECT_NEAR(allan_variance(NoiseModel{.K = 0.3}, 3.0), 0.09, 1e-15);
  EXPECT_DOUBLE_EQ(allan_variance(NoiseModel{.R = 2.0}, 3.0), 4.0 * 9.0 / 2.0);
  EXPECT_DOUBLE_EQ(allan_variance(NoiseModel{.Q = 2.0}, 3.0), 3.0 * 4.0 / 9.0);
  // the flicker plateau, sqrt(2 ln 2 / pi) = 0.6643 (IEEE Std 952 quotes 0.664 B)
  EXPECT_NEAR(std::sqrt(allan_variance(NoiseModel{.B = 1.0}, 123.0)), 0.664282, 1e-6);
  // Gauss-Markov: like a random walk with K^2 = 2 sigma^2 / Tc at short
  // tau, like white noise with N^2 = 2 sigma^2 Tc at long tau
  const NoiseModel gm{.gm_sigma = 1.0, .gm_tc = 100.0};
  EXPECT_NEAR(allan_variance(gm, 0.01) / (2.0 / 100.0 * 0.01 / 3.0), 1.0, 1e-4);
  EXPECT_NEAR(allan_variance(gm, 1e6) / (2.0 * 100.0 / 1e6), 1.0, 1e-3);
  // no Tc, no term
  EXPECT_EQ(allan_variance(NoiseModel{.gm_sigma = 1.0}, 1.0), 0.0);
  // the model is the sum of its terms
  const NoiseModel all{
      .N = 0.3, .B = 0.05, .K = 0.01, .R = 2e-5, .Q = 0.02, .gm_sigma = 0.1, .gm_tc = 300.0};
  for (const double tau : {1e-3, 1.0, 299.0, 1e6}) {
    double sum = 0.0;
    for (const NoiseTerm t : kNoiseTerms) sum += allan_variance(all, t, tau);
    EXPECT_NEAR(allan_variance(all, tau), sum, 1e-14 * sum);
  }
}

TEST(NoiseModel, GaussMarkovShapeMatchesTheClosedFormInLongDouble) {
  // x = tau/Tc. The closed form (2x + 4 (e^-x - 1) - (e^-2x - 1)) / x^2 in
  // long double (64-bit mantissa) cancels from terms of size x to 2x^3/3:
  // about 2^-64 / x^2 relative, 1e-16 for x >= 0.05. Below that, the Taylor
  // series of the numerator, e^-x and e^-2x expanded term by term: the
  // terms of order 0 (4 - 1 - 3), 1 (2x - 4x + 2x) and 2 (4/2 - 4/2) x^2
  // cancel exactly, leaving sum_{n>=3} (4 - 2^n) (-x)^n / n!, summed in
  // long double (25 terms).
  auto series = [](long double x) {
    long double sum = 0.0L, power = x * x, factorial = 2.0L;  // (-x)^n, n!
    for (int n = 3; n <= 27; ++n) {
      power *= -x;
      factorial *= n;
      sum += (4.0L - std::pow(2.0L, n)) * power / factorial;
    }
    return sum / (x * x);
  };
  for (double x = 1e-6; x < 1e3; x *= 1.07) {
    const long double lx = x;
    const long double expected =
        x >= 0.05 ? (2.0L * lx + 4.0L * std::expm1(-lx) - std::expm1(-2.0L * lx)) / (lx * lx)
                  : series(lx);
    EXPECT_NEAR(gauss_markov_allan_shape(x, 1.0) / static_cast<double>(expected), 1.0, 1e-13)
        << "tau/Tc " << x;
  }
  // only the ratio matters
  EXPECT_DOUBLE_EQ(gauss_markov_allan_shape(5.0, 20.0), gauss_markov_allan_shape(0.25, 1.0));
}

TEST(NoiseModel, DatasheetConversions) {
  EXPECT_DOUBLE_EQ(arw_deg_sqrt_h(60.0), 1.0);
  EXPECT_DOUBLE_EQ(white_noise_of_arw(0.067), 60.0 * 0.067);
  EXPECT_NEAR(flicker_floor_deg_h(1.0), 0.664282, 1e-6);
  EXPECT_NEAR(flicker_coefficient_deg_h(flicker_floor_deg_h(0.37)), 0.37, 1e-15);
  EXPECT_DOUBLE_EQ(kFlickerAllanFactor, allan_variance(NoiseModel{.B = 1.0}, 1.0));
}

TEST(NoiseModel, CoefficientsAndTermSets) {
  NoiseModel m;
  for (const NoiseTerm t : kNoiseTerms) m.set_coefficient(t, 1.0 + static_cast<int>(t));
  EXPECT_EQ(m.N, 1.0);
  EXPECT_EQ(m.Q, 5.0);
  EXPECT_EQ(m.gm_sigma, 6.0);
  for (const NoiseTerm t : kNoiseTerms) EXPECT_EQ(m.coefficient(t), 1.0 + static_cast<int>(t));
  EXPECT_EQ(to_string(m.terms()), "N+B+K+R+Q+GM");
  EXPECT_EQ(m.terms().parameter_count(), 7);
  EXPECT_EQ(to_string(NoiseModel{.N = 1.0, .K = 2.0}.terms()), "N+K");
  EXPECT_EQ(to_string(NoiseTermSet{}), "none");
  EXPECT_EQ(to_string(m.terms().without(NoiseTerm::ramp)), "N+B+K+Q+GM");
  EXPECT_EQ(to_string(NoiseModel{.N = 1.0}.terms().without(NoiseTerm::ramp)), "N");
  for (const char* text : {"none", "N", "N+B+K", "N+GM", "B+R+Q"}) {
    EXPECT_EQ(to_string(noise_term_set_from_string(text)), text);
  }
  EXPECT_EQ(test::message_of<UsageError>([] { noise_term_set_from_string("N+X"); }),
            "noise term: expected N, B, K, R, Q or GM, got 'X'");
  EXPECT_EQ(test::message_of<UsageError>([] { noise_term_set_from_string("N+N"); }),
            "noise terms: 'N' is named twice");
  for (std::size_t i = 0; i < kNoiseParameters.size(); ++i) {
    const NoiseParameter& p = kNoiseParameters[i];
    EXPECT_EQ(p.term, kNoiseTerms[std::min<std::size_t>(i, 5)]) << p.name;
  }
}

TEST(NoiseModel, AdevMinimumOfWhiteNoiseAndARandomWalk) {
  // d/dtau (N^2/tau + K^2 tau/3) = 0 at tau = sqrt(3) N/K; ADEV^2 there 2 N K / sqrt(3).
  const NoiseModel nk{.N = 1.0, .K = 0.01};
  const AdevMinimum m = adev_minimum(nk, 0.1, 1e5);
  EXPECT_NEAR(m.tau_s, std::sqrt(3.0) * 1.0 / 0.01, 1e-3);
  EXPECT_NEAR(m.adev_deg_h, std::sqrt(2 * 1.0 * 0.01 / std::sqrt(3.0)), 1e-9);
  EXPECT_FALSE(m.at_range_edge);
  EXPECT_TRUE(adev_minimum(nk, 0.1, 10.0).at_range_edge);
  EXPECT_THROW(adev_minimum(nk, 0.0, 10.0), UsageError);
}

TEST(NoiseModel, DominanceOctavesEndWhereTheLinesCross) {
  // White noise and a random walk cross at tau = sqrt(3) N / K = 100 s:
  // white carries the Allan variance below, the random walk above.
  NoiseModel nk{.N = 1.0, .K = std::sqrt(3.0) / 100.0};
  // within a step of the 400-step grid either way (the crossing is a grid point)
  const double grid = 1.5 * std::log2(1e4 / 1.0) / 400;
  EXPECT_NEAR(term_dominance_octaves(nk, NoiseTerm::white, 1.0, 1e4), std::log2(100.0), grid);
  EXPECT_NEAR(term_dominance_octaves(nk, NoiseTerm::random_walk, 1.0, 1e4), std::log2(100.0), grid);
  EXPECT_EQ(term_dominance_octaves(nk, NoiseTerm::flicker, 1.0, 1e4), 0.0);
  // A term alone carries all of it, over the whole range.
  EXPECT_NEAR(term_dominance_octaves(nk, NoiseTerm::white, 1.0, 10.0), std::log2(10.0), 1e-9);
  EXPECT_EQ(test::message_of<UsageError>(
                [&] { term_dominance_octaves(nk, NoiseTerm::white, 0.0, 10.0); }),
            "term_dominance_octaves: invalid tau range [0, 10] s");
}

}  // namespace
}  // namespace foglab
