// The Allan family against theory on simulated noise (IEEE Std 952 Annex C,
// NIST SP 1065 Table 8): slopes, levels inside the confidence intervals, the
// coverage of the intervals themselves, and numerical care with a large bias.
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/confidence.h"
#include "support/noise.h"

namespace foglab::stats {
namespace {

// Least-squares slope of log10(dev) against log10(tau).
double loglog_slope(const AllanResult& r, double tau_min_s, double tau_max_s) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int count = 0;
  for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
    if (r.tau_s[k] < tau_min_s || r.tau_s[k] > tau_max_s) continue;
    const double x = std::log10(r.tau_s[k]);
    const double y = std::log10(r.dev[k]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++count;
  }
  return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

AllanResult run(const std::vector<double>& rate, double fs_hz, AllanKind kind) {
  AllanOptions options;
  options.kind = kind;
  return allan_deviation(rate, fs_hz, InputKind::rate, options);
}

TEST(AllanTheory, WhiteRateNoiseHasSlopeMinusHalfForEveryStatistic) {
  constexpr double kFsHz = 100.0;
  constexpr double kN = 0.2;  // deg/h/sqrt(Hz)
  const std::vector<double> rate = test::white(1 << 20, 11, kN * std::sqrt(kFsHz));
  for (const AllanKind kind : all_allan_kinds()) {
    const AllanResult r = run(rate, kFsHz, kind);
    const double expected = kind == AllanKind::tdev || kind == AllanKind::ttotdev ? 0.5 : -0.5;
    EXPECT_NEAR(loglog_slope(r, 0.05, 100.0), expected, 0.05) << to_string(kind);
  }
}

TEST(AllanTheory, WhiteRateNoiseLevelIsNOverSqrtTauWithinIntervals) {
  // For white rate noise AVAR = HVAR = TOTVAR = N^2 / tau (SP1065 Table 8).
  constexpr double kFsHz = 50.0;
  constexpr double kN = 0.05;
  const std::vector<double> rate = test::white(1 << 19, 12, kN * std::sqrt(kFsHz));
  for (const AllanKind kind : {AllanKind::adev, AllanKind::oadev, AllanKind::hdev,
                               AllanKind::ohdev, AllanKind::totdev}) {
    const AllanResult r = run(rate, kFsHz, kind);
    for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
      EXPECT_EQ(r.alpha[k], 0) << to_string(kind) << " tau " << r.tau_s[k];
      // Neighbouring taus are correlated, so judge each tau at 99.9 %
      // where there are at least 100 clusters.
      if (r.tau_s[k] * kFsHz * 100 > static_cast<double>(rate.size())) continue;
      const Interval wide = chi2_interval(r.dev[k], r.edf[k], 0.999);
      const double truth = kN / std::sqrt(r.tau_s[k]);
      EXPECT_GE(truth, wide.low) << to_string(kind) << " tau " << r.tau_s[k];
      EXPECT_LE(truth, wide.high) << to_string(kind) << " tau " << r.tau_s[k];
    }
    EXPECT_NEAR(r.dev[0] / (kN / std::sqrt(r.tau_s[0])), 1.0, 0.01) << to_string(kind);
  }
}

TEST(AllanTheory, RateRandomWalkHasSlopePlusHalfAndLevelKSqrtTauOver3) {
  // A rate random walk of intensity K: AVAR = K^2 tau / 3 (IEEE 952).
  constexpr double kFsHz = 10.0;
  constexpr double kK = 0.01;  // deg/h/sqrt(s)
  const std::vector<double> rate = test::random_walk(1 << 19, 13, kK / std::sqrt(kFsHz));
  const AllanResult r = run(rate, kFsHz, AllanKind::oadev);
  EXPECT_NEAR(loglog_slope(r, 10.0, 1e4), 0.5, 0.1);
  int inside = 0, counted = 0;
  for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
    if (r.tau_s[k] < 5.0) continue;  // the discrete walk needs m >> 1
    const double truth = kK * std::sqrt(r.tau_s[k] / 3.0);
    ++counted;
    if (truth >= r.ci95_low[k] && truth <= r.ci95_high[k]) ++inside;
    EXPECT_EQ(r.alpha[k], -2) << "tau " << r.tau_s[k];
  }
  EXPECT_GE(inside, counted - 2);
}

