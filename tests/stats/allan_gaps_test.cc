// Tests of the Allan family on records with gaps (allan.h, "Gaps").
//
// Reference: a record's contiguous stretches analysed one by one. The
// pooled estimate is sum / count over the terms of every stretch; the edf
// the sum of the stretches'. The statistical test checks that edf against
// the spread of the estimate over independent records. Clusters that miss
// a few samples (AllanOptions::max_missing_share): against a direct
// computation of every term on the time axis, and against the same record
// without its gaps.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
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

// The samples of `record` (the whole time axis) that remain once the
// places in `missing` (sorted, distinct, inside) are dropped, and the gaps
// that leaves.
struct WithGaps {
  std::vector<double> present;
  std::vector<Gap> gaps;
};
WithGaps drop_places(const std::vector<double>& record, const std::vector<std::int64_t>& missing) {
  WithGaps w;
  std::size_t next = 0;
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(record.size()); ++i) {
    if (next < missing.size() && missing[next] == i) {
      const auto here = static_cast<std::int64_t>(w.present.size());
      if (!w.gaps.empty() && w.gaps.back().before_sample == here) {
        ++w.gaps.back().missing_samples;
      } else {
        w.gaps.push_back({here, 1});
      }
      ++next;
      continue;
    }
    w.present.push_back(record[static_cast<std::size_t>(i)]);
  }
  return w;
}

// Every overlapping term on the time axis, directly: each cluster's mean
// over its samples present (from running sums over the axis), a term kept
// when neither cluster misses more than floor(share m) samples.
std::pair<double, std::int64_t> direct_avar(const std::vector<double>& record,
                                            const std::vector<bool>& present, std::int64_t m,
                                            double share,
                                            std::pair<std::int64_t, std::int64_t> split = {0, 0}) {
  const auto allowed = static_cast<std::int64_t>(std::floor(share * static_cast<double>(m)));
  const std::size_t n = record.size();
  std::vector<double> sums(n + 1, 0.0);
  std::vector<std::int64_t> counts(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    sums[i + 1] = sums[i] + (present[i] ? record[i] : 0.0);
    counts[i + 1] = counts[i] + (present[i] ? 1 : 0);
  }
  double sum = 0.0;
  std::int64_t terms = 0;
  for (std::size_t i = 0; i + 2 * static_cast<std::size_t>(m) <= n; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(m), k = j + static_cast<std::size_t>(m);
    const std::int64_t a = counts[j] - counts[i], b = counts[k] - counts[j];
    if (m - a > allowed || m - b > allowed) continue;
    // no term touches the places [split.first, split.second)
    if (static_cast<std::int64_t>(i) < split.second && static_cast<std::int64_t>(k) > split.first) {
      continue;
    }
    const double d =
        (sums[k] - sums[j]) / static_cast<double>(b) - (sums[j] - sums[i]) / static_cast<double>(a);
    sum += 0.5 * d * d;
    ++terms;
  }
  return {terms > 0 ? sum / static_cast<double>(terms) : 0.0, terms};
}

