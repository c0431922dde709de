// Tests of reading MAT files v4, v5, v7 (compressed) and v7.3 (HDF5).
//
// Every file is written here with matio into a temporary directory, so the
// tests show what the reader makes of each layout, class and damage. The
// damaged files are made from good ones by cutting, patching or scrambling
// bytes; matio 1.5.23 reads some of them "successfully" (a short read with
// status 0), which is what the reader's own checks are for.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <matio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/io/reader.h"
#include "support/expect.h"
#include "support/files.h"
#include "support/mat_writer.h"
#include "support/noise.h"

namespace foglab::io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::UnorderedElementsAre;

using test::message_of;
using test::TempDir;

std::vector<unsigned char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

using test::MatWriter;

using test::ramp;

// The lab's layout f, t, Y1, Y2, T1, T2 at 100 Hz.
void write_lab_file(MatWriter& mat, std::size_t n = 50) {
  mat.scalar("f", 100.0);
  mat.vector("t", ramp(n, 0.0, 0.01));
  mat.vector("Y1", ramp(n, 1.5, 0.25));
  mat.vector("Y2", ramp(n, -3.0, 0.5));
  mat.vector("T1", ramp(n, 20.0, 0.01));
  mat.vector("T2", ramp(n, 21.0, 0.01));
}

// --- every version -------------------------------------------------------

struct Version {
  const char* label;
  mat_ft version;
  matio_compression compression;
};

class MatVersionTest : public ::testing::TestWithParam<Version> {
 protected:
  std::string make(const std::function<void(MatWriter&)>& fill) {
    const std::string path = dir_.file(std::string(GetParam().label) + ".mat");
    MatWriter mat(path, GetParam().version, GetParam().compression);
    fill(mat);
    mat.close();
    return path;
  }
  bool is_v4() const { return GetParam().version == MAT_FT_MAT4; }
  TempDir dir_;
};

TEST_P(MatVersionTest, LabLayoutGivesY1AndTheRateFromF) {
  const std::string path = make([](MatWriter& mat) { write_lab_file(mat); });
  const Series series = read_series(path, {});
  EXPECT_EQ(series.path, path);
  EXPECT_EQ(series.channel, "Y1");
  EXPECT_THAT(series.values, ElementsAreArray(ramp(50, 1.5, 0.25)));
  EXPECT_DOUBLE_EQ(series.sample_rate_hz, 100.0);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::variable_f);
  // v7.3 lists variables in HDF5's name order, the others in file order
  EXPECT_THAT(series.available_channels, UnorderedElementsAre("t", "Y1", "Y2", "T1", "T2"));
  EXPECT_THAT(list_channels(path), UnorderedElementsAre("t", "Y1", "Y2", "T1", "T2"));
}

TEST_P(MatVersionTest, ChannelOptionPicksAnyVariable) {
  const std::string path = make([](MatWriter& mat) { write_lab_file(mat); });
  ReadOptions options;
  options.channel = "T2";
  const Series series = read_series(path, options);
  EXPECT_EQ(series.channel, "T2");
  EXPECT_THAT(series.values, ElementsAreArray(ramp(50, 21.0, 0.01)));
}

TEST_P(MatVersionTest, RateComesFromTheTimeVariableWithoutF) {
  const std::string path = make([](MatWriter& mat) {
    mat.vector("t", ramp(40, 10.0, 0.002));
    mat.vector("Y1", ramp(40, 0.0, 1.0));
  });
  const Series series = read_series(path, {});
  EXPECT_NEAR(series.sample_rate_hz, 500.0, 1e-9);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::time_channel);
  EXPECT_EQ(series.sample_rate_channel, "t");
  EXPECT_EQ(series.channel, "Y1");  // t is time, so Y1 is the only data channel
}

TEST_P(MatVersionTest, RateOptionOverridesF) {
  const std::string path = make([](MatWriter& mat) { write_lab_file(mat); });
  ReadOptions options;
  options.sample_rate_hz = 2000.0;
  const Series series = read_series(path, options);
  EXPECT_EQ(series.sample_rate_hz, 2000.0);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::option);
}

