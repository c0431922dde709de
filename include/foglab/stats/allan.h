// foglab — the Allan family of stability statistics, with confidence intervals.
//
// Definitions (NIST SP 1065, W. J. Riley, "Handbook of Frequency Stability
// Analysis", 2008, section 5.2; IEEE Std 952-1997 Annex C for gyros). With
// phase (angle) samples x_i, i = 0 .. N-1, sample interval tau0, averaging
// factor m and tau = m tau0:
//
//   ADEV   non-overlapping Allan deviation: second differences
//          x_{i+2m} - 2 x_{i+m} + x_i at i = 0, m, 2m, ...,
//          AVAR = sum / (2 tau^2 n),  n = floor((N-1)/m) - 1            (SP1065 eq. 7)
//   OADEV  overlapping Allan deviation: the same at every i,
//          n = N - 2m                                                   (eq. 11)
//   MDEV   modified Allan deviation: second differences of m-sample phase
//          averages, MVAR = sum_j (sum_{i=j}^{j+m-1} d_i)^2 / (2 m^2 tau^2 n),
//          n = N - 3m + 1                                               (eq. 15)
//   TDEV   time deviation, tau/sqrt(3) MDEV, in [deg/h * s]              (eq. 17)
//   HDEV   non-overlapping Hadamard deviation: third differences
//          x_{i+3m} - 3 x_{i+2m} + 3 x_{i+m} - x_i at i = 0, m, ...,
//          HVAR = sum / (6 tau^2 n), n = floor((N-1)/m) - 2             (eq. 18)
//   OHDEV  overlapping Hadamard deviation, n = N - 3m                   (eq. 20)
//   TOTDEV total deviation: second differences at i = 1 .. N-2 of the record
//          extended at both ends by reflection, x*_{-j} = 2 x_0 - x_j and
//          x*_{N-1+j} = 2 x_{N-1} - x_{N-1-j};
//          TOTVAR = sum / (2 tau^2 (N - 2))                              (eq. 25)
//   MTOTDEV modified total deviation: for each of the n = N - 3m + 1
//          subsequences of 3m points, remove its frequency offset (the
//          difference of the means of its two halves over their distance),
//          extend it to 9m points by uninverted even reflection on both
//          sides, and average the squared second differences of m-point
//          phase averages at its 6m start points;
//          MTOTVAR = sum / (2 m^2 tau^2 6m n)                              (eq. 27)
//   TTOTDEV time total deviation, tau/sqrt(3) MTOTDEV, in [deg/h * s]       (eq. 28)
//   HTOTDEV Hadamard total deviation: the same subsequence procedure on the
//          rate (frequency) record y_k = x_{k+1} - x_k with second
//          differences of m-sample rate averages, HTOTVAR = sum / (6 * 6m n),
//          n = N - 3m; at m = 1 it is OHDEV (Riley's choice, as Stable32)  (eq. 29)
//   THEO1  Theo1 at even m (10 <= m <= N - 1), tau = 0.75 m tau0:
//          sum_{i=0}^{N-m-1} sum_{d=0}^{m/2-1} (x_i - x_{i-d+m/2} + x_{i+m}
//          - x_{i+d+m/2})^2 / (m/2 - d) / (0.75 (N - m) (m tau0)^2); "n" is
//          the number of terms, (N - m) m / 2, as Stable32 prints it        (eq. 30)
//
// Cost per tau: O(N) for every kind but THEO1 (MTOTDEV/HTOTDEV by the
// closed-form sums of src/stats/total_kernel.h), O(N log^2 m) for THEO1
// (FFT correlations, src/stats/theo1_kernel.h).
//
// A gyro RATE record y_k [deg/h] (k = 0 .. N-2) is the analogue of
// fractional frequency: foglab integrates it to an angle record after
// removing its mean with a compensated sum (the statistics are blind to a
// constant rate, and removing it first keeps 10^9-sample records with a large
// bias exact). An ANGLE record is the analogue of phase data.
//
// Slopes of ADEV/OADEV on log-log axes for the IEEE-952 gyro terms: angle
// quantisation Q tau^-1, angle random walk N tau^-1/2, bias instability
// (flicker) B tau^0, rate random walk K tau^+1/2, rate ramp R tau^+1.
//
// Confidence intervals: the power-law noise type alpha (S_y(f) ~ f^alpha) is
// identified at each tau (noise_id.h), the equivalent degrees of freedom come
// from Greenhall's general algorithm (edf.h; SP1065 Table 12 for TOTDEV),
// and the interval from the chi-square distribution (confidence.h,
// SP1065 eq. 45). Valid tau range: the default grids keep at least 10
// clusters, floor((N-1)/m) >= 10, as the lab manual asks (L_m >= 10).
//
// Gaps (core/gaps.h): a record with missing samples is analysed as its
// contiguous stretches. Each statistic pools the terms that lie wholly
// inside one stretch, sum / count over all of them (terms spanning a gap are
// left out, as Stable32 skips gap terms; nothing is interpolated); the noise
// type comes from the longest stretch, and the edf is the sum of the
// stretches' edf (their terms are independent for white and random-walk
// noise, nearly so for the others).
//
// Clusters that miss a few samples (AllanOptions::max_missing_share, OADEV
// of a rate record): a record that loses a sample here and there (a ROS
// bag, a serial link) has no long stretch, and pooling alone ends its taus
// where its longest stretch does. With a share s > 0 a term spanning gaps
// is kept when each of its two clusters misses at most s m of its m
// samples, each cluster's mean taken over the samples it has (nothing is
// interpolated). Only gaps that a term at the whole time axis's longest
// tau could span (2 s m samples) are bridged; longer ones, and those in
// AllanOptions::unbridged_gaps, still split the record, and with none
// bridged nothing changes. Otherwise the grid runs over the whole time
// axis, a tau is kept while its terms fill (min_clusters - 2) m,
// `segment_points` holds the parts the bridged gaps join (their places
// counted), `term_share` each tau's terms over theirs, and where terms
// spanning a gap enter, the edf is the parts' times that share and the
// noise type the longest stretch's, or where that is too short, that of
// the longest part with its missing samples at the mean (for the
// identification only). At m < 1/s no sample may be missing: the terms
// are the pooled ones.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/gaps.h"
#include "foglab/core/units.h"
#include "foglab/stats/noise_id.h"
#include "foglab/stats/tau_grid.h"

