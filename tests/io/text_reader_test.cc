// Tests of reading text tables: CSV, TSV and whitespace columns, headers,
// comments, column choice, the time column, and the messages for bad cells.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/io/channels.h"
#include "foglab/io/reader.h"
#include "reader_fixture.h"
#include "support/expect.h"
#include "support/files.h"

namespace foglab::io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

using test::message_of;

using TextReaderTest = ReaderTest;

TEST_F(TextReaderTest, CsvWithHeaderTakesRateAndItsSampleRateFromT) {
  // the layout `foglab generate` writes: t, rate, temperature
  const std::string path = write("run.csv",
                                 "t,rate,temperature\n"
                                 "0.0,1.5,20.0\n"
                                 "0.1,2.5,20.1\n"
                                 "0.2,-3.5,20.2\n");
  const Series series = read_series(path, {});
  EXPECT_EQ(series.path, path);
  EXPECT_EQ(series.channel, "rate");
  EXPECT_THAT(series.values, ElementsAre(1.5, 2.5, -3.5));
  EXPECT_NEAR(series.sample_rate_hz, 10.0, 1e-12);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::time_channel);
  EXPECT_EQ(series.sample_rate_channel, "t");
  EXPECT_THAT(series.available_channels, ElementsAre("t", "rate", "temperature"));
  EXPECT_THAT(list_channels(path), ElementsAre("t", "rate", "temperature"));
}

TEST_F(TextReaderTest, TabSeparatedWithTimeHeaderInAnyCase) {
  const std::string path = write("run.tsv",
                                 "Time_S\tY1\tY2\n"
                                 "10.00\t1\t4\n"
                                 "10.25\t2\t5\n"
                                 "10.50\t3\t6\n");
  const Series series = read_series(path, {});
  EXPECT_EQ(series.channel, "Y1");
  EXPECT_THAT(series.values, ElementsAre(1, 2, 3));
  EXPECT_NEAR(series.sample_rate_hz, 4.0, 1e-12);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::time_channel);
  EXPECT_EQ(series.sample_rate_channel, "Time_S");
}

TEST_F(TextReaderTest, WhitespaceColumnsWithoutHeaderAreChosenByIndex) {
  const std::string path = write("run.txt",
                                 "  0.0   10   -1e-3\n"
                                 "0.5\t\t20  +2.5E2\n"
                                 "1.0 30 3\n");
  ReadOptions options = with_fs(2.0);
  options.channel = "3";
  const Series series = read_series(path, options);
  EXPECT_EQ(series.channel, "3");
  EXPECT_THAT(series.values, ElementsAre(-1e-3, 250.0, 3.0));
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::option);
  EXPECT_THAT(series.available_channels, ElementsAre("1", "2", "3"));
}

TEST_F(TextReaderTest, TimeColumnOfAHeaderlessFileIsChosenByIndex) {
  const std::string path = write("run.txt", "0 5\n0.5 6\n1.0 7\n");
  ReadOptions options;
  options.channel = "2";
  options.time_channel = "1";
  const Series series = read_series(path, options);
  EXPECT_THAT(series.values, ElementsAre(5, 6, 7));
  EXPECT_DOUBLE_EQ(series.sample_rate_hz, 2.0);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::time_channel);
  EXPECT_EQ(series.sample_rate_channel, "1");
}

TEST_F(TextReaderTest, OneNumericColumnNeedsNoChannel) {
  const std::string path = write("rate.txt", "1.25\n2.5\n\n3.75\n");
  const Series series = read_series(path, with_fs(100.0));
  EXPECT_EQ(series.channel, "1");
  EXPECT_THAT(series.values, ElementsAre(1.25, 2.5, 3.75));
  EXPECT_EQ(series.sample_rate_hz, 100.0);
}

TEST_F(TextReaderTest, OneColumnWithoutFsAsksForIt) {
  const std::string path = write("rate.txt", "1\n2\n");
  const std::string message = message_of<UsageError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("'" + path + "' has no sample rate"));
  EXPECT_THAT(message, HasSubstr("give ReadOptions::sample_rate_hz"));
}

TEST_F(TextReaderTest, CommentsBlankLinesCrLfAndQuotesAreHandled) {
  const std::string path = write("commented.csv",
                                 "\xEF\xBB\xBF# recorded by hand\r\n"
                                 "\r\n"
                                 "   # another comment\r\n"
                                 "\"t\", \"rate\"  # names\r\n"
                                 "0, 1   # first\r\n"
                                 "\r\n"
                                 "1, 2\r\n"
                                 "# between\r\n"
                                 "2, \"3\"\r\n");
  const Series series = read_series(path, {});
  EXPECT_EQ(series.channel, "rate");
  EXPECT_THAT(series.values, ElementsAre(1, 2, 3));
  EXPECT_DOUBLE_EQ(series.sample_rate_hz, 1.0);
}