TEST_P(MatVersionTest, RowAndColumnVectorsReadTheSame) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.vector("row", ramp(7, 1.0, 1.0), /*row=*/true);
    mat.vector("col", ramp(7, 1.0, 1.0));
  });
  ReadOptions options;
  options.channel = "row";
  const Series row = read_series(path, options);
  options.channel = "col";
  const Series col = read_series(path, options);
  EXPECT_THAT(row.values, ElementsAre(1, 2, 3, 4, 5, 6, 7));
  EXPECT_EQ(row.values, col.values);
}

TEST_P(MatVersionTest, SingleAndIntegerClassesBecomeDoubles) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.vector<float>("Y1", {0.5f, -1.25f, 3.0e6f});
    mat.vector<std::int16_t>("counts", {-32768, 0, 32767}, /*row=*/true);
    mat.vector<std::int32_t>("big", {-2000000000, 7, 2000000000});
    mat.vector<std::uint8_t>("small", {0, 128, 255});
  });
  ReadOptions options;
  EXPECT_THAT(read_series(path, options).values, ElementsAre(0.5, -1.25, 3.0e6));
  options.channel = "counts";
  EXPECT_THAT(read_series(path, options).values, ElementsAre(-32768, 0, 32767));
  options.channel = "big";
  EXPECT_THAT(read_series(path, options).values, ElementsAre(-2e9, 7, 2e9));
  options.channel = "small";
  EXPECT_THAT(read_series(path, options).values, ElementsAre(0, 128, 255));
}

TEST_P(MatVersionTest, TheOnlyDataVariableIsTheDefaultWhateverItsName) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.vector("t", ramp(5, 0.0, 0.1));
    mat.vector("gyro_x", ramp(5, 1.0, 1.0));
    mat.vector("T", ramp(5, 30.0, 0.0));
    mat.vector("T1", ramp(5, 30.0, 0.0));
  });
  EXPECT_EQ(read_series(path, {}).channel, "gyro_x");
}

TEST_P(MatVersionTest, SeveralDataVariablesWithoutY1AreAnError) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.vector("A", ramp(5, 1.0, 1.0));
    mat.vector("B", ramp(5, 1.0, 1.0));
  });
  const std::string message = message_of<DataError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("'" + path + "'"));
  EXPECT_THAT(message, HasSubstr("several data channels"));
  EXPECT_THAT(message, HasSubstr("A"));
  EXPECT_THAT(message, HasSubstr("B"));
  EXPECT_THAT(message, HasSubstr("choose one with ReadOptions::channel"));
}

TEST_P(MatVersionTest, UnknownVariableListsTheVariablesPresent) {
  const std::string path = make([](MatWriter& mat) { write_lab_file(mat, 5); });
  ReadOptions options;
  options.channel = "Y3";
  const std::string message = message_of<DataError>([&] { read_series(path, options); });
  EXPECT_THAT(message, HasSubstr("'" + path + "'"));
  EXPECT_THAT(message, HasSubstr("no variable 'Y3'; variables present: "));
  for (const char* name : {"f", "t", "Y1", "Y2", "T1", "T2"}) {
    EXPECT_THAT(message, HasSubstr(name));
  }
}

TEST_P(MatVersionTest, MatrixAndComplexVariablesAreRejectedByName) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.matrix("M", 3, 4);
    mat.complex_vector("Z", std::vector<double>(6, 1.0), std::vector<double>(6, 2.0));
  });
  ReadOptions options;
  options.channel = "M";
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("variable 'M' is 3x4 double matrix; expected a real numeric vector"));
  options.channel = "Z";
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("variable 'Z' is complex 6x1 double; expected a real numeric vector"));
}

TEST_P(MatVersionTest, NoDataChannelListsWhatIsThere) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.matrix("M", 3, 4);
  });
  const std::string message = message_of<DataError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("no data channel"));
  EXPECT_THAT(message, HasSubstr("M (3x4 double matrix)"));
  EXPECT_THAT(message, HasSubstr("f (1x1 double)"));
}

