// Tests of the Allan family on records with gaps (allan.h, "Gaps").
//
// Reference: a record's contiguous stretches analysed one by one. The
// pooled estimate is sum / count over the terms of every stretch; the edf
// the sum of the stretches'. The statistical test checks that edf against
// the spread of the estimate over independent records.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/edf.h"
#include "support/noise.h"

namespace foglab::stats {
namespace {

using ::testing::HasSubstr;

constexpr double kFsHz = 10.0;

// The samples of `record` without those of its stretches in `gaps`' sense:
// stretch j of the present samples.
std::vector<std::vector<double>> stretches_of(const std::vector<double>& record,
                                              const std::vector<Gap>& gaps) {
  std::vector<std::vector<double>> out;
  for (const Stretch& s : contiguous_stretches(static_cast<std::int64_t>(record.size()), gaps)) {
    out.emplace_back(record.begin() + s.begin, record.begin() + s.end);
  }
  return out;
}

TEST(AllanGaps, EveryKindPoolsTheTermsOfItsStretches) {
  const std::vector<double> rate = test::white(3000, 41, 1.0);
  const std::vector<Gap> gaps = {{1000, 5}, {1700, 300}, {1750, 2}};
  for (const AllanKind kind : all_allan_kinds()) {
    AllanOptions options;
    options.kind = kind;
    options.confidence = false;
    options.bias_correction = false;  // HTOTDEV's depends on the noise identified
    options.grid.min_clusters = 2;
    const AllanResult pooled = allan_deviation(rate, kFsHz, InputKind::rate, options, gaps);
    ASSERT_EQ(pooled.segment_points, (std::vector<std::int64_t>{1001, 701, 51, 1251}))
        << to_string(kind);
    for (std::size_t k = 0; k < pooled.m.size(); ++k) {
      double weighted = 0.0;
      std::int64_t terms = 0;
      for (const std::vector<double>& stretch : stretches_of(rate, gaps)) {
        const auto points = static_cast<std::int64_t>(stretch.size()) + 1;
        if (pooled.m[k] > max_factor(kind, points)) continue;
        AllanOptions one = options;
        one.grid.kind = TauGridKind::list;
        one.grid.taus_s = {pooled.tau_s[k]};
        const AllanResult r = allan_deviation(stretch, kFsHz, InputKind::rate, one);
        const double dev =
            kind == AllanKind::tdev ? r.dev[0] * std::sqrt(3.0) / r.tau_s[0] : r.dev[0];
        weighted += dev * dev * static_cast<double>(r.n[0]);
        terms += r.n[0];
      }
      ASSERT_GT(terms, 0);
      EXPECT_EQ(pooled.n[k], terms) << to_string(kind) << " m " << pooled.m[k];
      double expected = std::sqrt(weighted / static_cast<double>(terms));
      if (kind == AllanKind::tdev) expected *= pooled.tau_s[k] / std::sqrt(3.0);
      EXPECT_NEAR(pooled.dev[k], expected, 1e-12 * expected)
          << to_string(kind) << " m " << pooled.m[k];
    }
  }
}

TEST(AllanGaps, ABiasJumpAcrossAGapDoesNotReachTheDeviation) {
  // White rate noise whose bias jumps by 50 sigma while the logger is off:
  // across the gap the averages would see the jump; inside the stretches
  // nothing changes.
  constexpr double kSigma = 1.0;
  std::vector<double> rate = test::white(1 << 16, 42, kSigma);
  for (std::size_t i = 30000; i < rate.size(); ++i) rate[i] += 50.0 * kSigma;
  const std::vector<Gap> gaps = {{30000, 1000}};
  const AllanResult pooled = allan_deviation(rate, kFsHz, InputKind::rate, {}, gaps);
  const AllanResult naive = allan_deviation(rate, kFsHz, InputKind::rate, {});
  for (std::size_t k = 0; k < pooled.m.size(); ++k) {
    // white: ADEV = sigma / sqrt(m), inside the 95 % interval's spread
    const double theory = kSigma / std::sqrt(static_cast<double>(pooled.m[k]));
    EXPECT_GT(theory, pooled.ci95_low[k] * 0.9) << "m " << pooled.m[k];
    EXPECT_LT(theory, pooled.ci95_high[k] * 1.1) << "m " << pooled.m[k];
  }
  // the same record taken as continuous shows the jump at the long taus
  EXPECT_GT(naive.dev.back(), 5.0 * pooled.dev.back());
}

TEST(AllanGaps, EdfIsTheSumOverTheStretchesAndMatchesTheSpread) {
  // 400 independent white records of 4000 samples, each with the same three
  // gaps; the spread of the AVAR estimate at each tau against 2 AVAR^2 / edf.
  const std::vector<Gap> gaps = {{700, 50}, {2500, 10}, {3100, 400}};
  constexpr int kRecords = 400;
  AllanOptions options;
  options.grid.kind = TauGridKind::list;
  options.grid.taus_s = {0.4, 3.2, 12.8};  // m = 4, 32, 128
  std::vector<double> sum(3, 0.0), sum2(3, 0.0);
  AllanResult last;
  for (int r = 0; r < kRecords; ++r) {
    const std::vector<double> rate = test::white(4000, 1000 + r, 1.0);
    last = allan_deviation(rate, kFsHz, InputKind::rate, options, gaps);
    for (std::size_t k = 0; k < 3; ++k) {
      const double avar = last.dev[k] * last.dev[k];
      sum[k] += avar;
      sum2[k] += avar * avar;
    }
  }
  for (std::size_t k = 0; k < 3; ++k) {
    // the edf reported for white noise is the stretches' sum
    EXPECT_EQ(last.alpha[k], 0);
    const double expected_edf = pooled_edf(0, last.m[k], last.segment_points);
    EXPECT_NEAR(last.edf[k], expected_edf, 1e-9 * expected_edf);
    const double mean = sum[k] / kRecords;
    const double variance = (sum2[k] - kRecords * mean * mean) / (kRecords - 1);
    const double edf_from_spread = 2.0 * mean * mean / variance;
    // The spread's own relative error is about sqrt(2 / 399) = 7 % in the
    // variance; 25 % is > 3 sigma.
    EXPECT_NEAR(edf_from_spread / last.edf[k], 1.0, 0.25) << "m " << last.m[k];
    // and the record taken as one stretch would claim more
    EXPECT_LT(last.edf[k], greenhall_edf(0, last.m[k], 4001));
  }
}

TEST(AllanGaps, StretchesTooShortForAnyTauAreADataError) {
  const std::vector<double> rate = test::white(4, 43, 1.0);
  const std::vector<Gap> gaps = {{1, 3}, {2, 3}, {3, 3}};
  try {
    allan_deviation(rate, kFsHz, InputKind::rate, {}, gaps);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("needs at least 2 rate samples, the longest stretch between gaps has 1"));
  }
  const std::vector<Gap> outside = {{4, 1}};
  EXPECT_THROW(allan_deviation(rate, kFsHz, InputKind::rate, {}, outside), UsageError);
}

}  // namespace
}  // namespace foglab::stats