TEST_F(TextReaderTest, ColumnsAreChosenByNameOrIndex) {
  const std::string path = write("three.csv", "a,b,c\n1,2,3\n4,5,6\n");
  ReadOptions options = with_fs(1.0);
  options.channel = "b";
  EXPECT_THAT(read_series(path, options).values, ElementsAre(2, 5));
  options.channel = "C";  // a name that matches only without regard to case
  EXPECT_THAT(read_series(path, options).values, ElementsAre(3, 6));
  options.channel = "1";
  const Series first = read_series(path, options);
  EXPECT_EQ(first.channel, "a");
  EXPECT_THAT(first.values, ElementsAre(1, 4));
}

TEST_F(TextReaderTest, DigitsThatNameAColumnAreAName) {
  const std::string path = write("named.csv", "x,1\n10,20\n30,40\n");
  ReadOptions options = with_fs(1.0);
  options.channel = "1";  // the column named "1" (the second), not column 1
  EXPECT_THAT(read_series(path, options).values, ElementsAre(20, 40));
}

TEST_F(TextReaderTest, UnknownColumnListsTheColumns) {
  const std::string path = write("three.csv", "t,a,b\n0,1,2\n");
  ReadOptions options = with_fs(1.0);
  options.channel = "rate";
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, options); }),
            "'" + path + "': no channel column 'rate'; columns: t, a, b");
  options.channel = "4";
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, options); }),
            "'" + path + "': no channel column 4: the table has 3 column(s) (t, a, b)");
}

TEST_F(TextReaderTest, SeveralColumnsWithoutAPreferredNameNeedAChannel) {
  const std::string path = write("three.csv", "t,a,b\n0,1,2\n");
  const std::string message = message_of<DataError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("'" + path + "'"));
  EXPECT_THAT(message, HasSubstr("several columns (t, a, b) and none is Y1 or rate"));
  EXPECT_THAT(message, HasSubstr("choose one with ReadOptions::channel"));
}

TEST_F(TextReaderTest, TheOnlyNonTimeColumnIsTheDefault) {
  const std::string path = write("two.csv", "time,gyro\n0,7\n0.5,8\n");
  const Series series = read_series(path, {});
  EXPECT_EQ(series.channel, "gyro");
  EXPECT_DOUBLE_EQ(series.sample_rate_hz, 2.0);
}

TEST_F(TextReaderTest, ACapitalTIsTemperatureNotTime) {
  const std::string path = write("temp.csv", "Y1,T\n1,20\n2,25\n");
  EXPECT_THAT(message_of<UsageError>([&] { read_series(path, {}); }),
              HasSubstr("has no sample rate"));
  EXPECT_EQ(read_series(path, with_fs(1.0)).channel, "Y1");
}

TEST_F(TextReaderTest, TimeWithAGapListsItsMissingSamples) {
  const std::string path = write("gap.csv", "t,rate\n0,1\n0.1,1\n0.2,1\n0.5,1\n0.6,1\n");
  const Series series = read_series(path, {});
  ASSERT_EQ(series.gaps.size(), 1u);
  EXPECT_EQ(series.gaps[0].before_sample, 3);  // 0.3 and 0.4 s are missing
  EXPECT_EQ(series.gaps[0].missing_samples, 2);
  EXPECT_EQ(series.values.size(), 5u);
  // 5 samples and 2 missing span 0.6 s: 10 Hz, not 4 / 0.6
  EXPECT_NEAR(series.sample_rate_hz, 10.0, 1e-9);
  // with a sample rate given the time column is not used, so it does not matter
  const Series ignored = read_series(path, with_fs(10.0));
  EXPECT_EQ(ignored.values.size(), 5u);
  EXPECT_TRUE(ignored.gaps.empty());
}

// A logger's clock beside a sensor's samples: times 50 Hz apart from 1.7e9 s, each moved by a
// uniform draw of +-35 % of a step, printed to the microsecond; the samples are numbered so
// that the ones kept can be told.
std::string jittered_table(std::size_t rows, const std::function<bool(std::size_t)>& lost,
                           std::size_t repeated) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  std::string text = "time_s,rate\n";
  for (std::size_t k = 0; k < rows; ++k) {
    const double t = 1.7e9 + (static_cast<double>(k) + jitter(random)) / 50.0;
    if (lost(k)) continue;
    const std::string row = fmt::format("{:.6f},{}\n", t, k);
    text += row;
    if (k == repeated) text += row;  // the logger wrote the row twice
  }
  return text;
}