TEST_P(MatVersionTest, TimesThatJitterAreReadOnTheirGridBesideF) {
  // a logger's times: +-30 % of a 10 ms step about the grid, one sample lost before the 301st
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<double> t;
  for (int k = 0; k < 2001; ++k) {
    if (k != 300) t.push_back((k + jitter(random)) / 100.0);
  }
  std::vector<double> y = ramp(2000, 0.0, 1.0);
  for (const bool with_f : {false, true}) {
    SCOPED_TRACE(with_f ? "with f" : "without f");
    const std::string path = make([&](MatWriter& mat) {
      if (with_f) mat.scalar("f", 100.0);
      mat.vector("t", t);
      mat.vector("Y1", y);
    });
    const Series series = read_series(path, {});
    ASSERT_EQ(series.gaps.size(), 1u);
    EXPECT_EQ(series.gaps[0].before_sample, 300);
    EXPECT_EQ(series.gaps[0].missing_samples, 1);
    EXPECT_EQ(series.values.size(), 2000u);
    ASSERT_TRUE(series.time_jitter.has_value());
    EXPECT_EQ(series.time_jitter->rows_dropped, 0u);
    EXPECT_NEAR(series.sample_rate_hz, 100.0, with_f ? 0.0 : 0.01);
    EXPECT_EQ(series.sample_rate_source,
              with_f ? SampleRateSource::variable_f : SampleRateSource::time_channel);
  }
}

TEST_P(MatVersionTest, TimeWithAGapListsTheMissingSamples) {
  std::vector<double> t = ramp(20, 0.0, 0.01);
  for (std::size_t i = 12; i < t.size(); ++i) t[i] += 0.01;  // one sample missing before the 13th
  const std::string path = make([&](MatWriter& mat) {
    mat.vector("t", t);
    mat.vector("Y1", ramp(20, 0.0, 1.0));
  });
  const Series series = read_series(path, {});
  ASSERT_EQ(series.gaps.size(), 1u);
  EXPECT_EQ(series.gaps[0].before_sample, 12);
  EXPECT_EQ(series.gaps[0].missing_samples, 1);
  EXPECT_NEAR(series.sample_rate_hz, 100.0, 1e-9);
  // beside f, the time vector's gaps are the record's too
  const std::string with_f = make([&](MatWriter& mat) {
    mat.scalar("f", 100.0);
    mat.vector("t", t);
    mat.vector("Y1", ramp(20, 0.0, 1.0));
  });
  EXPECT_EQ(read_series(with_f, {}).gaps.size(), 1u);
  // an irregular step (1.3 samples) is still an error naming the sample
  t = ramp(20, 0.0, 0.01);
  for (std::size_t i = 12; i < t.size(); ++i) t[i] += 0.003;
  const std::string odd = make([&](MatWriter& mat) {
    mat.vector("t", t);
    mat.vector("Y1", ramp(20, 0.0, 1.0));
  });
  const std::string message = message_of<DataError>([&] { read_series(odd, {}); });
  EXPECT_THAT(message, HasSubstr("'" + odd + "'"));
  EXPECT_THAT(message, HasSubstr("not uniformly sampled at sample 13 of 't'"));
  EXPECT_THAT(message, HasSubstr("0.11 s -> 0.123 s"));
  EXPECT_THAT(message, HasSubstr("expected 0.01 s"));
}

TEST_P(MatVersionTest, NonMonotonicTimeIsReported) {
  std::vector<double> t = ramp(20, 0.0, 0.5);
  t[7] = t[6];
  const std::string path = make([&](MatWriter& mat) {
    mat.vector("time", t);
    mat.vector("Y1", ramp(20, 0.0, 1.0));
  });
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, {}); }),
              HasSubstr("time is not increasing at sample 8 of 'time': 3 s follows 3 s"));
}

