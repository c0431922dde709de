// Tests of the Welch PSD and its log-frequency smoothing.
//
// The statistical tests use fixed seeds (std::mt19937_64) and tolerances that
// follow from the number of averaged values, stated at each test, so that a
// wrong scaling (a factor 2 for sidedness, fs, sum(w^2) instead of
// (sum w)^2, ...) fails by a wide margin while the seed could change freely.

#include "foglab/stats/psd.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "support/expect.h"

namespace foglab::stats {
namespace {

using ::testing::HasSubstr;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> white_noise(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  return x;
}

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double variance_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return s / static_cast<double>(v.size() - 1);
}

TEST(WelchPsd, FillsEveryFieldWithTheDefaultSegment) {
  // N = 1000: the largest power of two <= N/4 = 250 is 128; hop 64;
  // segments start at 0, 64, ..., 832 (832 + 128 <= 1000 < 896 + 128): 14.
  const auto x = white_noise(1000, 1.0, 1);
  const PsdResult r = welch_psd(x, 50.0);
  EXPECT_EQ(r.segment_length, 128u);
  EXPECT_EQ(r.segments, 14u);
  EXPECT_DOUBLE_EQ(r.sample_rate_hz, 50.0);
  EXPECT_DOUBLE_EQ(r.resolution_hz, 50.0 / 128.0);
  ASSERT_EQ(r.frequency_hz.size(), 64u);
  ASSERT_EQ(r.psd.size(), 64u);
  ASSERT_EQ(r.sqrt_psd.size(), 64u);
  EXPECT_DOUBLE_EQ(r.frequency_hz.front(), 50.0 / 128.0);  // DC dropped
  EXPECT_DOUBLE_EQ(r.frequency_hz.back(), 25.0);           // Nyquist kept
  for (std::size_t k = 0; k < r.psd.size(); ++k) {
    EXPECT_GT(r.psd[k], 0.0);
    EXPECT_DOUBLE_EQ(r.sqrt_psd[k], std::sqrt(r.psd[k]));
  }
}

TEST(WelchPsd, DefaultSegmentIsAtLeast16AndAtMostN) {
  EXPECT_EQ(welch_psd(white_noise(16, 1.0, 2), 1.0).segment_length, 16u);
  EXPECT_EQ(welch_psd(white_noise(16, 1.0, 2), 1.0).segments, 1u);
  EXPECT_EQ(welch_psd(white_noise(100, 1.0, 2), 1.0).segment_length, 16u);
  EXPECT_EQ(welch_psd(white_noise(128, 1.0, 2), 1.0).segment_length, 32u);
  EXPECT_EQ(welch_psd(white_noise(127, 1.0, 2), 1.0).segment_length, 16u);
}

TEST(WelchPsd, HopIsRoundedOverlapAndOddLengthsWork) {
  const auto x = white_noise(10000, 1.0, 3);
  // No overlap: hop = L, floor(10000 / 1000) = 10 segments.
  EXPECT_EQ(welch_psd(x, 1.0, {.segment_length = 1000, .overlap = 0.0}).segments, 10u);
  // Overlap 0.75 of 1001: hop = round(250.25) = 250; (10000 - 1001) / 250 + 1 = 36.
  const PsdResult r = welch_psd(x, 2.0, {.segment_length = 1001, .overlap = 0.75});
  EXPECT_EQ(r.segments, 36u);
  ASSERT_EQ(r.frequency_hz.size(), 500u);  // k = 1 .. floor(1001 / 2)
  EXPECT_DOUBLE_EQ(r.frequency_hz.back(), 500.0 * 2.0 / 1001.0);
  // Overlap at its limit with a short segment: hop is at least one sample.
  EXPECT_EQ(welch_psd(x, 1.0, {.segment_length = 16, .overlap = 0.95}).segments, 10000u - 15u);
}

// (a) White noise of standard deviation sigma at rate fs is flat at the
// two-sided level sigma^2 / fs. The mean over all K = 512 bins averages
// K x S periodogram values (S = 511 segments); with the Hann window adjacent
// bins are correlated (power correlation 4/9, next 1/36) and 50 % overlap
// adds 6 % variance, so the relative standard deviation of the mean is
// sqrt(1.06 * 1.94 / (K S)) = 0.28 % (the same as sqrt(2 / N) for the sample
// variance, as Parseval demands). We allow 1.5 % (about 5 sigma); a one-sided
// (doubled) or wrongly fs-scaled estimate misses by 100 % or more.
TEST(WelchPsd, WhiteNoiseIsFlatAtVarianceOverSampleRate) {
  constexpr std::size_t kSamples = std::size_t{1} << 18;
  constexpr double kSigma = 3.0;
  for (const double fs : {1.0, 400.0}) {
    SCOPED_TRACE(fs);
    const auto x = white_noise(kSamples, kSigma, 11);
    const PsdResult r = welch_psd(x, fs, {.segment_length = 1024});
    ASSERT_EQ(r.segments, 511u);
    const double expected = kSigma * kSigma / fs;
    EXPECT_NEAR(mean_of(r.psd) / expected, 1.0, 0.015);
    // Flat: the low and high halves agree within the same statistics (x sqrt 2).
    const std::size_t half = r.psd.size() / 2;
    const std::vector<double> low(r.psd.begin(), r.psd.begin() + half);
    const std::vector<double> high(r.psd.begin() + half, r.psd.end());
    EXPECT_NEAR(mean_of(low) / mean_of(high), 1.0, 0.025);
    // Each bin is a mean of S = 511 chi^2_2 / 2 values: relative sd ~ 4.5 %.
    for (const double p : r.psd) EXPECT_NEAR(p / expected, 1.0, 0.3);
  }
}

// (b) Parseval: 2 sum(psd) df recovers the variance of a coloured (AR(1),
// a = 0.5) record. The only losses are the dropped DC bin and each segment's
// mean, of order S(0) / (L var) = 3 / 1024; the Nyquist bin is counted twice
// (1 / L). Allow 2 %.
TEST(WelchPsd, ParsevalRecoversTheVariance) {
  const auto e = white_noise(std::size_t{1} << 17, 1.5, 21);
  std::vector<double> x(e.size());
  double state = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) x[i] = state = 0.5 * state + e[i] + 7.0;
  const PsdResult r = welch_psd(x, 250.0, {.segment_length = 1024});
  double sum = 0.0;
  for (const double p : r.psd) sum += p;
  EXPECT_NEAR(2.0 * sum * r.resolution_hz / variance_of(x), 1.0, 0.02);
}