TEST_F(TextReaderTest, TimesThatJitterAreReadOnTheirGridWithTheirGaps) {
  // 10 samples lost at 1000-1009, one at 2000, row 1500 written twice
  const std::string path =
      write("jitter.csv",
            jittered_table(
                3000, [](std::size_t k) { return (k >= 1000 && k < 1010) || k == 2000; }, 1500));
  const Series series = read_series(path, {});
  ASSERT_EQ(series.values.size(), 3000u - 11u);
  ASSERT_EQ(series.gaps.size(), 2u);
  EXPECT_EQ(series.gaps[0].before_sample, 1000);
  EXPECT_EQ(series.gaps[0].missing_samples, 10);
  EXPECT_EQ(series.gaps[1].before_sample, 1990);
  EXPECT_EQ(series.gaps[1].missing_samples, 1);
  // every sample kept once, in order: the repeated row dropped
  EXPECT_EQ(series.values[999], 999.0);
  EXPECT_EQ(series.values[1000], 1010.0);
  EXPECT_EQ(series.values[1490], 1500.0);
  EXPECT_EQ(series.values[1491], 1501.0);
  EXPECT_EQ(series.values[1990], 2001.0);
  EXPECT_NEAR(series.sample_rate_hz, 50.0, 50.0 * 1e-4);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::time_channel);
  ASSERT_TRUE(series.time_jitter.has_value());
  const TimeJitter& j = *series.time_jitter;
  EXPECT_EQ(j.rows_dropped, 1u);
  EXPECT_EQ(j.steps, 3000u - 11u);  // the rows read, less one
  EXPECT_GT(j.irregular_steps, j.steps * 9 / 10);
  // uniform +-35 % of 20 ms: rms 4.04 ms, largest just under 7 ms
  EXPECT_NEAR(j.rms_s / (0.35 * 0.02 / std::sqrt(3.0)), 1.0, 0.05);
  EXPECT_LT(j.max_s, 0.0071);
  EXPECT_GT(j.max_s, 0.0065);
  ASSERT_EQ(series.notes.size(), 2u);
  EXPECT_THAT(series.notes[0].text(), HasSubstr("read as a uniform sampling grid with jitter"));
  EXPECT_THAT(series.notes[1].text(), HasSubstr("1 of the 2990 rows dropped"));
  // exact times are not jitter
  EXPECT_FALSE(read_series(write("exact.csv", "t,rate\n0,1\n0.1,2\n0.2,3\n"), {}).time_jitter);
}

TEST_F(TextReaderTest, TimesStampedInBurstsSayTheyMayNotBeTheSampling) {
  // a 100 Hz sensor's samples handed over four at a time every 40 ms, stamped 1 ms apart as
  // they arrive: a regular 1 ms step with a gap after every fourth sample
  std::string text = "t,rate\n";
  for (int k = 0; k < 2000; ++k)
    text += fmt::format("{:.3f},{}\n", (k / 4) * 0.04 + (k % 4) * 0.001, k);
  const Series series = read_series(write("bursts.csv", text), {});
  EXPECT_EQ(series.gaps.size(), 499u);
  ASSERT_EQ(series.notes.size(), 1u);
  EXPECT_THAT(series.notes[0].text(),
              HasSubstr("show 499 gaps among 2000 samples, with 17964 samples missing on a grid "
                        "of 0.001 s steps: more are missing than present"));
  EXPECT_THAT(series.notes[0].text(), HasSubstr("ReadOptions::sample_rate_hz"));
  // a record with a few gaps has no such note
  EXPECT_THAT(read_series(write("gap.csv", "t,rate\n0,1\n0.1,1\n0.2,1\n0.5,1\n0.6,1\n"), {}).notes,
              IsEmpty());
}

TEST_F(TextReaderTest, AFewIrregularStepsAreEachAFaultAndNamed) {
  // 1000 regular times at 10 Hz, five of them late by 0.3 of a step: not jitter
  std::string text = "t,rate\n";
  for (int k = 0; k < 1000; ++k) {
    const bool late = k % 200 == 100;
    text += fmt::format("{:.2f},1\n", k * 0.1 + (late ? 0.03 : 0.0));
  }
  const std::string message =
      message_of<DataError>([&] { read_series(write("late.csv", text), {}); });
  EXPECT_THAT(message, HasSubstr("not uniformly sampled at sample 101 of 't' (line 102)"));
  EXPECT_THAT(message, HasSubstr("and 9 more irregular or decreasing step(s) of 999"));
  EXPECT_THAT(message, HasSubstr("ReadOptions::sample_rate_hz"));
}

TEST_F(TextReaderTest, TimesWithoutAGridStayAnError) {
  // times of a Poisson process (events, not samples): no grid to put them on
  std::mt19937_64 random(5);
  std::exponential_distribution<double> step(100.0);
  std::string text = "t,rate\n";
  double t = 0.0;
  for (int k = 0; k < 5000; ++k) {
    t += step(random);
    text += fmt::format("{:.9f},1\n", t);
  }
  const std::string message =
      message_of<DataError>([&] { read_series(write("events.csv", text), {}); });
  EXPECT_THAT(message, HasSubstr("not uniformly sampled at sample"));
  EXPECT_THAT(message, HasSubstr("do not scatter about a uniform grid either"));
  EXPECT_THAT(message, HasSubstr("ReadOptions::sample_rate_hz"));
}