TEST(AllanTheory, ModifiedAllanOfWhiteRateNoiseIsHalfTheAllanVariance) {
  // R(n) = MVAR/AVAR -> 1/2 for white FM at large m (SP1065 section 5.2.5).
  constexpr double kFsHz = 1.0;
  const std::vector<double> rate = test::white(1 << 20, 14, 1.0);
  AllanOptions options;
  options.kind = AllanKind::mdev;
  options.grid = parse_tau_grid("64,256,1024");
  const AllanResult mod = allan_deviation(rate, kFsHz, InputKind::rate, options);
  for (std::size_t k = 0; k < mod.tau_s.size(); ++k) {
    const double avar = 1.0 / mod.tau_s[k];
    EXPECT_NEAR(mod.dev[k] * mod.dev[k] / avar, 0.5, 0.08) << "tau " << mod.tau_s[k];
  }
}

TEST(AllanTheory, NinetyFivePercentIntervalsCoverTheTruthNinetyFivePercentOfTheTime) {
  // End-to-end check of noise ID + Greenhall edf + chi-square: 400 records.
  constexpr int kRecords = 400;
  int covered_oadev = 0, covered_adev = 0;
  for (int s = 0; s < kRecords; ++s) {
    const std::vector<double> rate = test::white(2000, 1000 + s, 1.0);
    AllanOptions options;
    options.grid = parse_tau_grid("8");
    const AllanResult o = allan_deviation(rate, 1.0, InputKind::rate, options);
    if (1.0 / std::sqrt(8.0) >= o.ci95_low[0] && 1.0 / std::sqrt(8.0) <= o.ci95_high[0]) {
      ++covered_oadev;
    }
    options.kind = AllanKind::adev;
    const AllanResult a = allan_deviation(rate, 1.0, InputKind::rate, options);
    if (1.0 / std::sqrt(8.0) >= a.ci95_low[0] && 1.0 / std::sqrt(8.0) <= a.ci95_high[0]) {
      ++covered_adev;
    }
  }
  // Binomial(400, 0.95): standard deviation 4.4 records; allow 3 sigma.
  EXPECT_NEAR(covered_oadev, 0.95 * kRecords, 13);
  EXPECT_NEAR(covered_adev, 0.95 * kRecords, 13);
}

TEST(AllanTheory, WhiteFmIsNeverCalledPhaseNoiseAtLongTauSoIntervalsStayHonest) {
  // With 30-60 decimated points the lag-1 method alone calls white FM "PM"
  // in roughly one record in four, and the PM edf is orders of magnitude too
  // large. Over 30 records, the truth must fall outside the 99.9 % interval
  // about as rarely as 99.9 % says (expected 0.45 of 450 taus; allow 3).
  int outside = 0, total = 0;
  for (int s = 0; s < 30; ++s) {
    const std::vector<double> rate = test::white(200000, 5000 + s, 1.0);
    const AllanResult r = allan_deviation(rate, 1.0, InputKind::rate, AllanOptions{});
    for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
      EXPECT_LE(r.alpha[k], 0) << "seed " << s << " tau " << r.tau_s[k];
      const Interval wide = chi2_interval(r.dev[k], r.edf[k], 0.999);
      const double truth = 1.0 / std::sqrt(r.tau_s[k]);
      if (truth < wide.low || truth > wide.high) ++outside;
      ++total;
    }
  }
  EXPECT_LE(outside, 3) << "of " << total;
}

