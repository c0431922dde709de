// Tests of reading raw little-endian float32/float64 records.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/io/reader.h"
#include "support/expect.h"
#include "reader_fixture.h"
#include "support/files.h"

namespace foglab::io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

using test::message_of;

// Little-endian bytes of the values, whatever the host's byte order.
template <typename T>
std::string little_endian_bytes(const std::vector<T>& values) {
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  std::string out;
  for (T value : values) {
    Bits bits = std::bit_cast<Bits>(value);
    for (std::size_t k = 0; k < sizeof(T); ++k) {
      out.push_back(static_cast<char>(bits & 0xff));
      bits = static_cast<Bits>(bits >> 8);
    }
  }
  return out;
}

using RawReaderTest = ReaderTest;

TEST_F(RawReaderTest, Float64RoundTrip) {
  const std::vector<double> values = {1.5, -2.25, 1e-300, 123456789.123456789, 0.0};
  const std::string path = write("rec.f64", little_endian_bytes(values));
  const Series series = read_series(path, with_fs(400.0));
  EXPECT_EQ(series.path, path);
  EXPECT_EQ(series.channel, "1");
  EXPECT_THAT(series.values, ElementsAreArray(values));
  EXPECT_EQ(series.sample_rate_hz, 400.0);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::option);
  EXPECT_THAT(series.available_channels, ElementsAre("1"));
  EXPECT_THAT(list_channels(path), ElementsAre("1"));
}

TEST_F(RawReaderTest, Float32RoundTrip) {
  const std::vector<float> values = {0.5f, -3.0f, 1.0e-7f, 16777216.0f};
  const std::string path = write("rec.F32", little_endian_bytes(values));  // any case
  const Series series = read_series(path, with_fs(1.0));
  EXPECT_THAT(series.values, ElementsAre(0.5, -3.0, static_cast<double>(1.0e-7f), 16777216.0));
}

TEST_F(RawReaderTest, LongRecordSpansSeveralBlocks) {
  std::vector<float> values(300000);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(i % 1000);
  const std::string path = write("long.f32", little_endian_bytes(values));
  const Series series = read_series(path, with_fs(1.0));
  ASSERT_EQ(series.values.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    ASSERT_EQ(series.values[i], static_cast<double>(values[i])) << "sample " << i + 1;
  }
}

TEST_F(RawReaderTest, FormatOptionOverridesTheExtension) {
  const std::string path = write("rec.bin", little_endian_bytes(std::vector<float>{2.0f, 4.0f}));
  ReadOptions options = with_fs(1.0);
  options.format = InputFormat::f32;
  EXPECT_THAT(read_series(path, options).values, ElementsAre(2.0, 4.0));
  options.format = InputFormat::f64;
  EXPECT_EQ(read_series(path, options).values.size(), 1u);
}

TEST_F(RawReaderTest, TruncatedFileIsADataError) {
  std::string bytes = little_endian_bytes(std::vector<double>(125, 1.0));
  bytes.push_back('\0');
  const std::string path = write("cut.f64", bytes);
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, with_fs(1.0)); }),
            "'" + path +
                "': truncated: 1001 bytes is not a multiple of 8 (the size of one "
                "float64 sample)");
  const std::string path32 = write("cut.f32", "abcdef");
  EXPECT_THAT(message_of<DataError>([&] { read_series(path32, with_fs(1.0)); }),
              HasSubstr("truncated: 6 bytes is not a multiple of 4"));
}

TEST_F(RawReaderTest, EmptyFileIsADataError) {
  const std::string path = write("empty.f64", "");
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, with_fs(1.0)); }),
            "'" + path + "': the file is empty (no samples)");
}

TEST_F(RawReaderTest, MissingSampleRateIsAUsageError) {
  const std::string path = write("rec.f64", little_endian_bytes(std::vector<double>{1.0}));
  EXPECT_EQ(message_of<UsageError>([&] { read_series(path, {}); }),
            "'" + path + "': raw input has no sample rate: give ReadOptions::sample_rate_hz");
}

TEST_F(RawReaderTest, OnlyChannelOneExists) {
  const std::string path = write("rec.f64", little_endian_bytes(std::vector<double>{1.0}));
  ReadOptions options = with_fs(1.0);
  options.channel = "1";
  EXPECT_EQ(read_series(path, options).values.size(), 1u);
  options.channel = "Y1";
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, options); }),
            "'" + path + "': no channel 'Y1': a raw file has one channel, '1'");
  options.channel.clear();
  options.time_channel = "t";
  EXPECT_THAT(message_of<UsageError>([&] { read_series(path, options); }),
              HasSubstr("raw input has no time column"));
}

TEST_F(RawReaderTest, NanIsReportedWithItsSampleIndex) {
  const std::vector<double> values = {1.0, std::numeric_limits<double>::quiet_NaN(), 2.0};
  const std::string path = write("nan.f64", little_endian_bytes(values));
  EXPECT_EQ(message_of<DataError>([&] { read_series(path, with_fs(1.0)); }),
            "'" + path + "': sample 2 of '1' is NaN");
  const std::vector<float> infinite = {1.0f, 2.0f, std::numeric_limits<float>::infinity()};
  const std::string path32 = write("inf.f32", little_endian_bytes(infinite));
  EXPECT_EQ(message_of<DataError>([&] { read_series(path32, with_fs(1.0)); }),
            "'" + path32 + "': sample 3 of '1' is +Inf");
}

TEST_F(RawReaderTest, UnitsAreConvertedToDegPerHour) {
  const std::string path = write("dps.f64", little_endian_bytes(std::vector<double>{1.0, -2.0}));
  ReadOptions options = with_fs(1.0);
  options.unit = RateUnit::deg_per_second;
  EXPECT_THAT(read_series(path, options).values, ElementsAre(3600.0, -7200.0));
  options.unit = RateUnit::rad_per_second;
  const Series series = read_series(path, options);
  EXPECT_DOUBLE_EQ(series.values[0], kDegPerRad * 3600.0);
  EXPECT_DOUBLE_EQ(series.values[1], -2.0 * kDegPerRad * 3600.0);
}

TEST_F(RawReaderTest, OverflowOnConversionIsADataError) {
  const std::string path = write("huge.f64", little_endian_bytes(std::vector<double>{1e306}));
  ReadOptions options = with_fs(1.0);
  options.unit = RateUnit::deg_per_second;
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("sample 1 of '1' (1e+306 deg/s) overflows when converted to deg/h"));
}

TEST_F(RawReaderTest, DashWithARawFormatReadsBinaryStandardInput) {
  const std::vector<double> values = {3.0, 1.0, 4.0, 1.0, 5.0};
  const std::string path = write("stdin.f64", little_endian_bytes(values));
  ASSERT_NE(std::freopen(path.c_str(), "rb", stdin), nullptr);
  ReadOptions options = with_fs(50.0);
  options.format = InputFormat::f64;
  const Series series = read_series("-", options);
  EXPECT_EQ(series.path, "-");
  EXPECT_THAT(series.values, ElementsAreArray(values));

  const std::string cut = write("stdin_cut.f64", little_endian_bytes(values) + "xyz");
  ASSERT_NE(std::freopen(cut.c_str(), "rb", stdin), nullptr);
  EXPECT_EQ(message_of<DataError>([&] { read_series("-", options); }),
            "standard input: truncated: 43 bytes is not a multiple of 8 (the size of one "
            "float64 sample)");
}

}  // namespace
}  // namespace foglab::io