TEST_F(TextReaderTest, IrregularStepIsAnErrorWithIndexAndValues) {
  // 1.3 steps: neither the sample step nor a whole number of missing samples
  const std::string path = write("odd_step.csv", "t,rate\n0,1\n0.1,1\n0.2,1\n0.33,1\n0.43,1\n");
  const std::string message = message_of<DataError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("'" + path + "'"));
  EXPECT_THAT(message, HasSubstr("not uniformly sampled at sample 4 of 't' (line 5): step 0.13 s "
                                 "(0.2 s -> 0.33 s), expected 0.1 s (an irregular step"));
}

TEST_F(TextReaderTest, TimeGoingBackIsAnError) {
  const std::string path = write("back.csv", "t,rate\n0,1\n1,1\n2,1\n1.5,1\n");
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, {}); }),
              HasSubstr("time is not increasing at sample 4 of 't' (line 5): 1.5 s follows 2 s"));
}

TEST_F(TextReaderTest, GapLateInALongRecordIsFound) {
  // past the first 64 steps the time column is checked as it streams by
  std::string content = "# logger output\ntime_s rate\n";
  for (int i = 0; i < 500; ++i) {
    const double t = 100.0 + 0.002 * (i < 321 ? i : i + 1);  // sample 322 is missing
    content += fmt::format("{} {}\n", t, i);
  }
  const std::string path = write("late_gap.txt", content);
  const Series series = read_series(path, {});
  ASSERT_EQ(series.gaps.size(), 1u);
  EXPECT_EQ(series.gaps[0].before_sample, 321);
  EXPECT_EQ(series.gaps[0].missing_samples, 1);
  EXPECT_NEAR(series.sample_rate_hz, 500.0, 1e-6);
  EXPECT_DOUBLE_EQ(series.start_time_s, 100.0);
}

TEST_F(TextReaderTest, TimesPrintedWithFewDecimalsAreNotGaps) {
  // 300 Hz printed with "%.3f": steps of 0.003 and 0.004 s are rounding
  std::string content = "t,rate\n";
  for (int i = 0; i < 300; ++i) content += fmt::format("{:.3f},{}\n", 5.0 + i / 300.0, i);
  const std::string path = write("rounded.csv", content);
  const Series series = read_series(path, {});
  // the rate comes from the span, which rounding moves by up to 1 ms in ~1 s
  EXPECT_NEAR(series.sample_rate_hz, 300.0, 300.0 * 0.001 / 0.996);
  // ... but a missing sample is still a gap
  content = "t,rate\n";
  for (int i = 0; i < 300; ++i) {
    if (i != 200) content += fmt::format("{:.3f},{}\n", 5.0 + i / 300.0, i);
  }
  const std::string gap = write("rounded_gap.csv", content);
  const Series with_gap = read_series(gap, {});
  ASSERT_EQ(with_gap.gaps.size(), 1u);
  EXPECT_EQ(with_gap.gaps[0].before_sample, 200);
  EXPECT_EQ(with_gap.gaps[0].missing_samples, 1);
  EXPECT_TRUE(series.gaps.empty());
}

TEST_F(TextReaderTest, WholeSecondTimesAreExact) {
  // integer seconds at 1 Hz: the print resolution (1 s) is no excuse for
  // a step of 2 s
  const std::string path = write("seconds.csv", "t,rate\n0,1\n1,1\n2,1\n4,1\n5,1\n");
  const Series series = read_series(path, {});
  ASSERT_EQ(series.gaps.size(), 1u);
  EXPECT_EQ(series.gaps[0].before_sample, 3);
  EXPECT_EQ(series.gaps[0].missing_samples, 1);
  EXPECT_NEAR(series.sample_rate_hz, 1.0, 1e-12);
}

TEST_F(TextReaderTest, OneOddFirstStepIsReportedAsTheOddOne) {
  // the reference step is the median of the first steps, not the first one
  const std::string path = write("odd.csv", "t,rate\n0,1\n0.13,1\n0.23,1\n0.33,1\n0.43,1\n");
  EXPECT_THAT(
      message_of<DataError>([&] { read_series(path, {}); }),
      HasSubstr("at sample 2 of 't' (line 3): step 0.13 s (0 s -> 0.13 s), expected 0.1 s"));
  // the same for a gap: four samples missing after the first, not an odd reference
  const std::string gap = write("odd_gap.csv", "t,rate\n0,1\n0.5,1\n0.6,1\n0.7,1\n0.8,1\n");
  const Series series = read_series(gap, {});
  ASSERT_EQ(series.gaps.size(), 1u);
  EXPECT_EQ(series.gaps[0].before_sample, 1);
  EXPECT_EQ(series.gaps[0].missing_samples, 4);
}