// White noise of unit variance plus a resonance: the second-order
// autoregression y_k = a1 y_{k-1} + a2 y_{k-2} + e_k with poles at radius r
// and frequency f (cycles per sample), its innovations e of sd `drive`.
struct Resonance {
  double r = 0.97, f = 0.2, drive = 0.25;
  double a1() const { return 2.0 * r * std::cos(6.283185307179586 * f); }
  double a2() const { return -r * r; }
  // The rate's autocovariance at lag l (Yule-Walker), the white noise's 1 at lag 0.
  double autocovariance(std::int64_t l) const {
    const double g0 =
        drive * drive * (1.0 - a2()) / ((1.0 + a2()) * ((1.0 - a2()) * (1.0 - a2()) - a1() * a1()));
    double before = g0, now = a1() * g0 / (1.0 - a2());
    if (l == 0) return g0 + 1.0;
    for (std::int64_t k = 1; k < l; ++k) {
      const double next = a1() * now + a2() * before;
      before = now, now = next;
    }
    return now;
  }
  // The exact Allan variance at factor m (tau0 = 1): the variance of the
  // difference of two neighbouring m-sample means.
  double allan_variance(std::int64_t m) const {
    double v = 0.0;
    for (std::int64_t i = 0; i < 2 * m; ++i) {
      for (std::int64_t j = 0; j < 2 * m; ++j) {
        const double wi = i < m ? -1.0 : 1.0, wj = j < m ? -1.0 : 1.0;
        v += wi * wj * autocovariance(i > j ? i - j : j - i);
      }
    }
    return v / (2.0 * static_cast<double>(m * m));
  }
  std::vector<double> record(std::size_t count, std::uint64_t seed) const {
    std::vector<double> y = test::white(count, seed, 1.0);
    const std::vector<double> e = test::white(count, seed + 77777, drive);
    double y1 = 0.0, y2 = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const double next = a1() * y1 + a2() * y2 + e[k];
      y2 = y1, y1 = next;
      y[k] += next;
    }
    return y;
  }
};

TEST(AllanTheory, AResonanceWidensTheIntervalsOfTheTausItCorrelates) {
  // The noise type's edf (SP 1065 section 5.3) assumes one power law; a
  // resonance keeps the second differences correlated over its decay time
  // (1 / (1 - r) = 33 samples here), so the estimate varies more than that
  // edf says. The terms' own spread (AllanOptions::term_spread_check) must
  // see it: the 95 % intervals at m = 1 and 2 hold the exact Allan variance
  // in 95 % of the records with the check (Binomial(100, 0.95): sd 2.2
  // records, 3 sd allowed; measured 96 and 95); the noise type's edf alone
  // held it in 71 and 56 of them (measured 2026-12-01).
  const Resonance res{.drive = 0.35};
  constexpr int kRecords = 100;
  const std::array<std::int64_t, 2> factors = {1, 2};
  std::array<int, 2> covered{}, covered_unchecked{};
  for (int s = 0; s < kRecords; ++s) {
    const std::vector<double> rate = res.record(1 << 17, 9000 + s);
    AllanOptions options;
    options.grid = parse_tau_grid("1,2");
    const AllanResult plain = allan_deviation(rate, 1.0, InputKind::rate, options);
    options.term_spread_check = true;
    const AllanResult checked = allan_deviation(rate, 1.0, InputKind::rate, options);
    for (std::size_t k = 0; k < factors.size(); ++k) {
      const double truth = std::sqrt(res.allan_variance(factors[k]));
      EXPECT_EQ(plain.dev[k], checked.dev[k]);
      covered[k] += truth >= checked.ci95_low[k] && truth <= checked.ci95_high[k];
      covered_unchecked[k] += truth >= plain.ci95_low[k] && truth <= plain.ci95_high[k];
    }
  }
  for (std::size_t k = 0; k < factors.size(); ++k) {
    EXPECT_NEAR(covered[k], 0.95 * kRecords, 7) << "m " << factors[k];
  }
  EXPECT_LT(covered_unchecked[1], 0.95 * kRecords - 7) << "the noise type's edf alone";
}

TEST(AllanTheory, TheTermSpreadCheckLeavesWhiteNoiseAlone) {
  // It divides an edf only beyond the 99.9 % quantile of chance: on white
  // noise about 0.1 % of the taus from m = 1 to 64 (expected 0.14 of 140
  // here; allow 2), and the 99.9 % intervals keep their coverage. At m = 1
  // it compares with the exact edf of sampled white noise, not Greenhall's,
  // which is 1.174 times that (the 17 % of edf_test.cc's first test): with
  // Greenhall's it had divided the edf at m = 1 on 7 of 8 records of 6 h
  // at 100 Hz.
  int divided = 0, checked = 0, outside = 0;
  for (int s = 0; s < 20; ++s) {
    const std::vector<double> rate = test::white(1 << 18, 7000 + s, 1.0);
    AllanOptions options;
    options.term_spread_check = true;
    const AllanResult r = allan_deviation(rate, 1.0, InputKind::rate, options);
    for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
      const Interval wide = chi2_interval(r.dev[k], r.edf[k], 0.999);
      const double truth = 1.0 / std::sqrt(r.tau_s[k]);
      outside += truth < wide.low || truth > wide.high;
      if (r.m[k] > 64) continue;  // beyond the check: fewer than 64 batches
      ++checked;
      divided += r.edf_reduction[k] > 1.0;
    }
  }
  EXPECT_EQ(checked, 20 * 7);
  EXPECT_LE(divided, 2) << "of " << checked;
  EXPECT_LE(outside, 2);
}