TEST(AllanGaps, ClustersMissingAFewSamplesAreEveryTermTheirShareAllows) {
  // 4000 places, gaps of 1, 1, 3, 30 and 2 samples (one at a stretch's very
  // start), a share of 10 %: clusters of 10 samples may miss one.
  const std::vector<double> record = test::white(4000, 47, 1.0);
  std::vector<std::int64_t> missing = {5, 640, 1500, 1501, 1502, 3999 - 1};
  for (std::int64_t i = 2200; i < 2230; ++i) missing.push_back(i);
  missing.push_back(3000), missing.push_back(3001);
  std::sort(missing.begin(), missing.end());
  const WithGaps w = drop_places(record, missing);
  std::vector<bool> present(record.size(), true);
  for (const std::int64_t i : missing) present[static_cast<std::size_t>(i)] = false;
  AllanOptions options;
  options.grid.kind = TauGridKind::all;
  options.grid.min_clusters = 3;
  options.max_missing_share = 0.1;
  const AllanResult r = allan_deviation(w.present, kFsHz, InputKind::rate, options, w.gaps);
  ASSERT_GE(r.m.size(), 100u);
  ASSERT_EQ(r.term_share.size(), r.m.size());
  ASSERT_EQ(r.segment_points, (std::vector<std::int64_t>{4001}));
  for (std::size_t k = 0; k < r.m.size(); ++k) {
    SCOPED_TRACE(r.m[k]);
    const auto [avar, terms] = direct_avar(record, present, r.m[k], 0.1);
    EXPECT_EQ(r.n[k], terms);
    EXPECT_NEAR(r.dev[k] * r.dev[k], avar, 1e-10 * avar);
    EXPECT_DOUBLE_EQ(r.term_share[k], static_cast<double>(terms) / (4001.0 - 2.0 * r.m[k]));
    if (r.m[k] < 10) {
      EXPECT_EQ(r.gap_spanning_terms[k], 0);  // none may miss a sample
    }
  }
  EXPECT_GT(r.gap_spanning_terms.back(), 0);
  // Below 1 / share the result is the pooled one, edf included.
  AllanOptions pooled_options = options;
  pooled_options.max_missing_share = 0.0;
  const AllanResult pooled =
      allan_deviation(w.present, kFsHz, InputKind::rate, pooled_options, w.gaps);
  for (std::size_t k = 0; k < pooled.m.size() && pooled.m[k] < 10; ++k) {
    EXPECT_EQ(r.m[k], pooled.m[k]);
    EXPECT_EQ(r.n[k], pooled.n[k]);
    EXPECT_DOUBLE_EQ(r.dev[k], pooled.dev[k]);
    EXPECT_DOUBLE_EQ(r.edf[k], pooled.edf[k]);
  }
  EXPECT_TRUE(pooled.term_share.empty());
  EXPECT_TRUE(pooled.gap_spanning_terms.empty());
}

TEST(AllanGaps, AGapTooLongToSpanOrAskedForStillSplitsTheRecord) {
  // The record above with the 30-sample gap at 2200 either asked to split
  // the record (a bias jump across it) or, with a share of 1 %, longer than
  // a term at the longest tau may span (2 x 13 samples at m = 1333): no
  // term touches it, and the parts are the stretches joined across the
  // other gaps.
  const std::vector<double> record = test::white(4000, 47, 1.0);
  std::vector<std::int64_t> missing = {5, 640, 1500, 1501, 1502, 3998, 3000, 3001};
  for (std::int64_t i = 2200; i < 2230; ++i) missing.push_back(i);
  std::sort(missing.begin(), missing.end());
  const WithGaps w = drop_places(record, missing);
  std::vector<bool> present(record.size(), true);
  for (const std::int64_t i : missing) present[static_cast<std::size_t>(i)] = false;
  const auto at =
      std::ranges::find_if(w.gaps, [](const Gap& g) { return g.missing_samples == 30; });
  ASSERT_NE(at, w.gaps.end());
  for (const double share : {0.1, 0.01}) {
    SCOPED_TRACE(share);
    AllanOptions options;
    options.grid.kind = TauGridKind::all;
    options.grid.min_clusters = 3;
    options.max_missing_share = share;
    if (share == 0.1) options.unbridged_gaps = {at->before_sample};
    const AllanResult r = allan_deviation(w.present, kFsHz, InputKind::rate, options, w.gaps);
    // the parts: places 0-2199 and 2230-3999, in angle points
    EXPECT_EQ(r.segment_points, (std::vector<std::int64_t>{2201, 1771}));
    for (std::size_t k = 0; k < r.m.size(); ++k) {
      SCOPED_TRACE(r.m[k]);
      const auto [avar, terms] = direct_avar(record, present, r.m[k], share, {2200, 2230});
      EXPECT_EQ(r.n[k], terms);
      EXPECT_NEAR(r.dev[k] * r.dev[k], avar, 1e-10 * avar);
      const double model_terms = std::max(0.0, 2201.0 - 2.0 * static_cast<double>(r.m[k])) +
                                 std::max(0.0, 1771.0 - 2.0 * static_cast<double>(r.m[k]));
      EXPECT_DOUBLE_EQ(r.term_share[k], static_cast<double>(terms) / model_terms);
    }
  }
}

