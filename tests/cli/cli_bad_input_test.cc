// Every bad input of issue 2 through the CLI: a clear message naming the
// file (and the line, column, sample or variable), the right exit code
// (2 usage, 3 data), no crash, and no output file written or clobbered.
#include <gtest/gtest.h>
#include <matio.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/cli.h"

namespace foglab {
namespace {

using test::quote;

struct BadCase {
  std::string name;
  std::string file_content;  // written to the file named `file`
  std::string file;
  std::string args;  // after "allan FILE"
  int exit_code;
  std::vector<std::string> message;  // fragments the error must contain
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class CliBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliBadInput, ClearMessageExitCodeAndNoOutputLost) {
  const BadCase& c = GetParam();
  test::TempDir dir;
  if (!c.file.empty()) std::ofstream(dir / c.file, std::ios::binary) << c.file_content;
  // An existing output must survive a failed run untouched.
  std::ofstream(dir / "kept.json") << "previous result";
  const std::string file = c.file.empty() ? quote(dir / "missing.csv") : quote(dir / c.file);
  std::string args = "allan ";
  args.append(file).append(" ").append(c.args);
  args.append(" --json ").append(quote(dir / "kept.json"));
  args.append(" --csv ").append(quote(dir / "new.csv"));
  const test::CliRun r = test::run_foglab(args);
  EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
  // The library's messages name its API fields (ReadOptions::sample_rate_hz,
  // parse_tau_grid("...")); the CLI shows the flags that set them.
  EXPECT_EQ(r.err.find("::"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("parse_tau_grid"), std::string::npos) << r.err;
  for (const auto& fragment : c.message) {
    EXPECT_NE(r.err.find(fragment), std::string::npos)
        << "missing '" << fragment << "' in: " << r.err;
  }
  EXPECT_EQ(test::read_file(dir / "kept.json"), "previous result");
  EXPECT_FALSE(std::filesystem::exists(dir / "new.csv"));
  EXPECT_TRUE(r.out.empty()) << r.out;
  // No temporary files left behind either.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, c.file.empty() ? 1u : 2u);
}

INSTANTIATE_TEST_SUITE_P(
    Issue2, CliBadInput,
    ::testing::Values(
        BadCase{"EmptyFile", "", "empty.csv", "--fs 1", 3, {"empty.csv", "no data"}},
        BadCase{"HeaderOnly",
                "rate\n",
                "header.csv",
                "--fs 1",
                3,
                {"header.csv", "header", "no data rows"}},
        BadCase{"NonNumericCell",
                "t,rate\n0,1\n1,2\n2,abc\n",
                "cell.csv",
                "",
                3,
                {"cell.csv", "line 4", "column 2", "rate", "'abc'"}},
        // a NaN is a missing sample (a gap); a record of nothing else has none
        BadCase{"OnlyNaNSamples",
                "nan\nNaN\nnan\n",
                "nan.txt",
                "--fs 1",
                3,
                {"nan.txt", "channel '1'", "all 3 are NaN"}},
        BadCase{
            "InfSample", "1\n2\ninf\n4\n", "inf.txt", "--fs 1", 3, {"inf.txt", "sample 3", "Inf"}},
        BadCase{
            "TooFewSamplesForTheGrid",
            "1\n2\n3\n",
            "short.txt",
            "--fs 1",
            3,
            {"too few", "oadev", "10 clusters", "lower --min-clusters or list the taus in --taus"}},
        BadCase{"TooFewSamplesForAStatistic",
                "1\n2\n",
                "two.txt",
                "--fs 1 --kind hdev --taus 1",
                3,
                {"hdev needs at least 3 rate samples"}},
        BadCase{"TauBeyondTheRecord",
                "1\n2\n3\n4\n5\n6\n",
                "six.txt",
                "--fs 1 --taus 100",
                3,
                {"tau 100 s needs more samples"}},
        BadCase{"GarbageMatFile",
                std::string(3000, '\x5a'),
                "garbage.mat",
                "",
                3,
                {"garbage.mat", "not a MAT file"}},
        BadCase{"UnknownUnit",
                "1\n2\n3\n",
                "u.txt",
                "--fs 1 --units furlong/s",
                2,
                {"unknown unit 'furlong/s'", "deg/h, deg/s or rad/s", "m/s^2, g or mg"}},
        BadCase{"ZeroSampleRate", "1\n2\n3\n", "z.txt", "--fs 0", 2, {"--fs 0", "positive"}},
        BadCase{"NegativeSampleRate", "1\n2\n3\n", "n.txt", "--fs -5", 2, {"--fs -5"}},
        BadCase{"NegativeTau",
                "1\n2\n3\n",
                "t.txt",
                "--fs 1 --taus 1,-2",
                2,
                {"tau -2 s is not positive"}},
        BadCase{"ZeroTau", "1\n2\n3\n", "t0.txt", "--fs 1 --taus 0", 2, {"not positive"}},
        BadCase{"UnknownStatistic",
                "1\n2\n3\n",
                "k.txt",
                "--fs 1 --kind allan",
                2,
                {"unknown statistic 'allan'"}},
        BadCase{"MissingFile", "", "", "--fs 1", 2, {"cannot open", "missing.csv"}},
        BadCase{"RawWithoutSampleRate",
                std::string(64, '\0'),
                "raw.f64",
                "",
                2,
                {"raw.f64", "raw input has no sample rate: give --fs"}},
        BadCase{"TextWithoutSampleRate",
                "1\n2\n3\n",
                "nofs.txt",
                "",
                2,
                {"nofs.txt", "(no time column t, time or time_s): give --fs"}},
        BadCase{"ColumnsWithoutAPreferredName",
                "a,b\n1,2\n3,4\n",
                "ab.csv",
                "--fs 1",
                3,
                {"ab.csv", "choose one with --channel (a name or a 1-based index)"}},
        BadCase{"TimeColumnWithAnIrregularStep",
                "t,rate\n0,1\n1,2\n2,3\n3.3,4\n4.3,5\n",
                "gap.csv",
                "",
                3,
                {"gap.csv", "give the sample rate [Hz] in --fs (the time is then ignored)"}},
        BadCase{"UnknownTauGrid",
                "1\n2\n3\n",
                "g.txt",
                "--fs 1 --taus sometimes",
                2,
                {"--taus 'sometimes': expected octave, decade, all"}},
        BadCase{"NoClusters",
                "1\n2\n3\n",
                "c.txt",
                "--fs 1 --min-clusters 0",
                2,
                {"--min-clusters 0 must be at least 1"}},
        BadCase{"TruncatedRaw",
                std::string(63, '\0'),
                "cut.f64",
                "--fs 1",
                3,
                {"cut.f64", "not a multiple of 8"}}),
    [](const auto& info) { return info.param.name; });

std::filesystem::path write_mat(const test::TempDir& dir, const std::string& name, double fs,
                                std::size_t samples, mat_ft version = MAT_FT_MAT5) {
  const auto path = dir / name;
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, version);
  std::vector<double> y(samples, 1.0);
  for (std::size_t i = 0; i < samples; ++i) y[i] = static_cast<double>(i % 7);
  size_t scalar[2] = {1, 1};
  size_t dims[2] = {samples, 1};
  matvar_t* f = Mat_VarCreate("f", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, scalar, &fs, 0);
  matvar_t* v = Mat_VarCreate("Y1", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, y.data(), 0);
  matvar_t* t = Mat_VarCreate("T1", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, y.data(), 0);
  Mat_VarWrite(mat, f, MAT_COMPRESSION_NONE);
  Mat_VarWrite(mat, v, MAT_COMPRESSION_NONE);
  Mat_VarWrite(mat, t, MAT_COMPRESSION_NONE);
  Mat_VarFree(f);
  Mat_VarFree(v);
  Mat_VarFree(t);
  Mat_Close(mat);
  return path;
}

TEST(CliBadMat, UnknownVariableListsTheVariablesPresent) {
  test::TempDir dir;
  const auto path = write_mat(dir, "lab.mat", 10.0, 100);
  const test::CliRun r = test::run_foglab("allan " + quote(path) + " --channel Y7");
  EXPECT_EQ(r.exit_code, 3);
  for (const char* s : {"lab.mat", "Y7", "f", "Y1", "T1"}) {
    EXPECT_NE(r.err.find(s), std::string::npos) << s << " in " << r.err;
  }
}

TEST(CliBadMat, TruncatedFilesOfEveryVersionAreDataErrors) {
  for (const mat_ft version : {MAT_FT_MAT5, MAT_FT_MAT73}) {
    test::TempDir dir;
    const auto path = write_mat(dir, "cut.mat", 10.0, 5000, version);
    const auto size = std::filesystem::file_size(path);
    for (const double keep : {0.9, 0.5, 0.1}) {
      const auto cut = dir / "cut_part.mat";
      std::filesystem::copy_file(path, cut, std::filesystem::copy_options::overwrite_existing);
      std::filesystem::resize_file(cut, static_cast<std::uintmax_t>(size * keep));
      const test::CliRun r = test::run_foglab("allan " + quote(cut) + " --channel Y1");
      EXPECT_EQ(r.exit_code, 3) << "keep " << keep << ": " << r.err;
      EXPECT_NE(r.err.find("cut_part.mat"), std::string::npos) << r.err;
    }
  }
}

TEST(CliBadMat, NonPositiveSampleRateInTheFileIsADataError) {
  test::TempDir dir;
  const auto path = write_mat(dir, "zero_f.mat", 0.0, 100);
  const test::CliRun r = test::run_foglab("allan " + quote(path));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("zero_f.mat"), std::string::npos) << r.err;
}

TEST(CliUsage, UnknownOptionsAndMissingArgumentsAreUsageErrors) {
  EXPECT_EQ(test::run_foglab("allan --frobnicate").exit_code, 2);
  EXPECT_EQ(test::run_foglab("").exit_code, 2);
  EXPECT_EQ(test::run_foglab("nosuchcommand").exit_code, 2);
  const test::CliRun help = test::run_foglab("allan --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--taus"), std::string::npos);
}

}  // namespace
}  // namespace foglab