TEST_F(TextReaderTest, NonNumericCellNamesLineColumnAndText) {
  const std::string path = write("bad.csv",
                                 "# header follows\n"
                                 "t,rate\n"
                                 "0,1\n"
                                 "1,2\n"
                                 "2,abc\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, {}); }),
            "'" + path + "': line 5, column 2 (rate): 'abc' is not a number");
}

TEST_F(TextReaderTest, NonNumericCellWithoutHeaderNamesTheColumnNumber) {
  const std::string path = write("bad.txt", "1 2\n3 4x\n");
  ReadOptions options = with_fs(1.0);
  options.channel = "2";
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, options); }),
            "'" + path + "': line 2, column 2: '4x' is not a number");
}

TEST_F(TextReaderTest, EmptyCellIsReported) {
  const std::string path = write("hole.csv", "t,rate\n0,1\n1,\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, {}); }),
            "'" + path + "': line 3, column 2 (rate) is empty");
}

TEST_F(TextReaderTest, TextInAColumnThatIsNotReadDoesNotMatter) {
  const std::string path = write("dated.csv", "date,rate\n2021-03-01,1\n2021-03-02,2\n");
  ReadOptions options = with_fs(1.0);
  options.channel = "rate";
  EXPECT_THAT(read_series(path, options).values, ElementsAre(1, 2));
}

TEST_F(TextReaderTest, RaggedRowIsReported) {
  const std::string path = write("ragged.csv", "t,rate,temp\n0,1,20\n1,2\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, {}); }),
            "'" + path + "': line 3 has 2 column(s), expected 3 as in line 1 (t, rate, temp)");
}

TEST_F(TextReaderTest, SemicolonsSeparateFieldsAndDecimalCommasNeedTheOption) {
  // Spreadsheets in much of Europe write "t;rate" and "0,5".
  const std::string path = write("excel.csv", "t;rate\n0;1,5\n1;-2,25e-1\n2;3\n");
  ReadOptions options;
  options.channel = "rate";
  const std::string message = message_of<DataError>([&] { read_series(path, options); });
  EXPECT_THAT(message, HasSubstr("line 2, column 2 (rate): '1,5' is not a number (a decimal "
                                 "comma: give ReadOptions::decimal_comma"));
  options.decimal_comma = true;
  const Series s = read_series(path, options);
  EXPECT_EQ(s.values, (std::vector<double>{1.5, -0.225, 3.0}));
  EXPECT_DOUBLE_EQ(s.sample_rate_hz, 1.0);
}

// UTF-16 (converted with iconv in blocks): a table of 3 MB, so that the
// conversion runs out of room and resumes several times, and a file cut in
// the middle of a character.
TEST_F(TextReaderTest, Utf16WithAByteOrderMarkIsReadInFull) {
  std::string text = "t,rate\r\n";
  std::vector<double> expected;
  for (int i = 0; i < 150000; ++i) {
    text += std::to_string(i) + "," + std::to_string(i % 97) + ".25\r\n";
    expected.push_back(i % 97 + 0.25);
  }
  for (const bool little_endian : {true, false}) {
    SCOPED_TRACE(little_endian ? "LE" : "BE");
    std::string bytes = little_endian ? "\xFF\xFE" : "\xFE\xFF";
    for (const char c : text) bytes += little_endian ? std::string{c, '\0'} : std::string{'\0', c};
    ReadOptions options;
    options.channel = "rate";
    const Series s = read_series(write("utf16.csv", bytes), options);
    EXPECT_EQ(s.values, expected);
    EXPECT_DOUBLE_EQ(s.sample_rate_hz, 1.0);
    bytes.pop_back();  // half a character at the end
    EXPECT_THAT(message_of<DataError>([&] { read_series(write("cut.csv", bytes), options); }),
                HasSubstr("ends in the middle of a character"));
  }
}

TEST_F(TextReaderTest, CarriageReturnsAloneEndLines) {
  const std::string path = write("mac.csv", "# old Mac\rt,rate\r0,1\r1,2\r2,4\r");
  ReadOptions options;
  options.channel = "rate";
  EXPECT_EQ(read_series(path, options).values, (std::vector<double>{1.0, 2.0, 4.0}));
}

TEST_F(TextReaderTest, TheSampleLimitAndTheLineLengthAreBounds) {
  std::string rows;
  for (int i = 0; i < 50; ++i) rows += std::to_string(i) + "\n";
  ReadOptions options = with_fs(1.0);
  options.max_samples = 40;
  EXPECT_THAT(message_of<DataError>([&] { read_series(write("rows.txt", rows), options); }),
              HasSubstr("more than 40 samples (at line 41)"));
  options.max_samples = 50;
  EXPECT_EQ(read_series(write("rows.txt", rows), options).values.size(), 50u);
  const std::string long_line = "1\n2\n" + std::string((1 << 20) + 10, '7') + "\n";
  EXPECT_THAT(message_of<DataError>([&] { read_series(write("long.txt", long_line), with_fs(1)); }),
              HasSubstr("line 3 is longer than 1 MiB"));
}

