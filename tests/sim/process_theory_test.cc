// Every process of the error model, generated alone, against its theory:
// overlapping Allan deviation inside its confidence intervals around the
// IEEE Std 952 formula (error_model.h) at every tau of the octave grid,
// including tau0, and the two-sided PSD levels and slopes (psd.h). Plus the
// building blocks: the normal generator, the exact OU step, the flicker bank.
//
// Because neighbouring taus of one record are correlated, a set passes when
// at least 85 % of its taus hold the theory inside their 95 % interval and
// none is outside the 99.9 % interval. Fixed seeds throughout.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "../../src/sim/generator_internal.h"
#include "foglab/sim/generator.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/confidence.h"
#include "foglab/stats/psd.h"

namespace foglab::sim {
namespace {

const double kPlateau = 2.0 * std::log(2.0) / std::numbers::pi;  // AVAR of flicker / B^2

std::vector<double> rate_of(const ErrorModel& m, double fs_hz, double samples, std::uint64_t seed) {
  GeneratorOptions o;
  o.sample_rate_hz = fs_hz;
  o.duration_s = samples / fs_hz;
  o.seed = seed;
  return generate(m, TemperatureProfile{}, o).rate_deg_h;
}

// The OADEV of `rate` against sqrt(theory_avar(tau)).
void expect_allan_matches(const std::vector<double>& rate, double fs_hz,
                          const std::function<double(double)>& theory_avar, const std::string& what) {
  const stats::AllanResult r = stats::allan_deviation(rate, fs_hz, InputKind::rate);
  ASSERT_GE(r.tau_s.size(), 10u) << what;
  int inside95 = 0;
  for (std::size_t i = 0; i < r.tau_s.size(); ++i) {
    const double theory = std::sqrt(theory_avar(r.tau_s[i]));
    if (theory >= r.ci95_low[i] && theory <= r.ci95_high[i]) ++inside95;
    const stats::Interval wide = stats::chi2_interval(r.dev[i], r.edf[i], 0.999);
    EXPECT_TRUE(theory >= wide.low && theory <= wide.high)
        << what << ": tau " << r.tau_s[i] << " s, OADEV " << r.dev[i] << ", theory " << theory
        << ", 99.9 % interval [" << wide.low << ", " << wide.high << "], edf " << r.edf[i];
  }
  EXPECT_GE(inside95, static_cast<int>(std::ceil(0.85 * static_cast<double>(r.tau_s.size()))))
      << what << ": " << inside95 << " of " << r.tau_s.size() << " taus inside the 95 % interval";
}

double gm_avar(double sigma, double tc, double tau) {
  const double x = tau / tc;
  return sigma * sigma * (2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x)) / (x * x);
}

// --- building blocks ----------------------------------------------------------

TEST(NormalGenerator, HasTheMomentsAndTailsOfTheStandardNormal) {
  const auto& z = detail::ziggurat();
  const std::uint64_t key = detail::process_key(3, 0, 1);
  const int n = 2000000;
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  int beyond2 = 0, beyond3 = 0, beyond4 = 0;
  std::vector<int> bins(20, 0);  // equiprobable bins of the normal
  std::vector<double> edges;     // inverse normal CDF at k/20 by bisection
  for (int k = 1; k < 20; ++k) {
    double lo = -10, hi = 10;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (0.5 * std::erfc(-mid / std::sqrt(2.0)) < k / 20.0 ? lo : hi) = mid;
    }
    edges.push_back(lo);
  }
  for (int i = 0; i < n; ++i) {
    const double x = detail::normal_at(z, key, static_cast<std::uint64_t>(i));
    s1 += x;
    s2 += x * x;
    s3 += x * x * x;
    s4 += x * x * x * x;
    beyond2 += std::fabs(x) > 2.0;
    beyond3 += std::fabs(x) > 3.0;
    beyond4 += std::fabs(x) > 4.0;
    bins[static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin())]++;
  }
  const double dn = n;
  EXPECT_NEAR(s1 / dn, 0.0, 4.0 / std::sqrt(dn));
  EXPECT_NEAR(s2 / dn, 1.0, 4.0 * std::sqrt(2.0 / dn));
  EXPECT_NEAR(s3 / dn, 0.0, 4.0 * std::sqrt(15.0 / dn));
  EXPECT_NEAR(s4 / dn, 3.0, 4.0 * std::sqrt(96.0 / dn));
  const auto expect_tail = [&](int count, double p) {
    EXPECT_NEAR(count / dn, p, 4.0 * std::sqrt(p / dn)) << "tail " << p;
  };
  expect_tail(beyond2, 0.045500263896);
  expect_tail(beyond3, 0.002699796063);
  expect_tail(beyond4, 0.000063342484);
  double chi2 = 0.0;
  for (const int b : bins) chi2 += (b - dn / 20) * (b - dn / 20) / (dn / 20);
  EXPECT_LT(chi2, 43.8);  // chi-square(19) at p = 0.001
}

