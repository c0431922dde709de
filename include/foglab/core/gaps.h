// foglab — stretches of missing samples in a record (a time axis with gaps:
// dropped samples, a logger's pause).
//
// A record with gaps is kept as the samples present, in order, plus the list
// of its gaps: gap g says that `missing_samples` samples are missing before
// the present sample `before_sample`. Nothing is interpolated. The
// statistics treat such a record as its contiguous stretches: the Allan
// family pools the terms that lie wholly inside one stretch (a term that
// would span a gap is left out, the way Stable32 skips gap terms; NIST
// SP 1065 section 5.15), and Welch's PSD averages the segments that lie
// wholly inside one stretch.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace foglab {

/// One stretch of missing samples.
struct Gap {
  /// Index, among the samples present, of the first sample after the gap
  /// (> 0: a record starts with a sample).
  std::int64_t before_sample = 0;
  std::int64_t missing_samples = 0;  ///< samples the time axis skips there (>= 1)
};

/// A contiguous stretch [begin, end) of the samples present.
struct Stretch {
  std::int64_t begin = 0;
  std::int64_t end = 0;
  std::int64_t size() const { return end - begin; }
};

/// Throws UsageError (naming `what`) unless the gaps are sorted by
/// before_sample, strictly inside (0, samples), and each misses >= 1 sample.
void check_gaps(std::span<const Gap> gaps, std::int64_t samples, std::string_view what);

/// The contiguous stretches of `samples` present samples with `gaps`
/// (checked as by check_gaps): one stretch without gaps.
std::vector<Stretch> contiguous_stretches(std::int64_t samples, std::span<const Gap> gaps);

/// The size of the longest of them [samples].
std::int64_t longest_stretch(std::span<const Stretch> stretches);

/// [s] Time of present sample `index` after the first sample, for samples
/// every 1/sample_rate_hz with `gaps` (sorted): (index + missing before it) / fs.
double elapsed_s(std::int64_t index, std::span<const Gap> gaps, double sample_rate_hz);

/// Where a gap lies: the times of the samples either side of it [s], after
/// the first sample.
struct GapSpan {
  double start_s = 0.0;  ///< the last sample before the gap
  double end_s = 0.0;    ///< the first sample after it
};

/// Every gap's span, in one pass (elapsed_s() of each side, without its
/// search per gap).
std::vector<GapSpan> gap_spans_s(std::span<const Gap> gaps, double sample_rate_hz);

/// Samples missing in all the gaps together.
std::int64_t missing_samples(std::span<const Gap> gaps);

}  // namespace foglab
