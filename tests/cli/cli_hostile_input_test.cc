// Issue 7, part 1: a catalogue of broken inputs run against every command
// that reads a recording (allan, psd, analyze, lab2 FILE). Each case has its
// golden expectation: the exit code (2 usage, 3 data), the key words of the
// message (always the file's name, and the variable, line or option), no
// "internal error" and no crash (never exit 1 or a signal), nothing on
// stdout, an existing output (--json) left untouched and no new output or
// temporary file anywhere in the directory (lab2: no --out directory).
//
// The files are made here: text tables by hand, MAT files of every wrong
// class with matio's C API (v5 and v7.3), HDF5 files that are not MAT files
// with the HDF5 C API. Records are a few hundred samples, so the whole
// catalogue runs in seconds.
//
// At about 1,000 lines this file is longer than the others on purpose: it
// is one catalogue, most of it the table of cases, and reads best as one
// table (the makers of broken files above it, the one parameterised test
// below it).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <matio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "support/cli.h"
#include "support/files.h"
#include "support/mat_writer.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using test::quote;
using ::testing::HasSubstr;
using ::testing::Not;

// ---- the good recording every broken one is made from ---------------------

constexpr std::size_t kSamples = 400;  // 40 s at 10 Hz
constexpr double kRateHz = 10.0;

std::vector<double> rate_samples(std::size_t n = kSamples) {
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> y(n);
  for (double& v : y) v = 1.5 + 0.3 * normal(rng);
  return y;
}
std::vector<double> time_samples(std::size_t n = kSamples) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) / kRateHz;
  return t;
}
std::vector<double> temperature_samples(std::size_t n = kSamples) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = 20.0 + 0.01 * static_cast<double>(i);
  return t;
}

// The rows of the good CSV "t,Y1,T1" (header first); row k >= 1 is sample k
// and line k + 1 of the file.
std::vector<std::string> csv_rows() {
  const auto t = time_samples(), y = rate_samples(), temp = temperature_samples();
  std::vector<std::string> rows = {"t,Y1,T1"};
  for (std::size_t i = 0; i < kSamples; ++i) {
    char line[96];
    std::snprintf(line, sizeof(line), "%.1f,%.6f,%.3f", t[i], y[i], temp[i]);
    rows.emplace_back(line);
  }
  return rows;
}

std::string join_rows(const std::vector<std::string>& rows) {
  std::string text;
  for (const auto& r : rows) text += r + "\n";
  return text;
}

using Maker = std::function<void(const fs::path&)>;

Maker text_file(const std::string& content) {
  return [content](const fs::path& p) { std::ofstream(p, std::ios::binary) << content; };
}

// The good CSV with `edit` applied to its rows.
Maker csv(const std::function<void(std::vector<std::string>&)>& edit) {
  return [edit](const fs::path& p) {
    std::vector<std::string> rows = csv_rows();
    edit(rows);
    std::ofstream(p, std::ios::binary) << join_rows(rows);
  };
}