TEST_P(MatVersionTest, ExplicitTimeVariableIsUsedBeforeF) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 100.0);
    mat.vector("clock", ramp(10, 0.0, 0.25));
    mat.vector("Y1", ramp(10, 0.0, 1.0));
  });
  ReadOptions options;
  options.time_channel = "clock";
  const Series series = read_series(path, options);
  EXPECT_DOUBLE_EQ(series.sample_rate_hz, 4.0);
  EXPECT_EQ(series.sample_rate_source, SampleRateSource::time_channel);
  EXPECT_EQ(series.sample_rate_channel, "clock");
  options.time_channel = "tick";
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("no time variable 'tick'; variables present: "));
}

TEST_P(MatVersionTest, TimeOfADifferentLengthIsAnError) {
  const std::string path = make([](MatWriter& mat) {
    mat.vector("t", ramp(9, 0.0, 0.1));
    mat.vector("Y1", ramp(10, 0.0, 1.0));
  });
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, {}); }),
              HasSubstr("time variable 't' has 9 samples but 'Y1' has 10"));
}

TEST_P(MatVersionTest, NonPositiveFIsADataError) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", -5.0);
    mat.vector("Y1", ramp(10, 0.0, 1.0));
  });
  const std::string message = message_of<DataError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("'" + path + "'"));
  EXPECT_THAT(message, HasSubstr("sample rate from variable f is -5 Hz"));
}

TEST_P(MatVersionTest, NoRateAnywhereAsksForFs) {
  const std::string path = make([](MatWriter& mat) { mat.vector("Y1", ramp(10, 0.0, 1.0)); });
  const std::string message = message_of<UsageError>([&] { read_series(path, {}); });
  EXPECT_THAT(message, HasSubstr("'" + path + "' has no sample rate"));
  EXPECT_THAT(message, HasSubstr("give ReadOptions::sample_rate_hz"));
}

TEST_P(MatVersionTest, NanSampleIsReportedWithItsIndex) {
  std::vector<double> y = ramp(30, 0.0, 1.0);
  y[16] = std::numeric_limits<double>::quiet_NaN();
  y[20] = std::numeric_limits<double>::infinity();
  const std::string path = make([&](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.vector("Y1", y);
  });
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, {}); }),
              HasSubstr("'" + path + "': sample 17 of 'Y1' is NaN"));
}

TEST_P(MatVersionTest, UnitsAreConvertedToDegPerHour) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.vector("Y1", std::vector<double>{1.0, -0.5});
  });
  ReadOptions options;
  options.unit = RateUnit::deg_per_second;
  EXPECT_THAT(read_series(path, options).values, ElementsAre(3600.0, -1800.0));
  options.unit = RateUnit::rad_per_second;
  const Series series = read_series(path, options);
  EXPECT_DOUBLE_EQ(series.values[0], kDegPerRad * 3600.0);
  EXPECT_DOUBLE_EQ(series.values[1], -0.5 * kDegPerRad * 3600.0);
}

INSTANTIATE_TEST_SUITE_P(AllVersions, MatVersionTest,
                         ::testing::Values(Version{"v4", MAT_FT_MAT4, MAT_COMPRESSION_NONE},
                                           Version{"v5", MAT_FT_MAT5, MAT_COMPRESSION_NONE},
                                           Version{"v7", MAT_FT_MAT5, MAT_COMPRESSION_ZLIB},
                                           Version{"v73", MAT_FT_MAT73, MAT_COMPRESSION_NONE}),
                         [](const auto& info) { return std::string(info.param.label); });

// --- classes only v5 and later can hold -----------------------------------

class MatV5PlusTest : public MatVersionTest {};

TEST_P(MatV5PlusTest, CharStructAndLogicalVariablesAreRejectedByName) {
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.text("label", "gyro1");
    mat.structure("meta", {1.0});
    mat.logical("ok", 3);
    mat.vector("Y1", ramp(4, 0.0, 1.0));
  });
  ReadOptions options;
  options.channel = "label";
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("variable 'label' is 1x5 char; expected a real numeric vector"));
  options.channel = "meta";
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("variable 'meta' is 1x1 struct"));
  options.channel = "ok";
  EXPECT_THAT(message_of<DataError>([&] { read_series(path, options); }),
              HasSubstr("variable 'ok' is 3x1 logical"));
  // ... and they never count as data channels
  EXPECT_EQ(read_series(path, {}).channel, "Y1");
  EXPECT_THAT(list_channels(path), ElementsAre("Y1"));
}

