// Tests of the gap bookkeeping (core/gaps.h).
#include "foglab/core/gaps.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "foglab/core/error.h"

namespace foglab {
namespace {

using ::testing::HasSubstr;

TEST(Gaps, StretchesLieBetweenTheGaps) {
  const std::vector<Gap> gaps = {{3, 2}, {7, 10}};
  const std::vector<Stretch> s = contiguous_stretches(10, gaps);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].begin, 0);
  EXPECT_EQ(s[0].end, 3);
  EXPECT_EQ(s[1].begin, 3);
  EXPECT_EQ(s[1].end, 7);
  EXPECT_EQ(s[2].size(), 3);
  EXPECT_EQ(contiguous_stretches(10, {}).size(), 1u);
  EXPECT_EQ(missing_samples(gaps), 12);
}

TEST(Gaps, ElapsedTimeCountsTheMissingSamples) {
  const std::vector<Gap> gaps = {{3, 2}, {7, 10}};
  // samples 0 1 2 | (2 missing) 3 4 5 6 | (10 missing) 7 8 9, every 0.5 s
  EXPECT_DOUBLE_EQ(elapsed_s(2, gaps, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(elapsed_s(3, gaps, 2.0), 2.5);
  EXPECT_DOUBLE_EQ(elapsed_s(6, gaps, 2.0), 4.0);
  EXPECT_DOUBLE_EQ(elapsed_s(7, gaps, 2.0), 9.5);
}

TEST(Gaps, SpansAreTheTimesOfTheSamplesEitherSide) {
  const std::vector<Gap> gaps = {{3, 2}, {7, 10}, {8, 1}};
  const std::vector<GapSpan> spans = gap_spans_s(gaps, 2.0);
  ASSERT_EQ(spans.size(), 3u);
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    EXPECT_EQ(spans[g].start_s, elapsed_s(gaps[g].before_sample - 1, gaps, 2.0));
    EXPECT_EQ(spans[g].end_s, elapsed_s(gaps[g].before_sample, gaps, 2.0));
  }
  EXPECT_DOUBLE_EQ(spans[1].start_s, 4.0);  // sample 6 after 2 missing
  EXPECT_DOUBLE_EQ(spans[1].end_s, 9.5);    // sample 7 after 12 missing
}

TEST(Gaps, UnsortedOrOutOfRangeGapsAreUsageErrors) {
  const std::vector<Gap> unsorted = {{5, 1}, {3, 1}};
  const std::vector<Gap> at_start = {{0, 1}};
  const std::vector<Gap> at_end = {{10, 1}};
  const std::vector<Gap> empty_gap = {{4, 0}};
  for (const auto* gaps : {&unsorted, &at_start, &at_end}) {
    try {
      check_gaps(*gaps, 10, "test");
      ADD_FAILURE() << "no error";
    } catch (const UsageError& e) {
      EXPECT_THAT(e.what(), HasSubstr("strictly inside the record's 10 samples"));
    }
  }
  EXPECT_THROW(check_gaps(empty_gap, 10, "test"), UsageError);
}

}  // namespace
}  // namespace foglab