// Sets field `column` (0-based) of data row `row` (1-based sample) to `value`.
void set_cell(std::vector<std::string>& rows, std::size_t row, std::size_t column,
              const std::string& value) {
  std::vector<std::string> fields;
  std::string field;
  for (const char c : rows[row] + ",") {
    if (c == ',') {
      fields.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  fields[column] = value;
  std::string joined;
  for (std::size_t k = 0; k < fields.size(); ++k) joined += (k ? "," : "") + fields[k];
  rows[row] = joined;
}

// ---- MAT files with matio ---------------------------------------------------

using test::MatWriter;

// What a lab-layout file holds; each field can be replaced by a case.
struct LabLayout {
  mat_ft version = MAT_FT_MAT5;
  bool with_f = true;
  double f = kRateHz;
  std::function<void(MatWriter&)> f_writer;  // replaces f when set
  bool with_t = true;
  std::vector<double> t = time_samples();
  std::function<void(MatWriter&)> y_writer = [](MatWriter& m) { m.vector("Y1", rate_samples()); };
  bool with_temperature = true;
  std::vector<double> temperature = temperature_samples();
  std::function<void(MatWriter&)> temperature_writer;  // replaces T1 when set
};

LabLayout layout(mat_ft version) {
  LabLayout l;
  l.version = version;
  return l;
}

void write_lab(const fs::path& p, const LabLayout& l) {
  MatWriter m(p, l.version);
  if (l.f_writer) {
    l.f_writer(m);
  } else if (l.with_f) {
    m.scalar("f", l.f);
  }
  if (l.with_t) m.vector("t", l.t);
  l.y_writer(m);
  if (l.temperature_writer) {
    l.temperature_writer(m);
  } else if (l.with_temperature) {
    m.vector("T1", l.temperature);
  }
}

Maker mat(const std::function<void(LabLayout&)>& edit, mat_ft version = MAT_FT_MAT5) {
  return [edit, version](const fs::path& p) {
    LabLayout l;
    l.version = version;
    edit(l);
    write_lab(p, l);
  };
}

// A good MAT file cut to `keep` of its size.
Maker truncated_mat(mat_ft version, double keep) {
  return [version, keep](const fs::path& p) {
    write_lab(p, layout(version));
    const auto size = fs::file_size(p);
    fs::resize_file(p, static_cast<std::uintmax_t>(static_cast<double>(size) * keep));
  };
}

Maker random_bytes(std::size_t n) {
  return [n](const fs::path& p) {
    std::mt19937 rng(7);
    std::string bytes(n, '\0');
    for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
    std::ofstream(p, std::ios::binary) << bytes;
  };
}

// ---- HDF5 files that are not MAT files -----------------------------------

// A plain HDF5 file holding the lab's variables as datasets (as h5py, or
// Octave's save -hdf5, would write them), optionally with a 512-byte user
// block (where a v7.3 MAT file keeps its MATLAB header); `fake_header`
// writes a MATLAB 7.3 header into that block over datasets that lack
// MATLAB's attributes.
Maker plain_hdf5(bool userblock, bool fake_header = false) {
  return [userblock, fake_header](const fs::path& p) {
    const hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    if (userblock) H5Pset_userblock(fcpl, 512);
    const hid_t file = H5Fcreate(p.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    auto dataset = [&](const char* name, const std::vector<double>& values) {
      const hsize_t dims[1] = {values.size()};
      const hid_t space = H5Screate_simple(1, dims, nullptr);
      const hid_t set =
          H5Dcreate2(file, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
      H5Dclose(set);
      H5Sclose(space);
    };
    dataset("f", {kRateHz});
    dataset("t", time_samples());
    dataset("Y1", rate_samples());
    dataset("T1", temperature_samples());
    H5Fclose(file);
    H5Pclose(fcpl);
    if (fake_header) {
      std::string header(128, ' ');
      const std::string text =
          "MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Jan  1 "
          "00:00:00 2024 HDF5 schema 1.00 .";
      header.replace(0, text.size(), text);
      header[124] = 0x00;
      header[125] = 0x02;
      header[126] = 'I';
      header[127] = 'M';
      std::fstream out(p, std::ios::binary | std::ios::in | std::ios::out);
      out.seekp(0);
      out.write(header.data(), static_cast<std::streamsize>(header.size()));
    }
  };
}

// ---- the catalogue ----------------------------------------------------------

enum class Cmd { allan, psd, analyze, lab2 };
const char* name_of(Cmd c) {
  switch (c) {
    case Cmd::allan:
      return "allan";
    case Cmd::psd:
      return "psd";
    case Cmd::analyze:
      return "analyze";
    case Cmd::lab2:
      return "lab2";
  }
  return "?";
}
const std::vector<Cmd> kAll = {Cmd::allan, Cmd::psd, Cmd::analyze, Cmd::lab2};
const std::vector<Cmd> kWithOptions = {Cmd::allan, Cmd::psd, Cmd::analyze};  // lab2 has no --fs
const std::vector<Cmd> kWithTemperature = {Cmd::analyze, Cmd::lab2};
// allan, psd and analyze take a NaN sample for a missing one (a gap)
const std::vector<Cmd> kRefusingNaN = {Cmd::lab2};

struct Case {
  std::string name;
  std::string file;  // its name in the test's directory
  Maker make;
  std::string options;  // given to allan, psd and analyze (lab2 takes none)
  std::vector<Cmd> commands;
  int exit_code;
  std::vector<std::string> words;       // the message must hold each (and the file's name)
  std::vector<std::string> lab2_words;  // instead of `words` for lab2, when set

  Case(std::string name_, std::string file_, Maker make_, std::string options_,
       std::vector<Cmd> commands_, int exit_code_, std::vector<std::string> words_,
       std::vector<std::string> lab2_words_ = {})
      : name(std::move(name_)),
        file(std::move(file_)),
        make(std::move(make_)),
        options(std::move(options_)),
        commands(std::move(commands_)),
        exit_code(exit_code_),
        words(std::move(words_)),
        lab2_words(std::move(lab2_words_)) {}
};

std::vector<Case> catalogue() {
  const auto v5 = MAT_FT_MAT5;
  const auto v73 = MAT_FT_MAT73;
  std::vector<Case> c = {
      // -- text: empty, header only, cells that are not numbers ------------
      {"EmptyFile", "empty.csv", text_file(""), "", kAll, 3, {"no data"}},
      {"OnlyComments",
       "comments.csv",
       text_file("# nothing here\n\n# at all\n"),
       "",
       kAll,
       3,
       {"no data"}},
      {"HeaderOnly", "header.csv", text_file("t,Y1,T1\n"), "", kAll, 3, {"header", "no data rows"}},
      {"NonNumericCell",
       "cell.csv",
       csv([](auto& r) { set_cell(r, 57, 1, "abc"); }),
       "",
       kAll,
       3,
       {"line 58", "Y1", "'abc'", "not a number"}},
      {"NonNumericTime",
       "time_cell.csv",
       csv([](auto& r) { set_cell(r, 9, 0, "12:00:01"); }),
       "",
       kAll,
       3,
       {"line 10", "column 1 (t)", "'12:00:01'"}},
      {"NonNumericTemperature",
       "temp_cell.csv",
       csv([](auto& r) { set_cell(r, 30, 2, "hot"); }),
       "",
       kWithTemperature,
       3,
       {"line 31", "T1", "'hot'"}},
      {"EmptyCell",
       "empty_cell.csv",
       csv([](auto& r) { set_cell(r, 12, 1, ""); }),
       "",
       kRefusingNaN,  // the others take it for a missing sample
       3,
       {"line 13", "Y1", "empty"}},
      {"RaggedRow",
       "ragged.csv",
       csv([](auto& r) { r[20] += ",7"; }),
       "",
       kAll,
       3,
       {"line 21", "4 column(s), expected 3"}},
      {"BinaryDataAsText",
       "noise.txt",
       random_bytes(2000),
       "--fs 10",
       kWithOptions,
       3,
       {"binary data", "is a NUL"}},
      {"ZerosAsText",
       "zeros.txt",
       text_file(std::string(5000, '\0')),
       "--fs 10",
       kWithOptions,
       3,
       {"byte 1 is a NUL", "binary data"}},
      {"DecimalCommasWithoutTheOption",
       "comma.csv",
       csv([](auto& r) {
         for (std::size_t k = 1; k < r.size(); ++k) {
           for (char& ch : r[k]) ch = ch == ',' ? ';' : ch == '.' ? ',' : ch;
         }
         r[0] = "t;Y1;T1";
       }),
       "",
       kWithOptions,
       3,
       {"line 2", "decimal comma", "--decimal-comma"}},
      {"ConstantRecord",
       "flat.csv",
       csv([](auto& r) {
         for (std::size_t k = 1; k < r.size(); ++k) set_cell(r, k, 1, "7.25");
       }),
       "",
       kAll,
       3,
       {"the record is constant", "7.25 deg/h"}},
      // -- NaN and Inf -------------------------------------------------------
      {"NaNSample",
       "nan.csv",
       csv([](auto& r) { set_cell(r, 33, 1, "NaN"); }),
       "",
       kRefusingNaN,
       3,
       {"sample 33", "'Y1'", "NaN"}},
      {"InfSample",
       "inf.csv",
       csv([](auto& r) { set_cell(r, 7, 1, "inf"); }),
       "",
       kAll,
       3,
       {"sample 7", "'Y1'", "+Inf"}},
      {"MinusInfSample",
       "minf.csv",
       csv([](auto& r) { set_cell(r, 400, 1, "-Infinity"); }),
       "",
       kAll,
       3,
       {"sample 400", "'Y1'", "-Inf"}},
      {"NaNTemperature",
       "nan_temp.csv",
       csv([](auto& r) { set_cell(r, 5, 2, "nan"); }),
       "",
       kRefusingNaN,
       3,
       {"sample 5", "'T1'", "NaN"}},
      {"NaNTime",
       "nan_time.csv",
       csv([](auto& r) { set_cell(r, 15, 0, "nan"); }),
       "",
       kAll,
       3,
       {"time", "sample 15", "line 16", "nan"}},
      {"NaNInMat",
       "nan.mat",
       mat([](LabLayout& l) {
         l.y_writer = [](MatWriter& m) {
           auto y = rate_samples();
           y[99] = std::numeric_limits<double>::quiet_NaN();
           m.vector("Y1", y);
         };
       }),
       "",
       kRefusingNaN,
       3,
       {"sample 100", "'Y1'", "NaN"}},
      // -- one sample ----------------------------------------------------------
      {"OneSampleWithTime",
       "one.csv",
       text_file("t,Y1,T1\n0,1.5,20\n"),
       "",
       kAll,
       3,
       {"1 sample", "t", "--fs"}},
      {"OneSample",
       "one.txt",
       text_file("1.5\n"),
       "--fs 10",
       kWithOptions,
       3,
       {"channel 1", "the record has 1"}},
      {"OneSampleMat",
       "one.mat",
       mat([](LabLayout& l) {
         l.with_t = false;
         l.with_temperature = false;
         l.y_writer = [](MatWriter& m) { m.vector("Y1", std::vector<double>{1.5}); };
       }),
       "--channel Y1",
       kWithOptions,
       3,
       {"channel Y1", "the record has 1"}},
      // -- Y, T and t of different lengths -----------------------------------
      {"TemperatureShorter",
       "short_temp.mat",
       mat([](LabLayout& l) { l.temperature.resize(kSamples - 1); }),
       "",
       kWithTemperature,
       3,
       {"Y1", "T1", "400", "399"}},
      {"TemperatureShorterV73",
       "short_temp73.mat",
       mat([](LabLayout& l) { l.temperature.resize(kSamples - 1); }, v73),
       "",
       kWithTemperature,
       3,
       {"Y1", "T1", "400", "399"}},
      {"TimeShorterNoF",
       "short_t.mat",
       mat([](LabLayout& l) {
         l.with_f = false;
         l.t.resize(kSamples - 1);
       }),
       "",
       kAll,
       3,
       {"'t' has 399 samples", "'Y1' has 400"}},
      {"TimeShorterWithF",
       "short_t_f.mat",
       mat([](LabLayout& l) { l.t.resize(kSamples - 1); }),
       "",
       kAll,
       3,
       {"'t' has 399 samples", "'Y1' has 400", "--fs"}},
      {"TimeLongerWithFV73",
       "long_t_f.mat",
       mat([](LabLayout& l) { l.t.push_back(40.0); }, v73),
       "",
       kAll,
       3,
       {"'t' has 401 samples", "'Y1' has 400"}},
      // -- repeated, decreasing, irregular time and gaps ----------------------
      {"RepeatedTime",
       "repeat.csv",
       csv([](auto& r) { set_cell(r, 101, 0, "9.9"); }),
       "",
       kAll,
       3,
       {"not increasing", "sample 101", "line 102", "'t'", "--fs"}},
      {"DecreasingTime",
       "decrease.csv",
       csv([](auto& r) { set_cell(r, 201, 0, "3.0"); }),
       "",
       kAll,
       3,
       {"not increasing", "sample 201", "line 202", "--fs"}},
      {"IrregularTime",
       "jitter.csv",
       csv([](auto& r) { set_cell(r, 150, 0, "14.95"); }),
       "",
       kAll,
       3,
       {"not uniformly sampled", "sample 150", "line 151", "--fs"}},
      // (a whole number of missing samples is a gap the analyses handle:
      // cli_sensor_effects_test.cc; a step of 1.3 samples is not)
      {"IrregularTimeMatNoF",
       "odd.mat",
       mat([](LabLayout& l) {
         l.with_f = false;
         for (std::size_t i = 200; i < kSamples; ++i) l.t[i] += 0.03;
       }),
       "",
       kAll,
       3,
       {"not uniformly sampled", "sample 201 of 't'", "--fs"}},
      {"IrregularTimeMatWithF",
       "odd_f.mat",
       mat([](LabLayout& l) {
         for (std::size_t i = 200; i < kSamples; ++i) l.t[i] += 0.03;
       }),
       "",
       kAll,
       3,
       {"not uniformly sampled", "sample 201 of 't'", "--fs"}},
      {"DecreasingTimeMatV73",
       "back73.mat",
       mat(
           [](LabLayout& l) {
             l.with_f = false;
             l.t[300] = 1.0;
           },
           v73),
       "",
       kAll,
       3,
       {"not increasing", "sample 301 of 't'", "--fs"}},
      // -- missing variables -------------------------------------------------
      {"MissingChannelMat",
       "lab.mat",
       mat([](LabLayout&) {}),
       "--channel Y7",
       kWithOptions,
       3,
       {"no variable 'Y7'", "variables present", "Y1", "T1"}},
      {"MissingChannelText",
       "lab.csv",
       csv([](auto&) {}),
       "--channel Y7",
       kWithOptions,
       3,
       {"no channel column 'Y7'", "t, Y1, T1"}},
      {"NoRateVariableForLab2",
       "norate.mat",
       mat([](LabLayout& l) { l.y_writer = [](MatWriter& m) { m.vector("Z", rate_samples()); }; }),
       "",
       {Cmd::lab2},
       3,
       {"no Y1 or Y2", "Z"}},
      {"NoSampleRateMat",
       "no_rate.mat",
       mat([](LabLayout& l) {
         l.with_f = false;
         l.with_t = false;
       }),
       "",
       kAll,
       2,
       {"no sample rate", "--fs"}},
      {"NoSampleRateText",
       "no_rate.csv",
       text_file("Y1\n1\n2\n3\n"),
       "",
       kAll,
       2,
       {"no sample rate", "--fs"}},
      {"MissingTemperatureOption",
       "lab.mat",
       mat([](LabLayout&) {}),
       "--temp T9",
       {Cmd::analyze},
       2,
       {"--temp T9", "T9", "T1"}},
      // -- damaged and foreign MAT files --------------------------------------
      {"EmptyMat", "empty.mat", text_file(""), "", kAll, 3, {"the MAT file is empty"}},
      {"RandomBytesMat", "random.mat", random_bytes(4096), "", kAll, 3, {"not a MAT file"}},
      {"TextNamedMat", "text.mat", csv([](auto&) {}), "", kAll, 3, {"not a MAT file"}},
      {"TruncatedV5", "cut5.mat", truncated_mat(v5, 0.5), "", kAll, 3, {"truncated"}},
      {"TruncatedV5Header", "cut5h.mat", truncated_mat(v5, 0.02), "", kAll, 3, {"MAT file"}},
      {"TruncatedV73", "cut73.mat", truncated_mat(v73, 0.5), "", kAll, 3, {"MAT file"}},
      {"TruncatedV73Userblock", "cut73u.mat", truncated_mat(v73, 0.1), "", kAll, 3, {"MAT file"}},
      {"Hdf5NotMat", "plain.mat", plain_hdf5(false), "", kAll, 3, {"HDF5", "not a MAT"}},
      {"Hdf5WithUserblockNotMat",
       "block.mat",
       plain_hdf5(true),
       "",
       kAll,
       3,
       {"HDF5", "not a MAT"}},
      {"Hdf5WithAMatlabHeaderOverPlainDatasets",
       "fake73.mat",
       plain_hdf5(true, true),
       "",
       kAll,
       3,
       {"MAT file is corrupt", "HDF5"}},
      {"Hdf5NamedH5",
       "plain.h5",
       plain_hdf5(false),
       "--fs 10",
       kWithOptions,
       3,
       {"HDF5 file, not text"}},
      // -- absurd values ------------------------------------------------------
      // (allan, psd and analyze read with io::kMaxSampleMagnitude; lab2 reads
      // its variables itself, without that limit: see
      // Lab2RejectsAbsurdValues below)
      {"AbsurdRate",
       "huge.csv",
       csv([](auto& r) { set_cell(r, 42, 1, "1e308"); }),
       "",
       kWithOptions,
       3,
       {"sample 42", "'Y1'", "1e+308", "too large"}},
      {"AbsurdNegativeRate",
       "nhuge.csv",
       csv([](auto& r) { set_cell(r, 3, 1, "-1.7e308"); }),
       "",
       kWithOptions,
       3,
       {"sample 3", "'Y1'", "too large"}},
      {"AbsurdTemperature",
       "hot.csv",
       csv([](auto& r) { set_cell(r, 8, 2, "1e308"); }),
       "",
       {Cmd::analyze},
       3,
       {"sample 8", "'T1'", "too large"}},
      {"AbsurdRateMatV73",
       "huge73.mat",
       mat(
           [](LabLayout& l) {
             l.y_writer = [](MatWriter& m) {
               auto y = rate_samples();
               y[9] = 1e308;
               m.vector("Y1", y);
             };
           },
           v73),
       "",
       kWithOptions,
       3,
       {"sample 10", "'Y1'", "too large"}},
      // samples whose squares underflow: the Allan deviation came out 0 and the
      // record was called noiseless ("repeats exactly")
      {"TinyRate",
       "tiny.csv",
       csv([](auto& r) {
         const auto y = rate_samples();
         for (std::size_t k = 1; k < r.size(); ++k) {
           char cell[32];
           std::snprintf(cell, sizeof(cell), "%.6g", y[k - 1] * 1e-300);
           set_cell(r, k, 1, cell);
         }
       }),
       "",
       kWithOptions,
       3,
       {"'Y1'", "no sample larger than", "too small"}},
      {"OverflowOnUnitConversion",
       "dps.csv",
       csv([](auto& r) { set_cell(r, 4, 1, "1e306"); }),
       "--units deg/s",
       kWithOptions,
       3,
       {"sample 4", "'Y1'", "overflows"}},
      // -- options: units, sample rate, tau -----------------------------------
      {"UnknownUnit",
       "lab.csv",
       csv([](auto&) {}),
       "--units furlong/s",
       kWithOptions,
       2,
       {"--units", "unknown unit 'furlong/s'", "deg/h, deg/s or rad/s", "m/s^2, g or mg"}},
      {"UnknownFormat",
       "lab.csv",
       csv([](auto&) {}),
       "--format xlsx",
       kWithOptions,
       2,
       {"--format", "xlsx"}},
      {"ZeroSampleRate",
       "lab.csv",
       csv([](auto&) {}),
       "--fs 0",
       kWithOptions,
       2,
       {"--fs 0", "positive"}},
      {"NegativeSampleRate",
       "lab.mat",
       mat([](LabLayout&) {}),
       "--fs -10",
       kWithOptions,
       2,
       {"--fs -10", "positive"}},
      {"InfiniteSampleRate",
       "lab.csv",
       csv([](auto&) {}),
       "--fs inf",
       kWithOptions,
       2,
       {"--fs", "positive, finite"}},
      {"ZeroFInMat",
       "zero_f.mat",
       mat([](LabLayout& l) { l.f = 0.0; }),
       "",
       kAll,
       3,
       {"variable f", "0 Hz"}},
      {"NegativeFInMat",
       "neg_f.mat",
       mat([](LabLayout& l) { l.f = -10.0; }, v73),
       "",
       kAll,
       3,
       {"variable f", "-10 Hz"}},
      {"NaNFInMat",
       "nan_f.mat",
       mat([](LabLayout& l) { l.f = std::nan(""); }),
       "",
       kAll,
       3,
       {"variable f", "nan Hz"}},
      // Issue 22: a rate far outside any gyro's is a broken file, not a
      // record to analyse (it had given NaN criteria and exit 0).
      {"HugeFInMat",
       "huge_f.mat",
       mat([](LabLayout& l) { l.f = 1e300; }),
       "",
       kAll,
       3,
       {"variable f", "1e+300 Hz", "1e+09"}},
      {"TinyFInMat",
       "tiny_f.mat",
       mat([](LabLayout& l) { l.f = 1e-300; }, v73),
       "",
       kAll,
       3,
       {"variable f", "1e-300 Hz", "1e-06"}},
      {"CharFInMat",
       "char_f.mat",
       mat([](LabLayout& l) { l.f_writer = [](MatWriter& m) { m.text("f", "10 Hz"); }; }),
       "",
       kAll,
       3,
       {"variable 'f'", "char"}},
      {"ZeroTau",
       "lab.csv",
       csv([](auto&) {}),
       "--taus 0",
       {Cmd::allan, Cmd::analyze},
       2,
       {"--taus", "not positive"}},
      {"NegativeTau",
       "lab.csv",
       csv([](auto&) {}),
       "--taus 1,-2",
       {Cmd::allan, Cmd::analyze},
       2,
       {"--taus", "tau -2 s is not positive"}},
      {"TauShorterThanTheSampleInterval",
       "lab.csv",
       csv([](auto&) {}),
       "--taus 0.01",
       {Cmd::allan, Cmd::analyze},
       2,
       {"tau 0.01 s", "sample interval"}},
      {"TauLongerThanTheRecord",
       "lab.csv",
       csv([](auto&) {}),
       "--taus 1,1000",
       {Cmd::allan, Cmd::analyze},
       3,
       {"channel Y1", "tau 1000 s", "more samples"}},
      {"SegmentLongerThanTheRecord",
       "lab.csv",
       csv([](auto&) {}),
       "--segment 100000",
       {Cmd::psd},
       2,
       {"channel Y1", "100000", "record length"}},
  };

  // -- MAT variables of the wrong class, v5 and v7.3 ------------------------
  using Writer = std::function<void(MatWriter&, const std::string&)>;
  struct Wrong {
    const char* name;
    Writer write;
    std::vector<std::string> words;
  };
  const std::vector<Wrong> wrong = {
      {"Char", [](MatWriter& m, const std::string& v) { m.text(v, "gyro rate"); }, {"1x9 char"}},
      {"Complex",
       [](MatWriter& m, const std::string& v) {
         m.complex_vector(v, rate_samples(kSamples), std::vector<double>(kSamples, 0.5));
       },
       {"complex 400x1 double"}},
      {"Sparse",
       [](MatWriter& m, const std::string& v) { m.sparse(v, kSamples); },
       {"400x1 sparse"}},
      {"Struct",
       [](MatWriter& m, const std::string& v) { m.structure(v, rate_samples(kSamples)); },
       {"1x1 struct"}},
      {"Cell",
       [](MatWriter& m, const std::string& v) { m.cell(v, rate_samples(kSamples)); },
       {"1x1 cell"}},
      {"Logical",
       [](MatWriter& m, const std::string& v) { m.logical(v, kSamples); },
       {"400x1 logical"}},
      {"Matrix",
       [](MatWriter& m, const std::string& v) { m.matrix(v, 20, 20); },
       {"20x20 double matrix"}},
      {"Empty", [](MatWriter& m, const std::string& v) { m.empty(v); }, {"0x0 double", "empty"}},
  };
  for (const auto& [version, label] : {std::pair{v5, "V5"}, std::pair{v73, "V73"}}) {
    for (const Wrong& w : wrong) {
      const std::string file = std::string(w.name) + label + ".mat";
      const Writer write = w.write;
      const Maker make =
          mat([write](LabLayout& l) { l.y_writer = [write](MatWriter& m) { write(m, "Y1"); }; },
              version);
      std::vector<std::string> words = {"variable 'Y1' is"};
      words.insert(words.end(), w.words.begin(), w.words.end());
      c.push_back({std::string("Wrong") + w.name + label, file, make, "--channel Y1", kWithOptions,
                   3, words});
      // Without --channel: no data channel, and the listing shows Y1's class.
      // lab2 lists the file's channels first, and Y1 is not among them.
      c.push_back({std::string("Wrong") + w.name + label + "Default",
                   file,
                   make,
                   "",
                   kAll,
                   3,
                   {"no data channel", "Y1 (" + w.words.front()},
                   {"Y1"}});
      // The lab's temperature T1 of the wrong class: analyze pairs Y1 with
      // T1, so T1 must be usable (not silently dropped).
      std::vector<std::string> t_words = {"variable 'T1' is"};
      t_words.insert(t_words.end(), w.words.begin(), w.words.end());
      c.push_back({std::string("WrongTemperature") + w.name + label,
                   "temp_" + file,
                   mat(
                       [write](LabLayout& l) {
                         l.temperature_writer = [write](MatWriter& m) { write(m, "T1"); };
                       },
                       version),
                   "",
                   {Cmd::analyze},
                   3,
                   t_words});
    }
  }
  return c;
}

struct Run {
  Case c;
  Cmd cmd;
};

std::vector<Run> runs() {
  std::vector<Run> out;
  for (const Case& c : catalogue()) {
    for (const Cmd cmd : c.commands) out.push_back({c, cmd});
  }
  return out;
}

void PrintTo(const Run& r, std::ostream* os) { *os << r.c.name << " " << name_of(r.cmd); }

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    names.insert(fs::relative(e.path(), dir).string());
  }
  return names;
}

class HostileInput : public ::testing::TestWithParam<Run> {};

TEST_P(HostileInput, ExitCodeMessageAndNoOutputTouched) {
  const Case& c = GetParam().c;
  const Cmd cmd = GetParam().cmd;
  test::TempDir dir;
  const fs::path file = dir / c.file;
  c.make(file);
  ASSERT_TRUE(fs::exists(file));
  // An existing output must survive a failed run untouched.
  std::ofstream(dir / "kept.json") << "previous result";
  const std::set<std::string> before = listing(dir.path());

  std::string args = std::string(name_of(cmd)) + " " + quote(file);
  if (cmd == Cmd::lab2) {
    args += " --no-plots --out " + quote(dir / "lab2_out");
  } else {
    args += " " + c.options + " --json " + quote(dir / "kept.json") + " --csv " +
            quote(dir / "new.csv");
    if (cmd == Cmd::analyze) {
      args += " --report " + quote(dir / "new.html") + " --kalibr " + quote(dir / "new.yaml");
    }
  }
  const test::CliRun r = test::run_foglab(args);

  EXPECT_NE(r.exit_code, -1) << "killed by a signal: " << r.err;
  EXPECT_NE(r.exit_code, 1) << "internal error: " << r.err;
  EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
  EXPECT_THAT(r.err, HasSubstr("foglab: error: "));
  EXPECT_THAT(r.err, Not(HasSubstr("internal error")));
  EXPECT_THAT(r.err, Not(HasSubstr("HDF5-DIAG")));  // HDF5's own stack never reaches stderr
  EXPECT_THAT(r.err, HasSubstr(c.file)) << "the message must name the file";
  const auto& words = cmd == Cmd::lab2 && !c.lab2_words.empty() ? c.lab2_words : c.words;
  for (const std::string& w : words) EXPECT_THAT(r.err, HasSubstr(w));
  EXPECT_EQ(r.out, "") << "nothing on stdout after an error";

  EXPECT_EQ(test::read_file(dir / "kept.json"), "previous result");
  EXPECT_EQ(listing(dir.path()), before) << "no new output or temporary file";
}

INSTANTIATE_TEST_SUITE_P(Issue7, HostileInput, ::testing::ValuesIn(runs()), [](const auto& info) {
  return info.param.c.name + "_" + name_of(info.param.cmd);
});

// lab2 FILE reads Y1/T1 itself (cmd_lab2.cc): 1e308 in either is a data
// error there too, as in analyze.
TEST(HostileInputLab2, Lab2RejectsAbsurdValues) {
  for (const std::size_t col : {std::size_t{1}, std::size_t{2}}) {
    test::TempDir dir;
    const fs::path file = dir / "huge.csv";
    csv([&](auto& r) { set_cell(r, 42, col, "1e308"); })(file);
    const test::CliRun r =
        test::run_foglab("lab2 " + quote(file) + " --no-plots --out " + quote(dir / "out"));
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_THAT(r.err, HasSubstr("sample 42"));
    EXPECT_THAT(r.err, HasSubstr("too large"));
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
}

// ---- what is accepted -------------------------------------------------------

std::string command_args(Cmd cmd, const fs::path& file, const test::TempDir& dir) {
  std::string args = std::string(name_of(cmd)) + " " + quote(file);
  if (cmd == Cmd::lab2) return args + " --no-plots --out " + quote(dir / "lab2_out");
  return args + " --json " + quote(dir / (std::string(name_of(cmd)) + ".json"));
}

// Valid JSON in which every number is finite (nlohmann writes NaN/Inf as
// null, so a parse that succeeds is already proof of that).
void expect_valid_json(const fs::path& path) {
  const std::string text = test::read_file(path);
  ASSERT_FALSE(text.empty()) << path;
  EXPECT_TRUE(nlohmann::json::accept(text)) << text.substr(0, 200);
  EXPECT_THAT(text, Not(HasSubstr("inf")));
  EXPECT_THAT(text, Not(HasSubstr("nan")));
}

// The good recordings the catalogue breaks pass through every command.
TEST(HostileInputControl, TheGoodRecordingsPassEveryCommand) {
  test::TempDir dir;
  const fs::path text = dir / "lab.csv", v5 = dir / "lab5.mat", v73 = dir / "lab73.mat";
  csv([](auto&) {})(text);
  write_lab(v5, layout(MAT_FT_MAT5));
  write_lab(v73, layout(MAT_FT_MAT73));
  for (const fs::path& file : {text, v5, v73}) {
    for (const Cmd cmd : kAll) {
      const test::CliRun r = test::run_foglab(command_args(cmd, file, dir));
      EXPECT_EQ(r.exit_code, 0) << name_of(cmd) << " " << file << ": " << r.err;
      if (cmd != Cmd::lab2) expect_valid_json(dir / (std::string(name_of(cmd)) + ".json"));
    }
  }
}

// Integer (and single) classes are accepted and converted to double, and a
// note on stderr says so.
template <typename T>
void expect_integer_class_accepted(const char* class_name, mat_ft version) {
  SCOPED_TRACE(std::string(class_name) + (version == MAT_FT_MAT73 ? " v7.3" : " v5"));
  test::TempDir dir;
  const fs::path file = dir / (std::string(class_name) + ".mat");
  LabLayout l = layout(version);
  l.y_writer = [](MatWriter& m) {
    std::vector<T> y(kSamples);
    std::mt19937 rng(3);
    for (T& v : y) v = static_cast<T>(10 + rng() % 20);
    m.vector("Y1", y);
  };
  write_lab(file, l);
  for (const Cmd cmd : kAll) {
    const test::CliRun r = test::run_foglab(command_args(cmd, file, dir));
    EXPECT_EQ(r.exit_code, 0) << name_of(cmd) << ": " << r.err;
    if (cmd == Cmd::lab2) continue;  // lab2 reads the variables itself, without notes
    EXPECT_THAT(r.err, HasSubstr("note:"));
    EXPECT_THAT(r.err, HasSubstr("'Y1'"));
    EXPECT_THAT(r.err, HasSubstr(class_name));
    EXPECT_THAT(r.err, HasSubstr("converted to double"));
    expect_valid_json(dir / (std::string(name_of(cmd)) + ".json"));
  }
}

TEST(HostileInputControl, IntegerClassesAreAcceptedAndConvertedWithANote) {
  for (const mat_ft version : {MAT_FT_MAT5, MAT_FT_MAT73}) {
    expect_integer_class_accepted<std::int16_t>("int16", version);
    expect_integer_class_accepted<std::uint8_t>("uint8", version);
    expect_integer_class_accepted<std::int32_t>("int32", version);
    expect_integer_class_accepted<std::uint64_t>("uint64", version);
  }
}

TEST(HostileInputControl, SingleIsReadWithoutANote) {
  test::TempDir dir;
  const fs::path file = dir / "single.mat";
  LabLayout l = layout(MAT_FT_MAT5);
  l.y_writer = [](MatWriter& m) {
    std::vector<float> y(kSamples);
    const auto d = rate_samples();
    std::copy(d.begin(), d.end(), y.begin());
    m.vector("Y1", y);
  };
  write_lab(file, l);
  const test::CliRun r = test::run_foglab(command_args(Cmd::allan, file, dir));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, Not(HasSubstr("converted")));
}

// Large but sane values (1e12 deg/h) are analysed, and the JSON holds only
// numbers and nulls.
TEST(HostileInputControl, LargeFiniteValuesGiveValidJson) {
  test::TempDir dir;
  const fs::path file = dir / "large.csv";
  csv([](auto& rows) {
    for (std::size_t k = 1; k < rows.size(); ++k) {
      set_cell(rows, k, 1, std::to_string(1e12 * (1.0 + 0.001 * static_cast<double>(k % 7))));
    }
  })(file);
  for (const Cmd cmd : kWithOptions) {
    const test::CliRun r = test::run_foglab(command_args(cmd, file, dir));
    EXPECT_EQ(r.exit_code, 0) << name_of(cmd) << ": " << r.err;
    expect_valid_json(dir / (std::string(name_of(cmd)) + ".json"));
  }
}

}  // namespace
}  // namespace foglab