TEST(AllanGaps, ARecordThatLosesASampleHereAndThereKeepsItsLongTaus) {
  // White noise and a random walk, 2^19 samples at 10 Hz (14.6 h), one
  // sample in 1000 lost at random places: no stretch is long, and the
  // pooled taus end early; with clusters that may miss 1 % of their
  // samples the deviation, its terms and its edf are those of the record
  // without the losses.
  constexpr std::size_t kN = std::size_t{1} << 19;
  std::vector<double> record = test::white(kN, 53, 1.0);
  const std::vector<double> walk = test::random_walk(kN, 54, 0.003);
  for (std::size_t i = 0; i < kN; ++i) record[i] += walk[i];
  std::mt19937_64 rng(55);
  std::uniform_int_distribution<std::int64_t> place(1, static_cast<std::int64_t>(kN) - 2);
  std::vector<std::int64_t> missing;
  for (std::size_t i = 0; i < kN / 1000; ++i) missing.push_back(place(rng));
  std::sort(missing.begin(), missing.end());
  missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
  const WithGaps w = drop_places(record, missing);

  const AllanResult whole = allan_deviation(record, kFsHz, InputKind::rate);
  AllanOptions pooled_options;
  const AllanResult pooled =
      allan_deviation(w.present, kFsHz, InputKind::rate, pooled_options, w.gaps);
  AllanOptions options;
  options.max_missing_share = 0.01;
  const AllanResult r = allan_deviation(w.present, kFsHz, InputKind::rate, options, w.gaps);

  // stretches of 1000 samples on average, the longest about 8000: four
  // octaves short of the whole record's 3277 s
  EXPECT_LE(pooled.tau_s.back(), whole.tau_s.back() / 16);
  ASSERT_EQ(r.m, whole.m);
  for (std::size_t k = 0; k < r.m.size(); ++k) {
    SCOPED_TRACE(r.m[k]);
    // The same noise with a few of its terms missing: at m < 100 the terms
    // that touch a gap, 2m + 1 of every 1000 (a share f of 0.3-20 %), whose
    // loss moves the estimate by about sqrt(f) of its own sd, the 95 %
    // half-width / 1.96 (0.4 % at m = 1, 40 % at the last tau); beyond, the
    // terms are all there, their clusters a sample or so short. Within
    // 0.3 half-widths: 4.5 sd of the first kind.
    const double half_width = whole.ci95_high[k] / whole.dev[k] - 1.0;
    EXPECT_NEAR(r.dev[k] / whole.dev[k], 1.0, 0.3 * half_width);
    if (r.gap_spanning_terms[k] > 0) {
      EXPECT_GT(r.term_share[k], 0.97);
      // the noise is identified on other samples (the longest stretch, or
      // the record with the missing samples at its mean): where it is
      // called the same, the edf is the whole record's for 97-100 % of its
      // terms
      if (r.alpha[k] == whole.alpha[k]) {
        EXPECT_NEAR(r.edf[k] / whole.edf[k], 1.0, 0.03);
      }
    }
  }
  EXPECT_GT(r.gap_spanning_terms.back(), 0);
}

TEST(AllanGaps, AShareOutsideItsRangeIsAUsageError) {
  const std::vector<double> rate = test::white(1000, 59, 1.0);
  const std::vector<Gap> gaps = {{500, 2}};
  AllanOptions options;
  options.max_missing_share = 0.2;
  EXPECT_THROW(allan_deviation(rate, kFsHz, InputKind::rate, options, gaps), UsageError);
  options.max_missing_share = -0.01;
  EXPECT_THROW(allan_deviation(rate, kFsHz, InputKind::rate, options, gaps), UsageError);
}

}  // namespace
}  // namespace foglab::stats