// (c) A sinusoid A sin(2 pi f0 t + phi) at a bin-centred f0 = k0 fs / L:
// the Hann window spreads it over bins k0 - 1 .. k0 + 1 (powers 1/4, 1, 1/4
// of the peak), the peak is at f0, and the power of the positive-frequency
// line doubled is A^2 / 2. Noise is 1e-3 of A, so 1 % is generous.
TEST(WelchPsd, BinCentredSinusoidHasItsPowerAtItsFrequency) {
  constexpr double kFs = 1024.0;
  constexpr std::size_t kLength = 1024;
  constexpr double kF0 = 100.0;  // bin 100
  constexpr double kAmplitude = 3.0;
  auto x = white_noise(std::size_t{1} << 15, 1e-3 * kAmplitude, 31);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] +=
        kAmplitude * std::sin(2.0 * std::numbers::pi * kF0 * static_cast<double>(i) / kFs + 0.3);
  }
  const PsdResult r = welch_psd(x, kFs, {.segment_length = kLength});
  std::size_t peak = 0;
  for (std::size_t k = 0; k < r.psd.size(); ++k) {
    if (r.psd[k] > r.psd[peak]) peak = k;
  }
  EXPECT_DOUBLE_EQ(r.frequency_hz[peak], kF0);
  EXPECT_NEAR(r.psd[peak - 1] / r.psd[peak], 0.25, 0.01);
  EXPECT_NEAR(r.psd[peak + 1] / r.psd[peak], 0.25, 0.01);
  double power = 0.0;
  for (std::size_t k = peak - 3; k <= peak + 3; ++k) power += r.psd[k];
  EXPECT_NEAR(2.0 * power * r.resolution_hz / (kAmplitude * kAmplitude / 2.0), 1.0, 0.01);
}