TEST(OuStep, IsStationaryAndTendsToBrownianMotion) {
  for (const double x : {1e-7, 1e-3, 0.2, 0.3, 1.0, 5.0, 40.0}) {
    const detail::OuStep s = detail::ou_step(1.0, x);
    // The state keeps unit variance.
    EXPECT_NEAR(s.rho * s.rho + s.s_state * s.s_state, 1.0, 1e-14) << x;
    // The stationary variance of the interval average: 2 (x - 1 + e^-x) / x^2.
    const double var_avg = 2.0 * (x + std::expm1(-x)) / (x * x);
    const double got = s.beta * s.beta + s.s_avg_state * s.s_avg_state + s.s_avg * s.s_avg;
    EXPECT_NEAR(got / var_avg, 1.0, x < 1e-5 ? 1e-6 : 1e-12) << x;
  }
  // Small steps: e1 ~ sqrt(2x), Cov(e1, e2) / Var e1 -> 1/2, conditional
  // variance of the average -> (2x)/12 (a Brownian bridge average).
  const detail::OuStep s = detail::ou_step(1.0, 1e-6);
  EXPECT_NEAR(s.s_state / std::sqrt(2e-6), 1.0, 1e-5);
  EXPECT_NEAR(s.s_avg_state / s.s_state, 0.5, 1e-5);
  EXPECT_NEAR(s.s_avg * s.s_avg / (2e-6 / 12.0), 1.0, 1e-4);
  // Series and closed forms of the Allan variance meet smoothly.
  for (const double x : {0.2499999, 0.2500001}) {
    EXPECT_NEAR(gauss_markov_allan_shape(x, 1.0), gm_avar(1.0, 1.0, x), 1e-12);
  }
  EXPECT_NEAR(gauss_markov_allan_shape(1e-6, 1.0) / (2e-6 / 3.0), 1.0, 1e-5);
}

TEST(FlickerBank, CalibratedPlateauIsFlatToOnePercentOverTheRecord) {
  struct Case {
    double fs_hz, duration_s;
  };
  for (const Case c : {Case{1.0, 3600.0}, Case{10.0, 86400.0}, Case{100.0, 1e6}, Case{2000.0, 5e5},
                       Case{1.0, 1e9}}) {
    const detail::FlickerDesign d = detail::design_flicker(c.fs_hz, c.duration_s);
    EXPECT_LT(d.max_relative_error, 0.01) << c.fs_hz << " Hz, " << c.duration_s << " s";
    EXPECT_EQ(d.fit_tau_min_s, 1.0 / c.fs_hz);
    EXPECT_EQ(d.fit_tau_max_s, c.duration_s);
    for (double tau = 1.0 / c.fs_hz; tau <= c.duration_s; tau *= 1.5) {
      EXPECT_NEAR(detail::flicker_bank_allan_variance(d, tau) / kPlateau, 1.0, 0.01) << tau;
    }
    int fast = 0;
    for (const auto& comp : d.components) {
      EXPECT_GE(comp.variance, 0.0);
      // Decimated components are updated at most every Tc / (64 tau0).
      if (comp.level > 0) {
        EXPECT_LE(std::ldexp(1.0, comp.level), comp.tc_s * c.fs_hz / detail::kFlickerDecimationRatio);
      } else {
        ++fast;
      }
    }
    EXPECT_LE(fast, 8);  // the per-sample cost
    EXPECT_GE(d.components.back().tc_s, 10.0 * c.duration_s);
  }
}

// --- each process alone: Allan deviation ----------------------------------------

TEST(ProcessTheory, WhiteRateNoiseFollowsNSquaredOverTau) {
  struct Case {
    double fs, n, samples;
  };
  for (const Case c : {Case{100.0, 0.5, 1e6}, Case{10.0, 2.0, 3e5}}) {
    ErrorModel m;
    m.noise.N = c.n;
    expect_allan_matches(rate_of(m, c.fs, c.samples, 12), c.fs,
                         [&](double tau) { return c.n * c.n / tau; }, "white N " + std::to_string(c.n));
  }
}