namespace foglab {
namespace {

// The MAT-reader findings of the fuzz target (fuzz/regressions/mat_reader/;
// each file's first byte is the target's mode byte, not part of the file).
struct FuzzFinding {
  std::string name;                  // in fuzz/regressions/mat_reader/
  std::vector<std::string> message;  // besides the file name
};

void PrintTo(const FuzzFinding& f, std::ostream* os) { *os << f.name; }

class CliFuzzFinding : public ::testing::TestWithParam<FuzzFinding> {};

TEST_P(CliFuzzFinding, IsADataErrorWithoutHugeAllocationsOrACrash) {
  const FuzzFinding& f = GetParam();
  const std::string input = test::read_file(std::filesystem::path(FOGLAB_TEST_DATA_DIR) / ".." /
                                            ".." / "fuzz" / "regressions" / "mat_reader" / f.name);
  ASSERT_GT(input.size(), 100u) << f.name;
  test::TempDir dir;
  std::ofstream(dir / "input.mat", std::ios::binary) << input.substr(1);
  std::ofstream(dir / "kept.json") << "previous result";
  const test::CliRun r =
      test::run_foglab("allan " + quote(dir / "input.mat") + " --json " + quote(dir / "kept.json"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("input.mat"), std::string::npos) << r.err;
  for (const std::string& fragment : f.message) {
    EXPECT_NE(r.err.find(fragment), std::string::npos)
        << "missing '" << fragment << "' in " << r.err;
  }
  EXPECT_EQ(test::read_file(dir / "kept.json"), "previous result");
}

INSTANTIATE_TEST_SUITE_P(
    Issue7, CliFuzzFinding,
    ::testing::Values(
        // A 1.5 kB file whose first v4 header claims a 1.8 GB name, which
        // Mat_Open() allocated.
        FuzzFinding{"oom-v4-name-length", {"truncated", "1828799004 bytes"}},
        // A v4 header whose name claims 1.7 GB in the byte order matio
        // reads it in (the other order claims 122 bytes).
        FuzzFinding{"oom-v4-name-byte-order", {"truncated", "needs 1711276052 bytes"}},
        // An uncompressed v5 matrix whose name claims 4 GB inside an
        // 848-byte element, which matio allocated.
        FuzzFinding{"oom-v5-name-length", {"variable #2", "4143972352 bytes"}},
        // An uncompressed v5 matrix whose dimensions claim 4 GB inside
        // a 56-byte element (matio allocated 8.5 GB for them); its array
        // flags' tag reads as a short one, which had misled the check.
        FuzzFinding{"oom-v5-dims-size", {"variable #1", "dimensions claiming 4278190088 bytes"}},
        // An uncompressed v5 matrix whose dimensions' size (3 bytes) is no
        // multiple of 4: matio reads no dimension and takes the name's tag
        // from the next bytes, which claim 973 MB.
        FuzzFinding{"oom-v5-name-after-short-dims",
                    {"variable #1", "a name claiming 973078529 bytes"}},
        // A compressed v5 header whose inflated dimensions are huge.
        FuzzFinding{"oom-v5-compressed-header", {"corrupt"}},
        // A v7.3 file whose HDF5 superblock points at a driver information
        // block claiming 4 GB, which HDF5 allocated and zero-filled (4.2 GB
        // of memory and 7 s, in the probe's child and again in the process).
        FuzzFinding{"oom-v73-driver-block",
                    {"damaged", "driver information block at byte 541 claims 4294967311"}},
        // A damaged v7.3 file on which HDF5 1.10 segfaults inside
        // Mat_Open(): probed in a child process, reported as damaged.
        FuzzFinding{"crash-v73-hdf5-segv", {"damaged", "HDF5"}}),
    [](const auto& info) {
      std::string name = info.param.name;
      for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

}  // namespace
}  // namespace foglab