TEST(AllanTheory, LargeBiasIsRemovedExactlyBeforeIntegration) {
  // The quick version of large_record_test: 2^20 samples.
  const std::vector<double> noise = test::white(1 << 20, 15, 1e-3);
  std::vector<double> biased = noise;
  for (double& v : biased) v += 1e6;
  for (const AllanKind kind : all_allan_kinds()) {
    AllanOptions options;
    options.kind = kind;
    options.confidence = false;
    const AllanResult a = allan_deviation(noise, 1.0, InputKind::rate, options);
    const AllanResult b = allan_deviation(biased, 1.0, InputKind::rate, options);
    for (std::size_t k = 0; k < a.dev.size(); ++k) {
      EXPECT_NEAR(b.dev[k] / a.dev[k], 1.0, 1e-6) << to_string(kind) << " m " << a.m[k];
    }
  }
}

TEST(AllanTheory, PhaseInputGivesTheSameDeviationsAsItsRate) {
  const std::vector<double> rate = test::white(10000, 16, 1.0);
  std::vector<double> angle(rate.size() + 1, 0.0);
  constexpr double kFsHz = 4.0;
  for (std::size_t i = 0; i < rate.size(); ++i) angle[i + 1] = angle[i] + rate[i] / kFsHz;
  for (const AllanKind kind : all_allan_kinds()) {
    AllanOptions options;
    options.kind = kind;
    options.confidence = false;
    const AllanResult a = allan_deviation(rate, kFsHz, InputKind::rate, options);
    const AllanResult b = allan_deviation(angle, kFsHz, InputKind::phase, options);
    ASSERT_EQ(a.dev.size(), b.dev.size());
    for (std::size_t k = 0; k < a.dev.size(); ++k) {
      EXPECT_NEAR(b.dev[k] / a.dev[k], 1.0, 1e-9) << to_string(kind);
      EXPECT_EQ(a.n[k], b.n[k]);
    }
  }
}

TEST(AllanTheory, InPlaceFormGivesTheSameResultAsTheCopyingForm) {
  const std::vector<double> rate = test::white(200000, 18, 3.0);
  for (const InputKind input : {InputKind::rate, InputKind::phase}) {
    std::vector<double> work = rate;
    EXPECT_EQ(detail::to_phase(rate, 5.0, input),
              (detail::to_phase_in_place(work, 5.0, input), work));
    std::vector<double> again = rate;
    AllanOptions options;
    options.kind = AllanKind::totdev;
    const AllanResult copy = allan_deviation(rate, 5.0, input, options);
    const AllanResult in_place = allan_deviation_in_place(again, 5.0, input, options);
    EXPECT_EQ(copy.dev, in_place.dev);
    EXPECT_EQ(copy.ci95_high, in_place.ci95_high);
  }
}

TEST(AllanTheory, ResultDoesNotDependOnTheNumberOfThreads) {
  const std::vector<double> rate = test::white(300000, 17, 1.0);
  for (const AllanKind kind : all_allan_kinds()) {
    AllanOptions options;
    options.kind = kind;
    omp_set_num_threads(1);
    const AllanResult one = allan_deviation(rate, 1.0, InputKind::rate, options);
    omp_set_num_threads(2);
    const AllanResult two = allan_deviation(rate, 1.0, InputKind::rate, options);
    EXPECT_EQ(one.dev, two.dev) << to_string(kind);
    EXPECT_EQ(one.alpha, two.alpha) << to_string(kind);
  }
}