// (d) A Wiener rate random walk x_n = x_{n-1} + K sqrt(dt) w_n has the
// two-sided PSD K^2 dt^2 / (4 sin^2(pi f dt)) ~ K^2 / (2 pi f)^2 for
// f << fs. Over the decade 0.5 .. 5 Hz at fs = 100 Hz (bins 21 .. 205 of
// L = 4096, S = 127 segments) each bin has a relative sd of about 9 %; the
// least-squares log-log slope over 185 bins is known to about +-0.02, and the
// mean level ratio to about 1 %. Required: slope -2 +- 0.15, level +-20 %.
TEST(WelchPsd, WienerRateRandomWalkFollowsMinusTwoSlope) {
  constexpr double kFs = 100.0;
  constexpr double kK = 0.4;  // [unit/sqrt(s)]
  const double dt = 1.0 / kFs;
  const auto w = white_noise(std::size_t{1} << 18, 1.0, 41);
  std::vector<double> x(w.size());
  double level = 5.0;
  for (std::size_t i = 0; i < w.size(); ++i) x[i] = level += kK * std::sqrt(dt) * w[i];
  const PsdResult r = welch_psd(x, kFs, {.segment_length = 4096});
  ASSERT_EQ(r.segments, 127u);

  double sx = 0, sy = 0, sxx = 0, sxy = 0, ratio = 0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < r.psd.size(); ++k) {
    const double f = r.frequency_hz[k];
    if (f < 0.5 || f > 5.0) continue;
    const double lx = std::log10(f);
    const double ly = std::log10(r.psd[k]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    const double model = kK * kK / std::pow(2.0 * std::numbers::pi * f, 2);
    ratio += r.psd[k] / model;
    ++count;
  }
  ASSERT_GT(count, 150u);
  const double n = static_cast<double>(count);
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(slope, -2.0, 0.15);
  EXPECT_NEAR(ratio / n, 1.0, 0.2);
}

// (e) Smoothing of white noise (fs = 1000 Hz, L = 4096, S = 127): the raw
// bins scatter by about 9 %; the smoothed points average from ~10 (at 10 Hz)
// to ~500 (at 500 Hz) raw bins, so their scatter is several times smaller.
TEST(LogSmooth, SmoothedWhiteNoiseIsFlatWithBinsPerDecadePoints) {
  constexpr double kFs = 1000.0;
  constexpr double kSigma = 2.0;
  const auto x = white_noise(std::size_t{1} << 18, kSigma, 51);
  const PsdResult raw = welch_psd(x, kFs, {.segment_length = 4096});
  const PsdResult smooth = log_smooth(raw, 10.0);

  EXPECT_EQ(smooth.segment_length, raw.segment_length);
  EXPECT_EQ(smooth.segments, raw.segments);
  EXPECT_DOUBLE_EQ(smooth.resolution_hz, raw.resolution_hz);
  EXPECT_DOUBLE_EQ(smooth.sample_rate_hz, raw.sample_rate_hz);
  ASSERT_EQ(smooth.psd.size(), smooth.frequency_hz.size());
  ASSERT_EQ(smooth.sqrt_psd.size(), smooth.frequency_hz.size());
  for (std::size_t i = 1; i < smooth.frequency_hz.size(); ++i) {
    EXPECT_GT(smooth.frequency_hz[i], smooth.frequency_hz[i - 1]);
  }

  // Every bin of [10, 100) Hz is populated (raw spacing 0.24 Hz < 2.6 Hz).
  std::size_t in_decade = 0;
  for (const double f : smooth.frequency_hz) in_decade += (f >= 10.0 && f < 100.0);
  EXPECT_EQ(in_decade, 10u);

  const double expected = kSigma * kSigma / kFs;
  const auto rms_deviation = [expected](const PsdResult& r) {
    double s = 0.0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < r.psd.size(); ++k) {
      if (r.frequency_hz[k] < 10.0) continue;
      s += std::pow(r.psd[k] / expected - 1.0, 2);
      ++count;
    }
    return std::sqrt(s / static_cast<double>(count));
  };
  const double raw_scatter = rms_deviation(raw);
  const double smooth_scatter = rms_deviation(smooth);
  EXPECT_GT(raw_scatter, 0.05);
  EXPECT_LT(smooth_scatter, raw_scatter / 3.0);
  for (std::size_t k = 0; k < smooth.psd.size(); ++k) {
    EXPECT_DOUBLE_EQ(smooth.sqrt_psd[k], std::sqrt(smooth.psd[k]));
    if (smooth.frequency_hz[k] >= 10.0) {
      EXPECT_NEAR(smooth.psd[k] / expected, 1.0, 0.2);
    }
  }
}

