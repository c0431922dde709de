#include "foglab/core/gaps.h"

#include <fmt/format.h>

#include <algorithm>

#include "foglab/core/error.h"

namespace foglab {

void check_gaps(std::span<const Gap> gaps, std::int64_t samples, std::string_view what) {
  std::int64_t previous = 0;
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    const Gap& gap = gaps[g];
    if (!(gap.before_sample > previous && gap.before_sample < samples)) {
      throw UsageError(fmt::format(
          "{}: gap {} lies before sample {}; gaps must be sorted and lie strictly inside the "
          "record's {} samples",
          what, g + 1, gap.before_sample, samples));
    }
    if (gap.missing_samples < 1) {
      throw UsageError(fmt::format("{}: gap {} misses {} samples; a gap misses at least 1", what,
                                   g + 1, gap.missing_samples));
    }
    previous = gap.before_sample;
  }
}

std::vector<Stretch> contiguous_stretches(std::int64_t samples, std::span<const Gap> gaps) {
  check_gaps(gaps, samples, "contiguous_stretches");
  std::vector<Stretch> stretches;
  std::int64_t begin = 0;
  for (const Gap& gap : gaps) {
    stretches.push_back({begin, gap.before_sample});
    begin = gap.before_sample;
  }
  stretches.push_back({begin, samples});
  return stretches;
}

std::int64_t longest_stretch(std::span<const Stretch> stretches) {
  std::int64_t longest = 0;
  for (const Stretch& s : stretches) longest = std::max(longest, s.size());
  return longest;
}

double elapsed_s(std::int64_t index, std::span<const Gap> gaps, double sample_rate_hz) {
  std::int64_t missing = 0;
  for (const Gap& gap : gaps) {
    if (gap.before_sample > index) break;
    missing += gap.missing_samples;
  }
  return static_cast<double>(index + missing) / sample_rate_hz;
}

std::vector<GapSpan> gap_spans_s(std::span<const Gap> gaps, double sample_rate_hz) {
  std::vector<GapSpan> spans;
  spans.reserve(gaps.size());
  std::int64_t missing_before = 0;
  for (const Gap& gap : gaps) {
    const auto before = static_cast<double>(gap.before_sample - 1 + missing_before);
    missing_before += gap.missing_samples;
    const auto after = static_cast<double>(gap.before_sample + missing_before);
    spans.push_back({before / sample_rate_hz, after / sample_rate_hz});
  }
  return spans;
}

std::int64_t missing_samples(std::span<const Gap> gaps) {
  std::int64_t total = 0;
  for (const Gap& gap : gaps) total += gap.missing_samples;
  return total;
}

}  // namespace foglab