TEST(AllanTheory, OctaveChainsGiveTheSumOfEachFactorTakenAlone) {
  // OADEV and TOTDEV take runs of m, 2m, 4m, 8m in one loop; a factor asked
  // for alone never is. A record of three chunks, a whole octave grid (whose
  // long factors stop inside a block), and factors that chain only in part.
  std::vector<double> rate = test::white(150000, 41, 1.0);
  const std::vector<double> walk = test::random_walk(150000, 42, 0.01);
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] += walk[i];
  const std::vector<double> phase = detail::to_phase(rate, 1.0, InputKind::rate);
  const std::vector<std::vector<std::int64_t>> grids = {
      {1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384, 32768, 65536},
      {3, 6, 12, 24, 5, 7, 14, 28, 56, 112, 9000, 18000, 36000, 72000, 74000}};
  for (const AllanKind kind : {AllanKind::oadev, AllanKind::totdev}) {
    for (const auto& factors : grids) {
      const std::vector<double> together = detail::deviations_from_phase(phase, kind, factors);
      for (std::size_t k = 0; k < factors.size(); ++k) {
        const std::int64_t alone[] = {factors[k]};
        EXPECT_NEAR(together[k] / detail::deviations_from_phase(phase, kind, alone)[0], 1.0, 1e-12)
            << to_string(kind) << " m " << factors[k];
      }
    }
  }
}

TEST(AllanTheory, TotalAndTheoFamilyFollowWhiteRateNoiseTheory) {
  // White rate (FM) noise, AVAR = N^2 / tau. HTOTVAR (bias-corrected)
  // estimates it: each tau within its 99.9 % interval. Theo1 estimates it
  // too (no bias for white FM): within 10 %, its edf being about N/m. MTOTVAR
  // estimates MVAR = AVAR / 2 (SP 1065 Table 8) with Riley's bias, MTOTVAR /
  // MVAR = 0.73 for white FM (Stable32 1.53's factor; printed raw, as
  // Stable32 1.60 prints it): the ratio on the same record within 0.06 of it
  // (measured 0.77-0.78 at m = 4 .. 64, docs/validation.md); TTOTDEV is
  // tau / sqrt(3) MTOTDEV.
  constexpr double kFsHz = 10.0;
  constexpr double kN = 0.3;
  const std::vector<double> rate = test::white(1 << 16, 21, kN * std::sqrt(kFsHz));
  auto run_on = [&](AllanKind kind, const char* taus) {
    AllanOptions options;
    options.kind = kind;
    options.grid = parse_tau_grid(taus);
    return allan_deviation(rate, kFsHz, InputKind::rate, options);
  };
  const AllanResult htot = run_on(AllanKind::htotdev, "0.4,1.6,6.4");
  const AllanResult theo = run_on(AllanKind::theo1, "1.5,3,6");
  const AllanResult mtot = run_on(AllanKind::mtotdev, "0.4,1.6,6.4");
  const AllanResult ttot = run_on(AllanKind::ttotdev, "0.4,1.6,6.4");
  const AllanResult mdev = run_on(AllanKind::mdev, "0.4,1.6,6.4");
  for (std::size_t k = 0; k < 3; ++k) {
    const double truth = kN / std::sqrt(htot.tau_s[k]);
    EXPECT_EQ(htot.alpha[k], 0) << "htotdev tau " << htot.tau_s[k];
    const Interval wide = chi2_interval(htot.dev[k], htot.edf[k], 0.999);
    EXPECT_GE(truth, wide.low) << "htotdev tau " << htot.tau_s[k];
    EXPECT_LE(truth, wide.high) << "htotdev tau " << htot.tau_s[k];
    const double theo_truth = kN / std::sqrt(theo.tau_s[k]);
    const Interval theo_wide = chi2_interval(theo.dev[k], theo.edf[k], 0.999);
    EXPECT_GE(theo_truth, theo_wide.low) << "theo1 tau " << theo.tau_s[k];
    EXPECT_LE(theo_truth, theo_wide.high) << "theo1 tau " << theo.tau_s[k];
    const double ratio = mtot.dev[k] * mtot.dev[k] / (mdev.dev[k] * mdev.dev[k]);
    EXPECT_NEAR(ratio, 0.73, 0.06) << "mtotdev tau " << mtot.tau_s[k];
    EXPECT_NEAR(ttot.dev[k], mtot.dev[k] * mtot.tau_s[k] / std::sqrt(3.0), 1e-12 * ttot.dev[k]);
  }
}