TEST_F(TextReaderTest, CommasBetweenIntegersStayDelimiters) {
  // "0, 1, 25" and a headerless "0,5" are comma-separated integers, not
  // decimal commas.
  ReadOptions options = with_fs(1.0);
  options.channel = "3";
  EXPECT_EQ(read_series(write("spaced.csv", "0, 1, 25\n1, 2, 26\n"), options).values,
            (std::vector<double>{25.0, 26.0}));
  options.channel = "2";
  EXPECT_EQ(read_series(write("pairs.csv", "0,5\n1,7\n"), options).values,
            (std::vector<double>{5.0, 7.0}));
}

TEST_F(TextReaderTest, BinaryDataIsNotTakenForText) {
  const std::string path = write("record.dat", std::string("\x01\x02\xf0\x3f\x00\x02", 6));
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, with_fs(1.0)); }),
              HasSubstr("'" + path + "': byte 5 is a NUL: binary data, not text"));
  // Control characters without a NUL: still not text.
  const std::string control = write("control.dat", std::string("1\x01\x02\n2\n", 6));
  EXPECT_THAT(message_of<DataError>([&] { read_series(control, with_fs(1.0)); }),
              HasSubstr("line 1 holds binary data, not text"));
}

TEST_F(TextReaderTest, AMatFileUnderAnotherNameIsRecognised) {
  const std::string path = write("record.dat",
                                 "MATLAB 5.0 MAT-file, Platform: x, Created on: Sat Nov 21\n"
                                 "  \x00\x01IM\x0e\x00\x00\x00");
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, with_fs(1.0)); }),
              HasSubstr("'" + path + "': this is a MAT file, not text"));
}

TEST_F(TextReaderTest, AFileRefusedOnItsFirstBlockIsClosed) {
  // Binary, MAT and HDF5 files are refused while the reader is being
  // constructed; each had left its descriptor open (a fuzzing finding: a
  // long run ran out of descriptors).
  const auto open_descriptors = [] {
    return std::distance(fs::directory_iterator("/proc/self/fd"), fs::directory_iterator{});
  };
  const std::string binary = write("record.dat", std::string("\x01\x02\xf0\x3f\x00\x02", 6));
  const std::string mat = write("record.txt",
                                "MATLAB 5.0 MAT-file, Platform: x, Created on: Sat Nov 21\n"
                                "  \x00\x01IM\x0e\x00\x00\x00");
  const std::string hdf5 = write("record.csv", std::string("\x89HDF\r\n\x1a\n", 8));
  const auto before = open_descriptors();
  for (int k = 0; k < 20; ++k) {
    for (const std::string& path : {binary, mat, hdf5}) {
      EXPECT_THROW(read_series(path, with_fs(1.0)), DataError) << path;
    }
  }
  EXPECT_EQ(open_descriptors(), before);
}

TEST_F(TextReaderTest, HeaderWithoutRowsIsReported) {
  const std::string path = write("header.csv", "# only names\nt,rate\n\n# nothing else\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, {}); }),
            "'" + path + "': the file has a header (t, rate) but no data rows");
}

TEST_F(TextReaderTest, EmptyAndCommentOnlyFilesHaveNoData) {
  const std::string empty = write("empty.csv", "");
  EXPECT_EQ(message_of<DataError>([&] { read_series(empty, with_fs(1.0)); }),
            "'" + empty + "': no data (the file is empty or has only comments)");
  const std::string comments = write("comments.txt", "# a\n\n   \n# b\n");
  EXPECT_THAT(message_of<DataError>([&] { read_series(comments, with_fs(1.0)); }),
              HasSubstr("no data"));
  EXPECT_THAT(message_of<DataError>([&] { list_channels(comments); }), HasSubstr("no data"));
}

TEST_F(TextReaderTest, NanAndInfAreReportedWithTheirSampleIndex) {
  const std::string path = write("nan.csv", "t,rate\n0,1\n1,2\n2,nan\n3,4\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, {}); }),
            "'" + path + "': sample 3 of 'rate' is NaN");
  const std::string inf = write("inf.txt", "1\n2\n3\n-inf\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(inf, with_fs(1.0)); }),
            "'" + inf + "': sample 4 of '1' is -Inf");
}