TEST(LogSmooth, AveragesDecadeAlignedBinsAtGeometricMeanFrequency) {
  PsdResult in;
  for (int f = 1; f <= 100; ++f) {
    in.frequency_hz.push_back(f);
    in.psd.push_back(f);
    in.sqrt_psd.push_back(std::sqrt(f));
  }
  const PsdResult out = log_smooth(in, 1.0);
  ASSERT_EQ(out.frequency_hz.size(), 3u);  // [1, 10), [10, 100), [100, 1000)
  EXPECT_DOUBLE_EQ(out.psd[0], 5.0);
  EXPECT_DOUBLE_EQ(out.psd[1], 54.5);
  EXPECT_DOUBLE_EQ(out.psd[2], 100.0);
  EXPECT_NEAR(out.frequency_hz[0], std::pow(362880.0, 1.0 / 9.0), 1e-12);  // (9!)^(1/9)
  EXPECT_NEAR(out.frequency_hz[2], 100.0, 1e-12);
  EXPECT_DOUBLE_EQ(out.sqrt_psd[1], std::sqrt(54.5));

  // Two bins per decade: edges 1, 3.162, 10, 31.62, 100.
  const PsdResult half = log_smooth(in, 2.0);
  ASSERT_EQ(half.psd.size(), 5u);
  EXPECT_DOUBLE_EQ(half.psd[0], 2.0);    // 1, 2, 3
  EXPECT_DOUBLE_EQ(half.psd[1], 6.5);    // 4 .. 9
  EXPECT_DOUBLE_EQ(half.psd[2], 20.5);   // 10 .. 31
  EXPECT_DOUBLE_EQ(half.psd[3], 65.5);   // 32 .. 99
  EXPECT_DOUBLE_EQ(half.psd[4], 100.0);  // 100
}

// (f) Bad parameters name the parameter and the value.
TEST(WelchPsd, RejectsBadParametersNamingThem) {
  const auto x = white_noise(100, 1.0, 61);
  for (const double fs : {0.0, -1.0, kNan, kInf}) {
    const std::string m = test::message_of<UsageError>([&] { welch_psd(x, fs); });
    EXPECT_THAT(m, HasSubstr("sample_rate_hz"));
    EXPECT_THAT(m, HasSubstr(fmt::format("got {}", fs)));
  }
  // Too few samples is the data's fault: a short record, or one whose gaps
  // leave no 16 samples in a row.
  const auto short_record = white_noise(15, 1.0, 62);
  EXPECT_THAT(test::message_of<DataError>([&] { welch_psd(short_record, 1.0); }),
              HasSubstr("at least 16 rate samples in a row, the record has 15"));
  const std::vector<Gap> every_tenth = {{10, 1}, {20, 1}, {30, 1}, {40, 1}, {50, 1},
                                        {60, 1}, {70, 1}, {80, 1}, {90, 1}};
  EXPECT_THAT(test::message_of<DataError>([&] { welch_psd(x, 1.0, {}, every_tenth); }),
              HasSubstr("the longest stretch between gaps has 10"));
  EXPECT_THAT(test::message_of<UsageError>([&] { welch_psd(x, 1.0, {.segment_length = 8}); }),
              HasSubstr("segment_length must be 0 (automatic) or in [16, 100]"));
  EXPECT_THAT(test::message_of<UsageError>([&] { welch_psd(x, 1.0, {.segment_length = 8}); }),
              HasSubstr("got 8"));
  EXPECT_THAT(test::message_of<UsageError>([&] { welch_psd(x, 1.0, {.segment_length = 101}); }),
              HasSubstr("got 101"));
  EXPECT_THAT(test::message_of<UsageError>([&] { welch_psd(x, 1.0, {.overlap = 1.0}); }),
              HasSubstr("overlap must be in [0, 0.95], got 1"));
  EXPECT_THAT(test::message_of<UsageError>([&] { welch_psd(x, 1.0, {.overlap = -0.25}); }),
              HasSubstr("overlap must be in [0, 0.95], got -0.25"));
  EXPECT_THAT(test::message_of<UsageError>([&] { welch_psd(x, 1.0, {.overlap = kNan}); }),
              HasSubstr("overlap"));

  const PsdResult r = welch_psd(x, 1.0);
  EXPECT_THAT(test::message_of<UsageError>([&] { log_smooth(r, 0.0); }),
              HasSubstr("bins_per_decade must be positive and finite, got 0"));
  EXPECT_THAT(test::message_of<UsageError>([&] { log_smooth(r, -3.0); }), HasSubstr("got -3"));
  EXPECT_THAT(test::message_of<UsageError>([&] { log_smooth(r, kInf); }),
              HasSubstr("bins_per_decade"));
  PsdResult bad = r;
  bad.frequency_hz[0] = 0.0;
  EXPECT_THAT(test::message_of<UsageError>([&] { log_smooth(bad, 10.0); }),
              HasSubstr("frequency_hz[0] must be positive"));
}