TEST(ProcessTheory, RateRandomWalkFollowsKSquaredTauOverThreeFromTau0) {
  struct Case {
    double fs, k, samples;
  };
  for (const Case c : {Case{100.0, 0.02, 1e6}, Case{1.0, 0.5, 3e5}}) {
    ErrorModel m;
    m.noise.K = c.k;
    expect_allan_matches(rate_of(m, c.fs, c.samples, 12), c.fs,
                         [&](double tau) { return c.k * c.k * tau / 3.0; }, "random walk K " + std::to_string(c.k));
  }
}

TEST(ProcessTheory, GaussMarkovFollowsItsAllanFormula) {
  struct Case {
    double fs, sigma, tc, samples;
  };
  for (const Case c : {Case{100.0, 0.2, 0.02, 1e6},  // Tc = 2 tau0: the averaging matters
                       Case{10.0, 1.0, 3.0, 1e6}, Case{1.0, 0.5, 300.0, 1e6}}) {
    ErrorModel m;
    m.noise.gm_sigma = c.sigma;
    m.noise.gm_tc = c.tc;
    expect_allan_matches(rate_of(m, c.fs, c.samples, 13), c.fs,
                         [&](double tau) { return gm_avar(c.sigma, c.tc, tau); },
                         "Gauss-Markov Tc " + std::to_string(c.tc));
  }
}

TEST(ProcessTheory, QuantisationFollowsThreeQSquaredOverTauSquared) {
  struct Case {
    double fs, q, samples;
  };
  for (const Case c : {Case{100.0, 0.1, 1e6}, Case{1000.0, 0.005, 1e6}}) {
    ErrorModel m;
    m.noise.Q = c.q;
    expect_allan_matches(rate_of(m, c.fs, c.samples, 14), c.fs,
                         [&](double tau) { return 3.0 * c.q * c.q / (tau * tau); },
                         "quantisation Q " + std::to_string(c.q));
  }
}

TEST(ProcessTheory, RateRampGivesRTauOverSqrtTwoExactly) {
  ErrorModel m;
  m.noise.R = 0.01;
  const std::vector<double> rate = rate_of(m, 10.0, 1e5, 15);
  stats::AllanOptions o;
  o.confidence = false;
  const stats::AllanResult r = stats::allan_deviation(rate, 10.0, InputKind::rate, o);
  ASSERT_GE(r.tau_s.size(), 10u);
  for (std::size_t i = 0; i < r.tau_s.size(); ++i) {
    EXPECT_NEAR(r.dev[i] / (0.01 * r.tau_s[i] / std::sqrt(2.0)), 1.0, 1e-6) << r.tau_s[i];
  }
}

TEST(ProcessTheory, FlickerPlateauIsFlatWithinFivePercentOverFourDecades) {
  // One record's OADEV of flicker noise scatters by several per cent at
  // large tau, so the Allan variance is averaged over six seeds (six
  // independent records of 4e6 samples at 100 Hz): tau = 0.01 .. 163.84 s,
  // 4.2 decades, at least 244 clusters.
  ErrorModel m;
  m.noise.B = 0.7;
  const double fs = 100.0;
  const int seeds = 6;
  std::vector<double> tau, mean_avar;
  stats::AllanOptions o;
  o.confidence = false;
  o.grid.min_clusters = 244;
  for (int s = 0; s < seeds; ++s) {
    const stats::AllanResult r = stats::allan_deviation(rate_of(m, fs, 4e6, 100 + s), fs, InputKind::rate, o);
    if (s == 0) {
      tau = r.tau_s;
      mean_avar.assign(tau.size(), 0.0);
    }
    for (std::size_t i = 0; i < tau.size(); ++i) mean_avar[i] += r.dev[i] * r.dev[i] / seeds;
  }
  ASSERT_GE(tau.size(), 15u);
  EXPECT_GE(tau.back() / tau.front(), 1e4);
  const double plateau_dev = std::sqrt(kPlateau) * m.noise.B;  // 0.664 B
  for (std::size_t i = 0; i < tau.size(); ++i) {
    EXPECT_NEAR(std::sqrt(mean_avar[i]) / plateau_dev, 1.0, 0.05) << "tau " << tau[i] << " s";
    // Where the average is precise (up to 10 s), it also shows that the
    // decimated slow components (linear interpolation between their exact
    // steps) lose no more than 2 % of the Allan variance.
    if (tau[i] <= 10.0) {
      EXPECT_NEAR(mean_avar[i] / (m.noise.B * m.noise.B * kPlateau), 1.0, 0.02)
          << "tau " << tau[i] << " s";
    }
  }
}

// --- PSD levels and slopes ---------------------------------------------------

// Least-squares slope of log10(psd) against log10(f) over [f_lo, f_hi], and the
// mean ratio of psd to `theory` there (on 10-per-decade log bins).
struct PsdFit {
  double slope = 0.0;
  double min_ratio = 1e300;
  double max_ratio = 0.0;
  int points = 0;
};

