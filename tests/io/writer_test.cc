// Tests of the atomic writers: MAT v5, CSV and raw round trips through the
// readers, and that a failed write leaves no file.
#include "foglab/io/writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <matio.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/io/reader.h"
#include "support/expect.h"
#include "support/files.h"
#include "support/noise.h"

namespace foglab::io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;
using test::message_of;

using test::ramp;

std::vector<double> awkward(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = std::sin(0.37 * static_cast<double>(i)) * 1e3 / 3.0;
  v[0] = 0.1 + 0.2;
  v[1] = -std::numeric_limits<double>::denorm_min();
  v[2] = 1.0e300;
  return v;
}

ReadOptions channel(const std::string& name) {
  ReadOptions options;
  options.channel = name;
  return options;
}

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  return names;
}

TEST(WriteMat, EveryVariableRoundTripsThroughTheReader) {
  test::TempDir dir;
  const std::string path = dir.file("FOG1_1.mat");
  const double f = 10.0;
  const std::vector<double> t = ramp(1000, 0.0, 0.1);
  const std::vector<double> y1 = awkward(1000);
  const std::vector<double> y2 = ramp(1000, -5.0, 0.01);
  const std::vector<double> t1(1000, 25.0);
  const std::vector<double> t2 = ramp(1000, 20.0, 0.01);
  const std::vector<NamedVector> vars = {{"f", {&f, 1}}, {"t", t},   {"Y1", y1},
                                         {"Y2", y2},     {"T1", t1}, {"T2", t2}};
  write_mat(path, vars);

  for (const NamedVector& v : vars) {
    if (v.name == "f") continue;
    const Series s = read_series(path, channel(v.name));
    EXPECT_EQ(s.channel, v.name);
    EXPECT_THAT(s.values, ElementsAreArray(v.values.begin(), v.values.end())) << v.name;
    EXPECT_EQ(s.sample_rate_hz, 10.0);
    EXPECT_EQ(s.sample_rate_source, SampleRateSource::variable_f);
  }
  EXPECT_THAT(list_channels(path), ElementsAre("t", "Y1", "Y2", "T1", "T2"));
  EXPECT_THAT(files_in(dir.path()), ElementsAre("FOG1_1.mat"));  // no temporary left
}

TEST(WriteMat, VectorsAreColumnsAndFIsAScalar) {
  test::TempDir dir;
  const std::string path = dir.file("shape.mat");
  const double f = 20.0;
  const std::vector<double> y = ramp(7, 1.0, 1.0);
  const std::vector<NamedVector> vars = {{"f", {&f, 1}}, {"Y1", y}};
  write_mat(path, vars);

  mat_t* mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
  ASSERT_NE(mat, nullptr);
  EXPECT_EQ(Mat_GetVersion(mat), MAT_FT_MAT5);
  matvar_t* fv = Mat_VarRead(mat, "f");
  ASSERT_NE(fv, nullptr);
  EXPECT_EQ(fv->rank, 2);
  EXPECT_EQ(fv->dims[0], 1u);
  EXPECT_EQ(fv->dims[1], 1u);
  EXPECT_EQ(fv->class_type, MAT_C_DOUBLE);
  EXPECT_EQ(*static_cast<const double*>(fv->data), 20.0);
  Mat_VarFree(fv);
  matvar_t* yv = Mat_VarReadInfo(mat, "Y1");
  ASSERT_NE(yv, nullptr);
  EXPECT_EQ(yv->dims[0], 7u);
  EXPECT_EQ(yv->dims[1], 1u);
  Mat_VarFree(yv);
  Mat_Close(mat);
}

TEST(WriteMat, ReplacesAnExistingFileWhole) {
  test::TempDir dir;
  const std::string path = dir.file("a.mat");
  const std::vector<double> a = ramp(100, 0.0, 1.0);
  const std::vector<double> b = ramp(3, 7.0, 1.0);
  write_mat(path, std::vector<NamedVector>{{"Y1", a}});
  write_mat(path, std::vector<NamedVector>{{"Y1", b}});
  ReadOptions options;
  options.sample_rate_hz = 1.0;
  EXPECT_THAT(read_series(path, options).values, ElementsAre(7.0, 8.0, 9.0));
}