TEST_P(MatV5PlusTest, ContainersBesideTheDataDoNotStopTheReading) {
  // The structural check bounds a container's elements by its bytes (matio
  // allocates a pointer for each); containers as MATLAB writes them pass:
  // structure arrays with and without fields, a cell array of empty cells.
  const std::string path = make([](MatWriter& mat) {
    mat.scalar("f", 10.0);
    mat.structure_array("nofields", 5, 0);
    mat.structure_array("settings", 40, 3);
    mat.empty_cells("notes", 60);
    mat.vector("Y1", ramp(4, 0.0, 1.0));
  });
  const Series s = read_series(path, {});
  EXPECT_EQ(s.channel, "Y1");
  EXPECT_EQ(s.values.size(), 4u);
  EXPECT_THAT(list_channels(path), ElementsAre("Y1"));
}

INSTANTIATE_TEST_SUITE_P(V5AndLater, MatV5PlusTest,
                         ::testing::Values(Version{"v5", MAT_FT_MAT5, MAT_COMPRESSION_NONE},
                                           Version{"v7", MAT_FT_MAT5, MAT_COMPRESSION_ZLIB},
                                           Version{"v73", MAT_FT_MAT73, MAT_COMPRESSION_NONE}),
                         [](const auto& info) { return std::string(info.param.label); });

TEST(MatReader, CompressedV73IsRead) {
  TempDir dir;
  const std::string path = dir.file("z73.mat");
  {
    MatWriter mat(path, MAT_FT_MAT73, MAT_COMPRESSION_ZLIB);
    mat.scalar("f", 4.0);
    mat.vector<float>("Y1", {1.0f, 2.0f, 3.0f});
  }
  EXPECT_THAT(read_series(path, {}).values, ElementsAre(1, 2, 3));
}

// --- damaged files ---------------------------------------------------------

class DamagedMatTest : public ::testing::Test {
 protected:
  // A good file to damage: f then a 1000-sample Y1 (the last variable).
  std::string good(const std::string& name, mat_ft version, matio_compression compression) {
    const std::string path = dir_.file(name);
    MatWriter mat(path, version, compression);
    mat.scalar("f", 100.0);
    mat.vector("Y1", ramp(1000, 0.0, 0.001));
    return path;
  }
  // Reads `path` expecting a DataError whose message names the file and
  // says `what`; nothing may reach stderr on the way.
  void expect_data_error(const std::string& path, const std::string& what) {
    ::testing::internal::CaptureStderr();
    const std::string message = message_of<DataError>([&] { read_series(path, {}); });
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_THAT(message, HasSubstr("'" + path + "'"));
    EXPECT_THAT(message, HasSubstr(what));
    EXPECT_EQ(printed, "") << "matio/HDF5 printed to stderr";
  }
  TempDir dir_;
};

TEST_F(DamagedMatTest, GarbageWithAMatExtensionIsNotAMatFile) {
  const std::string path = dir_.file("garbage.mat");
  std::vector<unsigned char> bytes(3000);
  std::uint32_t state = 12345;
  for (auto& byte : bytes) {
    state = state * 1664525u + 1013904223u;
    byte = static_cast<unsigned char>(state >> 24);
  }
  write_bytes(path, bytes);
  expect_data_error(path, "not a MAT file");
}

TEST_F(DamagedMatTest, TextWithAMatExtensionIsNotAMatFile) {
  const std::string path = dir_.file("notes.mat");
  std::ofstream(path) << "t,Y1\n0,1\n";
  expect_data_error(path, "not a MAT file");
}

TEST_F(DamagedMatTest, EmptyFileIsReportedAsEmpty) {
  // matio opens an empty file as a v4 file without variables
  const std::string path = dir_.file("empty.mat");
  std::ofstream(path).close();
  expect_data_error(path, "the MAT file is empty");
}