TEST(AllanTheory, Theo1IntervalsCoverTheTruthNinetyFivePercentOfTheTime) {
  // Noise ID + Howe and Peppler's Theo1 edf + chi-square, end to end: 300
  // white-FM records of 4000 samples at tau = 0.75 * 200 = 150 s (the
  // record's 3.75 % Theo1 reaches far past OADEV's clusters rule).
  constexpr int kRecords = 300;
  int covered = 0;
  for (int s = 0; s < kRecords; ++s) {
    const std::vector<double> rate = test::white(4000, 3000 + s, 1.0);
    AllanOptions options;
    options.kind = AllanKind::theo1;
    options.grid = parse_tau_grid("15,150");  // a short tau, where white FM is identified
    const AllanResult r = allan_deviation(rate, 1.0, InputKind::rate, options);
    const double truth = 1.0 / std::sqrt(r.tau_s[1]);
    if (truth >= r.ci95_low[1] && truth <= r.ci95_high[1]) ++covered;
  }
  // Binomial(300, 0.95): standard deviation 3.8 records; allow 3 sigma.
  EXPECT_NEAR(covered, 0.95 * kRecords, 11.3);
}

TEST(AllanTheory, TotalAndTheoFamilyIgnoreABiasAndThreadsAndAgreeOnPhaseInput) {
  const std::vector<double> noise = test::white(20000, 22, 1.0);
  std::vector<double> biased = noise;
  for (double& v : biased) v += 1e6;
  constexpr double kFsHz = 4.0;
  std::vector<double> angle(noise.size() + 1, 0.0);
  for (std::size_t i = 0; i < noise.size(); ++i) angle[i + 1] = angle[i] + noise[i] / kFsHz;
  for (const AllanKind kind :
       {AllanKind::mtotdev, AllanKind::ttotdev, AllanKind::htotdev, AllanKind::theo1}) {
    AllanOptions options;
    options.kind = kind;
    omp_set_num_threads(1);
    const AllanResult one = allan_deviation(noise, kFsHz, InputKind::rate, options);
    omp_set_num_threads(2);
    const AllanResult two = allan_deviation(noise, kFsHz, InputKind::rate, options);
    const AllanResult bias = allan_deviation(biased, kFsHz, InputKind::rate, options);
    const AllanResult phase = allan_deviation(angle, kFsHz, InputKind::phase, options);
    ASSERT_FALSE(one.dev.empty()) << to_string(kind);
    for (std::size_t k = 0; k < one.dev.size(); ++k) {
      EXPECT_NEAR(two.dev[k] / one.dev[k], 1.0, 1e-12) << to_string(kind) << " m " << one.m[k];
      EXPECT_NEAR(bias.dev[k] / one.dev[k], 1.0, 1e-6) << to_string(kind) << " m " << one.m[k];
      EXPECT_NEAR(phase.dev[k] / one.dev[k], 1.0, 1e-9) << to_string(kind) << " m " << one.m[k];
      EXPECT_EQ(phase.n[k], one.n[k]);
    }
  }
}

TEST(AllanInput, TooShortRecordsAreDataErrorsThatSayWhatIsNeeded) {
  const std::vector<double> two = {1.0, 2.0};
  AllanOptions options;
  options.kind = AllanKind::hdev;
  options.grid = parse_tau_grid("1");
  try {
    allan_deviation(two, 1.0, InputKind::rate, options);
    FAIL() << "expected DataError";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("hdev needs at least 3 rate samples"),
              std::string::npos)
        << e.what();
  }
  const std::vector<double> small = test::white(50, 1, 1.0);
  AllanOptions octave;  // 50 samples hold fewer than 10 clusters only for m > 5
  EXPECT_EQ(allan_deviation(small, 1.0, InputKind::rate, octave).m,
            (std::vector<std::int64_t>{1, 2, 4}));
  AllanOptions too_long;
  too_long.grid = parse_tau_grid("30");
  try {
    allan_deviation(small, 1.0, InputKind::rate, too_long);
    FAIL() << "expected DataError";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("tau 30 s needs more samples"), std::string::npos)
        << e.what();
  }
  const std::vector<double> nine = test::white(9, 1, 1.0);
  try {
    allan_deviation(nine, 1.0, InputKind::rate, octave);
    FAIL() << "expected DataError";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("at least 10 clusters"), std::string::npos) << e.what();
  }
  EXPECT_THROW(allan_deviation(small, 0.0, InputKind::rate, octave), UsageError);
  EXPECT_THROW(allan_deviation(small, -5.0, InputKind::rate, octave), UsageError);
}

}  // namespace
}  // namespace foglab::stats