TEST(WriteMat, FailureInAMissingDirectoryLeavesNoFileAndNamesThePath) {
  test::TempDir dir;
  const std::string path = (dir / "missing" / "out.mat").string();
  const std::vector<double> y = ramp(10, 0.0, 1.0);
  const std::string message = message_of<UsageError>(
      [&] { write_mat(path, std::vector<NamedVector>{{"Y1", y}}); });
  EXPECT_THAT(message, HasSubstr("cannot write '" + path + "'"));
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(WriteMat, RejectsBadNamesAndEmptyVectorsWithoutWriting) {
  test::TempDir dir;
  const std::string path = dir.file("bad.mat");
  const std::vector<double> y = ramp(10, 0.0, 1.0);
  EXPECT_THAT(message_of<UsageError>(
                  [&] { write_mat(path, std::vector<NamedVector>{{"1abc", y}}); }),
              HasSubstr("'1abc' is not a valid MATLAB variable name"));
  EXPECT_THAT(message_of<UsageError>(
                  [&] { write_mat(path, std::vector<NamedVector>{{"Y", y}, {"Y", y}}); }),
              HasSubstr("given twice"));
  EXPECT_THAT(message_of<UsageError>(
                  [&] { write_mat(path, std::vector<NamedVector>{{"Y", {}}}); }),
              HasSubstr("'Y' is empty"));
  EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(WriteCsv, ColumnsRoundTripExactlyThroughTheTextReader) {
  test::TempDir dir;
  const std::string path = dir.file("run.csv");
  const std::vector<double> t = ramp(500, 0.0, 0.05);
  const std::vector<double> rate = awkward(500);
  const std::vector<double> temp = ramp(500, 20.0, 0.02);
  const std::vector<NamedVector> cols = {{"t", t}, {"rate", rate}, {"temperature", temp}};
  const std::vector<std::string> comments = {"units: t s, rate deg/h, temperature degC"};
  write_csv(path, cols, comments);

  const std::string text = test::read_file(path);
  EXPECT_EQ(text.rfind("# units: t s, rate deg/h, temperature degC\nt,rate,temperature\n", 0), 0u);
  EXPECT_THAT(list_channels(path), ElementsAre("t", "rate", "temperature"));
  const Series r = read_series(path, channel("rate"));
  EXPECT_THAT(r.values, ElementsAreArray(rate));
  EXPECT_NEAR(r.sample_rate_hz, 20.0, 1e-9);
  EXPECT_THAT(read_series(path, channel("temperature")).values, ElementsAreArray(temp));
}

TEST(WriteCsv, UnequalColumnsAreRefusedWithoutAFile) {
  test::TempDir dir;
  const std::string path = dir.file("x.csv");
  const std::vector<double> a = ramp(5, 0.0, 1.0);
  const std::vector<double> b = ramp(4, 0.0, 1.0);
  EXPECT_THAT(message_of<UsageError>(
                  [&] { write_csv(path, std::vector<NamedVector>{{"a", a}, {"b", b}}); }),
              HasSubstr("cannot write '" + path + "': column 'b' has 4 values"));
  EXPECT_FALSE(fs::exists(path));
}

TEST(WriteRaw, Float64RoundTripsBitForBit) {
  test::TempDir dir;
  const std::string path = dir.file("rate.f64");
  const std::vector<double> v = awkward(333);
  write_raw(path, v, RawType::f64);
  EXPECT_EQ(fs::file_size(path), 333u * 8u);
  ReadOptions options;
  options.sample_rate_hz = 100.0;
  EXPECT_THAT(read_series(path, options).values, ElementsAreArray(v));
}

TEST(WriteRaw, Float32HoldsTheRoundedValues) {
  test::TempDir dir;
  const std::string path = dir.file("rate.f32");
  const std::vector<double> v = ramp(100, -3.0, 0.1);
  write_raw(path, v, RawType::f32);
  EXPECT_EQ(fs::file_size(path), 400u);
  ReadOptions options;
  options.sample_rate_hz = 1.0;
  const Series s = read_series(path, options);
  ASSERT_EQ(s.values.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(s.values[i], static_cast<double>(static_cast<float>(v[i])));
  }
}

TEST(RawFileWriter, AppendsBlocksAndAppearsOnlyOnCommit) {
  test::TempDir dir;
  const std::string path = dir.file("stream.f64");
  {
    RawFileWriter writer(path, RawType::f64);
    writer.append(ramp(10, 0.0, 1.0));
    writer.append(ramp(5, 10.0, 1.0));
    EXPECT_FALSE(fs::exists(path));
    EXPECT_EQ(writer.samples(), 15u);
    writer.commit();
  }
  ReadOptions options;
  options.sample_rate_hz = 1.0;
  EXPECT_THAT(read_series(path, options).values, ElementsAreArray(ramp(15, 0.0, 1.0)));
}

TEST(RawFileWriter, AbandonedWriteLeavesNothing) {
  test::TempDir dir;
  const std::string path = dir.file("abandoned.f32");
  {
    RawFileWriter writer(path, RawType::f32);
    writer.append(ramp(10, 0.0, 1.0));
  }  // destroyed without commit, as when an exception unwinds
  EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(WriteRaw, FailureInAMissingDirectoryNamesThePath) {
  test::TempDir dir;
  const std::string path = (dir / "no" / "such" / "x.f64").string();
  const std::vector<double> v = ramp(4, 0.0, 1.0);
  EXPECT_THAT(message_of<UsageError>([&] { write_raw(path, v, RawType::f64); }),
              HasSubstr("cannot write '" + path + "'"));
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(files_in(dir.path()).empty());
}

}  // namespace
}  // namespace foglab::io