TEST_F(DamagedMatTest, V5CutInsideTheHeaderIsNotAMatFile) {
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  bytes.resize(100);
  write_bytes(path, bytes);
  expect_data_error(path, "not a MAT file");
}

TEST_F(DamagedMatTest, V5CutInsideTheDataIsTruncated) {
  // matio lists Y1 and "reads" it with status 0, leaving the rest unset
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  bytes.resize(bytes.size() / 2);
  write_bytes(path, bytes);
  expect_data_error(path, "the MAT file is truncated: variable #2 (at byte 192)");
}

TEST_F(DamagedMatTest, V5MissingItsLastByteIsTruncated) {
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  bytes.pop_back();
  write_bytes(path, bytes);
  expect_data_error(path, "truncated");
}

TEST_F(DamagedMatTest, V4CutInsideTheDataIsTruncated) {
  const std::string path = good("v4.mat", MAT_FT_MAT4, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  bytes.resize(bytes.size() - 1);
  write_bytes(path, bytes);
  expect_data_error(path, "the MAT file is truncated: variable #2");
}

TEST_F(DamagedMatTest, CompressedV7CutInsideTheStreamIsTruncated) {
  const std::string path = good("v7.mat", MAT_FT_MAT5, MAT_COMPRESSION_ZLIB);
  std::vector<unsigned char> bytes = read_bytes(path);
  bytes.resize(bytes.size() - 200);
  write_bytes(path, bytes);
  expect_data_error(path, "the MAT file is truncated: variable #2");
}

TEST_F(DamagedMatTest, ScrambledCompressedDataIsCorrupt) {
  // The element sizes are intact, so only zlib notices; matio logs
  // "inflate returned data error" and returns 0.
  const std::string path = good("v7.mat", MAT_FT_MAT5, MAT_COMPRESSION_ZLIB);
  std::vector<unsigned char> bytes = read_bytes(path);
  for (std::size_t i = bytes.size() - 400; i < bytes.size() - 300; ++i) bytes[i] ^= 0x5a;
  write_bytes(path, bytes);
  expect_data_error(path, "corrupt");
}

TEST_F(DamagedMatTest, V5VariableClaimingMoreSamplesThanStoredIsCaught) {
  // Y1's dimensions say 1500 x 1 but only 1000 values follow: matio reads to
  // the end of the file, returns 0 and leaves the rest of the buffer unset.
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  // Y1 is the element at byte 192: tag (8), array flags (16), dims tag (8),
  // then the first dimension as int32.
  const std::size_t first_dim = 192 + 8 + 16 + 8;
  std::int32_t rows = 0;
  std::memcpy(&rows, bytes.data() + first_dim, 4);
  ASSERT_EQ(rows, 1000);
  rows = 1500;
  std::memcpy(bytes.data() + first_dim, &rows, 4);
  write_bytes(path, bytes);
  expect_data_error(path, "variable 'Y1' (1500x1 double) ends after 1000 samples");
}

TEST_F(DamagedMatTest, ImpossibleDimensionsAreRefusedBeforeAllocating) {
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  const std::int32_t rows = 2000000000;
  std::memcpy(bytes.data() + 192 + 8 + 16 + 8, &rows, 4);
  write_bytes(path, bytes);
  expect_data_error(path, "claims 2000000000x1 double elements, more than a");
}

TEST_F(DamagedMatTest, DimensionsClaimingMoreThanTheirElementAreRefusedBeforeAllocating) {
  // matio allocates 8 bytes per claimed 4-byte dimension before reading
  // them: this claim would have been an 8.5 GB allocation. matio reads the
  // array flags' tag in the long form whatever its type word says; the
  // fuzzing finding's type word read as a short tag, which had walked the
  // check past the dimensions.
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  // Y1's element at byte 192: tag (8), array flags (tag 8, flags 8), then
  // the dimensions' tag: type int32 (5) and its size, 8 bytes for two.
  const auto set_word = [&](std::size_t at, std::uint32_t value) {
    std::memcpy(bytes.data() + at, &value, 4);
  };
  std::uint32_t size = 0;
  std::memcpy(&size, bytes.data() + 192 + 8 + 16 + 4, 4);
  ASSERT_EQ(size, 8u);
  set_word(192 + 8, 0x00060000u);           // the flags' type word, as found
  set_word(192 + 8 + 12, 1u);               // the flags' second word
  set_word(192 + 8 + 16 + 4, 0xff000008u);  // the dimensions' size
  write_bytes(path, bytes);
  expect_data_error(path, "variable #2 (at byte 192) has dimensions claiming 4278190088 bytes");
}

TEST_F(DamagedMatTest, ACellArrayOfMoreElementsThanItsBytesIsRefusedBeforeAllocating) {
  // Y1 turned into a cell array (class 1) of 2,000,000 x 1: matio would
  // allocate a pointer per cell, which 8,000 bytes of data cannot hold.
  const std::string path = good("v5.mat", MAT_FT_MAT5, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  const std::size_t class_byte = 192 + 8 + 8;
  ASSERT_EQ(bytes[class_byte], MAT_C_DOUBLE);
  bytes[class_byte] = MAT_C_CELL;
  const std::int32_t rows = 2000000;
  std::memcpy(bytes.data() + 192 + 8 + 16 + 8, &rows, 4);
  write_bytes(path, bytes);
  expect_data_error(path, "variable #2 (at byte 192) claims 2000000 cells in the");
}

TEST_F(DamagedMatTest, AV73DriverBlockClaimingMoreThanTheFileIsRefusedBeforeHdf5) {
  // HDF5 allocates and zero-fills what a superblock's driver information
  // block claims: 4 GB of memory for this file (a fuzzing finding).
  const std::string path = good("v73.mat", MAT_FT_MAT73, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  // The superblock at 512: version 0, 8-byte offsets; its driver block
  // address (relative to the base address, 512) after the base, free-space
  // and end-of-file addresses, undefined (all ones) as written.
  ASSERT_EQ(bytes[512 + 8], 0);
  ASSERT_EQ(bytes[512 + 13], 8);
  const std::size_t driver_address = 512 + 24 + 3 * 8;
  ASSERT_EQ(bytes[driver_address], 0xff);
  // A block in the file's last 16 bytes: version 0, then a size of 4 GB.
  const std::uint64_t block_at = bytes.size() - 16;
  const std::uint64_t relative = block_at - 512;
  std::memcpy(bytes.data() + driver_address, &relative, 8);
  std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(block_at), bytes.end(), 0);
  const std::uint32_t claimed = 0xffffffffu;
  std::memcpy(bytes.data() + block_at + 4, &claimed, 4);
  write_bytes(path, bytes);
  expect_data_error(path, fmt::format("driver information block at byte {} claims 4294967311 "
                                      "bytes, more than the {}-byte file holds",
                                      block_at, bytes.size()));
}

TEST_F(DamagedMatTest, TruncatedV73IsReportedThroughHdf5) {
  // HDF5 opens the file only to log "File has been truncated"; without our
  // log function it would print its error stack to stderr.
  const std::string path = good("v73.mat", MAT_FT_MAT73, MAT_COMPRESSION_NONE);
  std::vector<unsigned char> bytes = read_bytes(path);
  bytes.resize(bytes.size() / 2);
  write_bytes(path, bytes);
  expect_data_error(path, "File has been truncated");
}

TEST_F(DamagedMatTest, MatCannotComeFromStandardInput) {
  ReadOptions options;
  options.format = InputFormat::mat;
  EXPECT_THAT(message_of<UsageError>([&] { read_series("-", options); }),
              HasSubstr("MAT files cannot be read from standard input"));
}

TEST_F(DamagedMatTest, MissingFileIsAUsageError) {
  const std::string path = dir_.file("absent.mat");
  EXPECT_EQ(message_of<UsageError>([&] { read_series(path, {}); }),
            "cannot open '" + path + "': No such file or directory");
}

}  // namespace
}  // namespace foglab::io