namespace foglab::stats {

/// Which statistic to compute.
enum class AllanKind {
  adev,
  oadev,
  mdev,
  hdev,
  ohdev,
  tdev,
  totdev,  // the classic seven
  mtotdev,
  ttotdev,
  htotdev,
  theo1  // the total and Theo family
};

/// "adev", "oadev", "mdev", "hdev", "ohdev", "tdev", "totdev", "mtotdev",
/// "ttotdev", "htotdev", "theo1".
std::string_view to_string(AllanKind kind);
/// Parses the names above; throws UsageError listing them otherwise.
AllanKind allan_kind_from_string(std::string_view text);
/// Every kind, in the order above.
std::span<const AllanKind> all_allan_kinds();
/// TDEV and TTOTDEV: time deviations, tau / sqrt(3) times their frequency
/// deviation, in the rate's unit times s.
bool is_time_deviation(AllanKind kind);

/// The rules that turn identify_noise()'s calls into each tau's alpha.
enum class NoiseRules {
  /// Stable32's rules (noise_id.h) plus the physical constraint that phase
  /// noise cannot dominate beyond the shortest tau where frequency noise
  /// does: a later PM call is taken as white FM ("fm_floor"). Keeps the
  /// intervals of white FM honest where B1 and lag-1 misfire.
  foglab,
  /// Stable32's rules alone: its alpha column, tau for tau.
  stable32,
};

/// "foglab", "stable32".
std::string_view to_string(NoiseRules rules);
/// Parses the names above; throws UsageError listing them otherwise.
NoiseRules noise_rules_from_string(std::string_view text);

struct AllanOptions {
  AllanKind kind = AllanKind::oadev;
  TauGrid grid;            ///< averaging times (default: octave, >= 10 clusters)
  bool confidence = true;  ///< identify noise, compute edf and intervals
  /// HTOTDEV only: divide the variance by Riley's bias factor of the
  /// identified noise type (white FM 0.995, flicker FM 0.851, random-walk FM
  /// 0.771; none at m = 1 or for phase noise), as Stable32 prints it. The
  /// noise is identified for this even without `confidence`.
  bool bias_correction = true;
  NoiseRules noise_rules = NoiseRules::foglab;
  /// OADEV of a rate record with gaps: the share of a cluster's samples that
  /// may be missing (see "Clusters that miss a few samples" above; 0, the
  /// default: terms wholly inside one stretch only). In [0, 0.1].
  double max_missing_share = 0.0;
  /// With max_missing_share: the gaps (by Gap::before_sample) that no term
  /// may span all the same, as if the share were 0 there (a bias jump
  /// across them, which a spanning term would count as noise).
  std::vector<std::int64_t> unbridged_gaps;
  /// OADEV: check each tau's edf against its terms' own spread (see
  /// AllanResult::edf_reduction). Off by default: the `allan` command gives
  /// the noise type's edf, as Stable32 does.
  bool term_spread_check = false;
};

/// One statistic over a tau grid. All vectors have one entry per tau.
struct AllanResult {
  AllanKind kind = AllanKind::oadev;
  InputKind input = InputKind::rate;
  double sample_rate_hz = 0.0;       ///< [Hz]
  std::int64_t phase_points = 0;     ///< N, number of angle samples analysed
  /// Angle samples of each contiguous stretch analysed (one entry, N, for a
  /// record without gaps). A rate stretch of L samples has L + 1 angle
  /// points, so with gaps the entries add up to N plus the number of gaps.
  std::vector<std::int64_t> segment_points;
  /// averaging factors, tau = m / fs (THEO1: tau = 0.75 m / fs)
  std::vector<std::int64_t> m;
  std::vector<double> tau_s;         ///< [s]
  /// [deg/h] (TDEV, TTOTDEV: [deg/h * s], the analogue of a time deviation)
  std::vector<double> dev;
  std::vector<std::int64_t> n;       ///< number of terms in each estimate
  /// With gaps bridged (AllanOptions::max_missing_share): n over the terms
  /// the parts of segment_points hold (the stretches, merged across the
  /// bridged gaps); empty otherwise.
  std::vector<double> term_share;
  /// With gaps bridged: the terms of n that span a gap (clusters missing a
  /// few samples); empty otherwise.
  std::vector<std::int64_t> gap_spanning_terms;
  std::vector<int> alpha;            ///< identified noise exponent, S_y ~ f^alpha
  std::vector<AlphaMethod> alpha_method;  ///< how each alpha was identified (noise_id.h)
  std::vector<double> edf;           ///< equivalent degrees of freedom
  /// With AllanOptions::term_spread_check: what the noise type's edf was
  /// divided by (1 where nothing was). The edf of SP 1065 (section 5.3)
  /// assumes one power-law noise type; a narrow-band random process (a
  /// resonance) leaves the terms correlated over longer than that, and the
  /// estimate varies more. The variance of the mean of d_k^2 (d_k the
  /// second differences of the angle at factor m) is measured from the
  /// means of batches of max(64 m, 1024) terms and of every doubling of
  /// that length (at least 64 batches, within the first 2^21 angle points
  /// of the longest stretch), by the mean square difference of neighbouring
  /// batches (so that a slow change over the run, which the record's value
  /// averages, does not count), and compared with the noise type's, 2
  /// AVAR^2 / edf (at m = 1 with white noise identified, the exact edf of
  /// the sampled terms, 2 n^2 / (3 n - 1), which Greenhall's exceeds by
  /// 17 %); the largest ratio beyond chance (the 99.9 % quantile of
  /// chi-square over its degrees of freedom, 0.1 % shared among the lengths
  /// tried) divides that edf, and edf_reduction is what the noise type's
  /// edf was divided by to give it. It does not change `dev`.
  std::vector<double> edf_reduction;
  std::vector<double> ci68_low, ci68_high;  ///< 68.27 % interval, same unit as dev
  std::vector<double> ci95_low, ci95_high;  ///< 95 % interval
};

/// Computes one statistic of `samples` (rate [deg/h] or angle
/// [(deg/h)*s], see units.h) sampled at `sample_rate_hz`.
/// `gaps` (sorted, checked as by check_gaps()) are the stretches of missing
/// samples between the samples given; see "Gaps" above.
/// Throws UsageError for a bad sample rate, grid or gap list, DataError when
/// the record is too short for the statistic at a requested tau.
AllanResult allan_deviation(std::span<const double> samples, double sample_rate_hz, InputKind input,
                            const AllanOptions& options = {}, std::span<const Gap> gaps = {});

/// As allan_deviation(), but turns `samples` into the angle record in place
/// (no second array: peak memory stays at one copy of the record). The
/// vector's contents are unspecified afterwards. The CLI uses this form.
AllanResult allan_deviation_in_place(std::vector<double>& samples, double sample_rate_hz,
                                     InputKind input, const AllanOptions& options = {},
                                     std::span<const Gap> gaps = {});

/// Theo1's smallest averaging factor (SP1065 section 5.2.15: even m >= 10).
inline constexpr std::int64_t kTheo1MinFactor = 10;

/// Largest averaging factor at which `kind` is defined for N phase points
/// (0 if none is).
std::int64_t max_factor(AllanKind kind, std::int64_t phase_points);

// The steps of allan_deviation(), for the tests and benchmarks that check
// and time them one by one; not a stable interface.
namespace detail {

/// The angle record foglab analyses, in units where tau0 = 1: a rate record
/// becomes x_0 = 0, x_{k+1} = x_k + (y_k - mean(y)) (length N+1); an angle
/// record becomes x_k * fs minus the straight line through its end points.
std::vector<double> to_phase(std::span<const double> samples, double sample_rate_hz,
                             InputKind input);

/// The same in place; a rate record grows by one element.
void to_phase_in_place(std::vector<double>& samples, double sample_rate_hz, InputKind input);

/// Throws UsageError unless `sample_rate_hz` is a positive finite number.
void check_sample_rate(double sample_rate_hz);

/// The number of angle points of a record of `samples` samples: N + 1 for a
/// rate record, N for an angle record.
std::size_t phase_points(std::size_t samples, InputKind input);

/// The same angle record written to out[0 .. phase_points() - 1], in
/// parallel (each thread first touches the part it writes, so `out` may be
/// fresh, uninitialised memory); `out` may be `samples.data()`.
void to_phase_into(std::span<const double> samples, double sample_rate_hz, InputKind input,
                   double* out);

/// Deviation values only (no confidence intervals) on an angle record made by
/// to_phase(), for the given averaging factors. Throws DataError if an
/// averaging factor is too large for the statistic.
std::vector<double> deviations_from_phase(std::span<const double> phase, AllanKind kind,
                                          std::span<const std::int64_t> factors,
                                          std::vector<std::int64_t>* terms = nullptr);

}  // namespace detail

}  // namespace foglab::stats