TEST_F(TextReaderTest, NanSamplesAreMissingSamplesWhenAskedAndBecomeGaps) {
  // rows (t = 0.0 .. 1.1 s at 10 Hz, 0.5 s lost in the time column):
  // NaN at 0.0 (the record starts later), an empty cell at 0.2, NaN at
  // 0.4 beside the time column's gap at 0.5 (one gap of two samples), NaN
  // at 1.1 (the record ends earlier); the temperature NaN at 0.8 only
  const std::string path = write("nan_rows.csv",
                                 "t,rate,T\n0,nan,20\n0.1,1,20\n0.2,,20\n0.3,3,20\n0.4,NaN,20\n"
                                 "0.6,6,20\n0.7,7,20\n0.8,8,nan\n0.9,9,20\n1,10,20\n1.1,nan,20\n");
  ReadOptions options;
  options.channel = "rate";
  // without the option an empty cell and a NaN are errors, as before
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, options); }),
            "'" + path + "': line 4, column 2 (rate) is empty");
  EXPECT_EQ(message_of<DataError>(
                [&] { read_series(write("nan_only.csv", "t,rate\n0,1\n0.1,nan\n"), options); }),
            "'" + dir_.file("nan_only.csv") + "': sample 2 of 'rate' is NaN");
  options.nan_is_missing = true;
  Series series = read_series(path, options);
  ASSERT_EQ(series.values.size(), 11u);  // every row, the NaN kept
  ASSERT_EQ(series.gaps.size(), 1u);     // the time axis' gap, before row 5 (0.6 s)
  EXPECT_EQ(series.gaps[0].before_sample, 5);
  EXPECT_EQ(series.gaps[0].missing_samples, 1);

  ReadOptions temperature_options = with_fs(series.sample_rate_hz);
  temperature_options.channel = "T";
  temperature_options.nan_is_missing = true;
  Series temperature = read_series(path, temperature_options);
  ASSERT_EQ(temperature.values.size(), 11u);

  const MissingSamples left = drop_missing_samples(series, &temperature.values);
  EXPECT_EQ(left.samples, 5);
  EXPECT_EQ(left.stretches, 5);
  EXPECT_EQ(left.at_start, 1);
  EXPECT_EQ(left.at_end, 1);
  EXPECT_THAT(series.values, ElementsAre(1, 3, 6, 7, 9, 10));
  EXPECT_THAT(temperature.values, ElementsAre(20, 20, 20, 20, 20, 20));
  // kept at 0.1, 0.3, 0.6, 0.7, 0.9, 1.0 s: gaps of 1 (0.2), 2 (0.4, 0.5) and 1 (0.8)
  ASSERT_EQ(series.gaps.size(), 3u);
  EXPECT_EQ(series.gaps[0].before_sample, 1);
  EXPECT_EQ(series.gaps[0].missing_samples, 1);
  EXPECT_EQ(series.gaps[1].before_sample, 2);
  EXPECT_EQ(series.gaps[1].missing_samples, 2);
  EXPECT_EQ(series.gaps[2].before_sample, 4);
  EXPECT_EQ(series.gaps[2].missing_samples, 1);
  EXPECT_NEAR(series.start_time_s, 0.1, 1e-12);
  EXPECT_EQ(series.nan_left_out.samples, 5);

  // an infinity is still an error; a channel of NaN only has nothing left
  ReadOptions raw = with_fs(1.0);
  raw.nan_is_missing = true;
  const std::string inf = write("inf_rows.txt", "1\nnan\n-inf\n");
  EXPECT_EQ(message_of<DataError>([&] { read_series(inf, raw); }),
            "'" + inf + "': sample 3 of '1' is -Inf");
  Series empty = read_series(write("all_nan.txt", "nan\nnan\n"), raw);
  EXPECT_THAT(message_of<DataError>([&] { drop_missing_samples(empty, nullptr); }),
              HasSubstr("all 2 are NaN"));
  // without a NaN nothing changes
  Series whole = read_series(write("whole.txt", "1\n2\n"), raw);
  EXPECT_EQ(drop_missing_samples(whole, nullptr).samples, 0);
  EXPECT_THAT(whole.values, ElementsAre(1, 2));
}

TEST_F(TextReaderTest, UnitsAreConvertedToDegPerHour) {
  const std::string path = write("dps.txt", "1\n-0.5\n");
  ReadOptions options = with_fs(1.0);
  options.unit = rate_unit_from_string("deg/s");
  EXPECT_THAT(read_series(path, options).values, ElementsAre(3600.0, -1800.0));
  options.unit = rate_unit_from_string("rad/s");
  const Series series = read_series(path, options);
  EXPECT_DOUBLE_EQ(series.values[0], kDegPerRad * 3600.0);
  EXPECT_DOUBLE_EQ(series.values[1], -0.5 * kDegPerRad * 3600.0);
}