// (g) The result is bitwise the same with 1 and 2 threads, for short segments
// (many segments per chunk) and long ones (one or a few per chunk).
TEST(WelchPsd, ResultDoesNotDependOnThreadCount) {
  const auto x = white_noise(std::size_t{1} << 18, 1.0, 71);
  const int saved = omp_get_max_threads();
  for (const std::size_t length : {std::size_t{64}, std::size_t{16384}, std::size_t{65536}}) {
    SCOPED_TRACE(length);
    omp_set_num_threads(1);
    const PsdResult one = welch_psd(x, 10.0, {.segment_length = length});
    omp_set_num_threads(2);
    const PsdResult two = welch_psd(x, 10.0, {.segment_length = length});
    EXPECT_EQ(one.segments, two.segments);
    EXPECT_EQ(one.psd, two.psd);  // exact comparison of every bin
  }
  omp_set_num_threads(saved);
}

TEST(WelchGaps, SegmentsInsideTheStretchesAreAveraged) {
  // The PSD of a record with gaps is the segment-weighted mean of its
  // stretches' PSDs with the same segment length; segments never span a gap.
  const std::vector<double> rate = white_noise(10000, 2.0, 77);
  const std::vector<Gap> gaps = {{3000, 10}, {3100, 5}, {9000, 1000}};
  WelchOptions options;
  options.segment_length = 256;
  const PsdResult pooled = welch_psd(rate, 10.0, options, gaps);
  std::vector<double> weighted(pooled.psd.size(), 0.0);
  std::size_t segments = 0;
  for (const Stretch& s : contiguous_stretches(10000, gaps)) {
    if (s.size() < 256) continue;  // the stretch of 100 samples holds no segment
    const std::span<const double> part(rate.data() + s.begin, static_cast<std::size_t>(s.size()));
    const PsdResult r = welch_psd(part, 10.0, options);
    for (std::size_t k = 0; k < r.psd.size(); ++k) weighted[k] += r.psd[k] * r.segments;
    segments += r.segments;
  }
  EXPECT_EQ(pooled.segments, segments);
  for (std::size_t k = 0; k < weighted.size(); ++k) {
    EXPECT_NEAR(pooled.psd[k], weighted[k] / segments, 1e-12 * pooled.psd[k]) << "bin " << k;
  }
  // the automatic segment follows the longest stretch (5900 samples): 1024
  EXPECT_EQ(welch_psd(rate, 10.0, {}, gaps).segment_length, 1024u);
}

}  // namespace
}  // namespace foglab::stats