PsdFit fit_psd(const std::vector<double>& rate, double fs, std::size_t segment, double f_lo, double f_hi,
               const std::function<double(double)>& theory) {
  stats::WelchOptions w;
  w.segment_length = segment;
  const stats::PsdResult p = stats::log_smooth(stats::welch_psd(rate, fs, w), 10.0);
  PsdFit fit;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < p.frequency_hz.size(); ++i) {
    const double f = p.frequency_hz[i];
    if (f < f_lo || f > f_hi) continue;
    const double x = std::log10(f), y = std::log10(p.psd[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++fit.points;
    const double ratio = p.psd[i] / theory(f);
    fit.min_ratio = std::min(fit.min_ratio, ratio);
    fit.max_ratio = std::max(fit.max_ratio, ratio);
  }
  fit.slope = (fit.points * sxy - sx * sy) / (fit.points * sxx - sx * sx);
  return fit;
}

TEST(ProcessPsd, WhiteNoiseIsFlatAtNSquared) {
  ErrorModel m;
  m.noise.N = 0.5;
  const std::vector<double> rate = rate_of(m, 100.0, 1e6, 21);
  stats::WelchOptions w;
  w.segment_length = 4096;
  const stats::PsdResult p = stats::welch_psd(rate, 100.0, w);
  double mean = 0.0;
  for (const double v : p.psd) mean += v / static_cast<double>(p.psd.size());
  EXPECT_NEAR(mean / 0.25, 1.0, 0.02);
  // Log bins above 0.5 Hz hold >= 20 Welch bins of 488 segments each.
  const PsdFit fit = fit_psd(rate, 100.0, 4096, 0.5, 50.0, [](double) { return 0.25; });
  EXPECT_NEAR(fit.slope, 0.0, 0.03);
  EXPECT_GT(fit.min_ratio, 0.95);
  EXPECT_LT(fit.max_ratio, 1.05);
}

TEST(ProcessPsd, RandomWalkHasSlopeMinusTwoAndLevelKSquaredOverTwoPiFSquared) {
  ErrorModel m;
  m.noise.K = 0.5;
  const double fs = 10.0;
  const PsdFit fit = fit_psd(rate_of(m, fs, 1e6, 22), fs, 8192, 0.01, 0.5, [&](double f) {
    return m.noise.K * m.noise.K / std::pow(2.0 * std::numbers::pi * f, 2.0);
  });
  EXPECT_GE(fit.points, 15);
  EXPECT_NEAR(fit.slope, -2.0, 0.15);
  EXPECT_GT(fit.min_ratio, 0.8);
  EXPECT_LT(fit.max_ratio, 1.2);
}

TEST(ProcessPsd, FlickerHasSlopeMinusOneAndLevelBSquaredOverTwoPiF) {
  // Two-sided S(f) = B^2 / (2 pi f): with 4 int_0^inf S(f) sin^4(pi f tau) /
  // (pi f tau)^2 df and int_0^inf sin^4(x)/x^3 dx = ln 2 it gives the
  // plateau (2 ln2 / pi) B^2 (IEEE Std 952 Annex C).
  ErrorModel m;
  m.noise.B = 1.0;
  const double fs = 100.0;
  const PsdFit fit = fit_psd(rate_of(m, fs, 4e6, 23), fs, 65536, 0.01, 5.0, [&](double f) {
    return m.noise.B * m.noise.B / (2.0 * std::numbers::pi * f);
  });
  EXPECT_GE(fit.points, 25);
  EXPECT_NEAR(fit.slope, -1.0, 0.15);
  EXPECT_GT(fit.min_ratio, 0.8);
  EXPECT_LT(fit.max_ratio, 1.2);
}

TEST(ProcessPsd, GaussMarkovIsLorentzian) {
  ErrorModel m;
  m.noise.gm_sigma = 1.0;
  m.noise.gm_tc = 30.0;
  const double fs = 10.0;
  const PsdFit fit = fit_psd(rate_of(m, fs, 1e6, 24), fs, 16384, 2e-3, 0.5, [&](double f) {
    const double w = 2.0 * std::numbers::pi * f * m.noise.gm_tc;
    return 2.0 * m.noise.gm_sigma * m.noise.gm_sigma * m.noise.gm_tc / (1.0 + w * w);
  });
  EXPECT_GE(fit.points, 15);
  EXPECT_GT(fit.min_ratio, 0.8);
  EXPECT_LT(fit.max_ratio, 1.2);
}

}  // namespace
}  // namespace foglab::sim