TEST_F(TextReaderTest, UnknownUnitAndFormatNamesAreUsageErrors) {
  EXPECT_THAT(message_of<UsageError>([] { rate_unit_from_string("mrad/s"); }),
              HasSubstr("unknown unit 'mrad/s': expected deg/h, deg/s or rad/s (gyroscopes), "
                        "m/s^2, g or mg (accelerometers)"));
  EXPECT_THAT(message_of<UsageError>([] { input_format_from_string("xlsx"); }),
              HasSubstr("unknown input format 'xlsx': expected auto, mat, text"));
  EXPECT_EQ(input_format_from_string("csv"), InputFormat::text);
  EXPECT_EQ(input_format_from_string("TSV"), InputFormat::text);
  EXPECT_EQ(input_format_from_string("float32"), InputFormat::f32);
  EXPECT_EQ(input_format_from_string("float64"), InputFormat::f64);
  EXPECT_EQ(input_format_from_string("auto"), InputFormat::automatic);
  for (InputFormat format : {InputFormat::automatic, InputFormat::mat, InputFormat::text,
                             InputFormat::f32, InputFormat::f64}) {
    EXPECT_EQ(input_format_from_string(to_string(format)), format);
  }
}

TEST_F(TextReaderTest, BadSampleRateOptionIsAUsageError) {
  const std::string path = write("rate.txt", "1\n2\n");
  for (double bad : {0.0, -10.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    const std::string message = message_of<UsageError>([&] { read_series(path, with_fs(bad)); });
    EXPECT_THAT(message, HasSubstr("invalid sample rate ReadOptions::sample_rate_hz"));
    EXPECT_THAT(message, HasSubstr("'" + path + "'"));
  }
}

TEST_F(TextReaderTest, MissingFileAndDirectoryAreUsageErrors) {
  const std::string missing = (dir_ / "absent.csv").string();
  EXPECT_EQ(message_of<UsageError>([&] { read_series(missing, with_fs(1.0)); }),
            "cannot open '" + missing + "': No such file or directory");
  EXPECT_EQ(message_of<UsageError>([&] { list_channels(missing); }),
            "cannot open '" + missing + "': No such file or directory");
  EXPECT_EQ(message_of<UsageError>([&] { read_series(dir_.path().string(), with_fs(1.0)); }),
            "cannot open '" + dir_.path().string() + "': Is a directory");
}

TEST_F(TextReaderTest, LongFileIsReadCompletely) {
  // more than one 1 MiB block, so lines straddle block boundaries
  std::string content = "t rate\n";
  for (int i = 0; i < 100000; ++i) {
    content += std::to_string(i * 0.001) + " " + std::to_string(i % 977) + "\n";
  }
  const std::string path = write("long.txt", content);
  const Series series = read_series(path, {});
  ASSERT_EQ(series.values.size(), 100000u);
  for (std::size_t i = 0; i < series.values.size(); ++i) {
    ASSERT_EQ(series.values[i], static_cast<double>(i % 977)) << "sample " << i + 1;
  }
  EXPECT_NEAR(series.sample_rate_hz, 1000.0, 1e-6);
}

TEST_F(TextReaderTest, DashReadsTextFromStandardInput) {
  const std::string path = write("stdin.csv", "t,rate\n0,4\n0.5,5\n");
  ASSERT_NE(std::freopen(path.c_str(), "rb", stdin), nullptr);
  const Series series = read_series("-", {});
  EXPECT_EQ(series.path, "-");
  EXPECT_THAT(series.values, ElementsAre(4, 5));
  EXPECT_DOUBLE_EQ(series.sample_rate_hz, 2.0);
  // messages call it "standard input"
  ASSERT_NE(std::freopen(path.c_str(), "rb", stdin), nullptr);
  ReadOptions options;
  options.channel = "Y9";
  EXPECT_EQ(message_of<DataError>([&] { read_series("-", options); }),
            "standard input: no channel column 'Y9'; columns: t, rate");
}

TEST(ChannelNames, SayWhichSensorAChannelIs) {
  for (const char* gyro :
       {"gyro_x", "GyroZ", "gx", "g_y", "wz", "omega_x", "angular_velocity.y", "gyro_x_dps"}) {
    EXPECT_EQ(sensor_by_name(gyro), Sensor::gyroscope) << gyro;
  }
  for (const char* accel :
       {"accel_x", "AccY", "ax", "a_z", "linear_acceleration.z", "accel_z_mg"}) {
    EXPECT_EQ(sensor_by_name(accel), Sensor::accelerometer) << accel;
  }
  for (const char* other : {"Y1", "rate", "2", "t", "temperature", "T1", "g", "axis", "gps_x"}) {
    EXPECT_FALSE(sensor_by_name(other)) << other;
  }
  EXPECT_EQ(inertial_channels({"t", "gx", "gy", "ax", "temperature"}),
            (std::vector<std::string>{"gx", "gy", "ax"}));
}

}  // namespace
}  // namespace foglab::io
