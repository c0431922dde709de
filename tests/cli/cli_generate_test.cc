// CLI tests of `foglab generate` and `foglab lab2-data`.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "foglab/io/reader.h"
#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using test::quote;
using test::run_foglab;

io::ReadOptions channel(const std::string& name) {
  io::ReadOptions o;
  o.channel = name;
  return o;
}

double adev_at(const json& allan, double tau_s) {
  const auto& taus = allan["tau_s"];
  for (std::size_t k = 0; k < taus.size(); ++k) {
    if (std::abs(taus[k].get<double>() - tau_s) < 1e-9) return allan["dev"][k].get<double>();
  }
  ADD_FAILURE() << "no tau " << tau_s;
  return 0.0;
}

TEST(CliGenerate, WhiteNoiseRoundTripsThroughAllan) {
  test::TempDir dir;
  const auto mat = dir / "white.mat";
  const test::CliRun gen = run_foglab("generate --N 3 --fs 100 --hours 1 --seed 5 --out " +
                                      quote(mat));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_THAT(gen.out, HasSubstr("360000 samples at 100 Hz"));
  const test::CliRun allan = run_foglab("allan " + quote(mat) + " --taus 1,10 --json -");
  ASSERT_EQ(allan.exit_code, 0) << allan.err;
  const json j = json::parse(allan.out);
  // 3600 clusters at 1 s: the ADEV's relative standard error is about 1.2 %
  EXPECT_NEAR(adev_at(j, 1.0), 3.0, 0.05 * 3.0);
  EXPECT_NEAR(adev_at(j, 10.0), 3.0 / std::sqrt(10.0), 0.1 * 3.0 / std::sqrt(10.0));
}

TEST(CliGenerate, MatHoldsFtY1T1ReadableByTheReader) {
  test::TempDir dir;
  const std::string path = dir.file("run.mat");
  const test::CliRun gen =
      run_foglab("generate --preset kvh-dsp-3000 --fs 10 --hours 0.1 --temperature ramp:10 "
                 "--temp-coef 1,0.1 --out " + quote(path));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_THAT(io::list_channels(path), ::testing::ElementsAre("t", "Y1", "T1"));
  const io::Series y = io::read_series(path, channel("Y1"));
  EXPECT_EQ(y.values.size(), 3600u);
  EXPECT_EQ(y.sample_rate_hz, 10.0);
  EXPECT_EQ(y.sample_rate_source, io::SampleRateSource::variable_f);
  const io::Series t = io::read_series(path, channel("T1"));
  EXPECT_NEAR(t.values.back() - t.values.front(), 10.0, 0.5);
}

TEST(CliGenerate, CsvHasTRateTemperatureColumns) {
  test::TempDir dir;
  const std::string path = dir.file("run.csv");
  const test::CliRun gen =
      run_foglab("generate --N 1 --fs 20 --hours 0.01 --out " + quote(path));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_THAT(io::list_channels(path), ::testing::ElementsAre("t", "rate", "temperature"));
  const io::Series r = io::read_series(path, channel("rate"));
  EXPECT_EQ(r.values.size(), 720u);
  EXPECT_NEAR(r.sample_rate_hz, 20.0, 1e-6);
  EXPECT_EQ(test::read_file(path).rfind("# foglab", 0), 0u);
}

TEST(CliGenerate, RawF64IsStreamedAndEqualsTheMatRecord) {
  test::TempDir dir;
  const std::string raw = dir.file("run.f64");
  const std::string mat = dir.file("run.mat");
  const std::string model = "--N 2 --K 0.01 --B 0.5 --fs 50 --hours 0.05 --seed 9 ";
  ASSERT_EQ(run_foglab("generate " + model + "--out " + quote(raw)).exit_code, 0);
  ASSERT_EQ(run_foglab("generate " + model + "--out " + quote(mat)).exit_code, 0);
  io::ReadOptions o;
  o.sample_rate_hz = 50.0;
  const io::Series a = io::read_series(raw, o);
  const io::Series b = io::read_series(mat, channel("Y1"));
  EXPECT_EQ(fs::file_size(raw), 9000u * 8u);
  EXPECT_EQ(a.values, b.values);  // same seed, same bits, streamed or not
  const std::string f32 = dir.file("run.f32");
  ASSERT_EQ(run_foglab("generate " + model + "--out " + quote(f32)).exit_code, 0);
  EXPECT_EQ(fs::file_size(f32), 9000u * 4u);
}

TEST(CliGenerate, TruthJsonStatesEveryParameterWithUnits) {
  test::TempDir dir;
  const test::CliRun gen = run_foglab(
      "generate --preset class-tactical --B 5 --gm-sigma 0.5 --gm-tc 100 --bias 3 "
      "--temp-coef 0.2,0.01 --input-rate 12 --fs 10 --hours 0.05 --seed 42 --stream 3 "
      "--temperature ramp:10@20 --out " + quote(dir / "x.mat") + " --truth " +
      quote(dir / "truth.json"));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  const json t = json::parse(test::read_file(dir / "truth.json"));
  const json& m = t["model"];
  EXPECT_NEAR(m["N"].get<double>(), 60 * 0.158, 1e-12);  // from the preset
  EXPECT_EQ(m["B"], 5.0);                               // overridden
  EXPECT_EQ(m["gm_sigma"], 0.5);
  EXPECT_EQ(m["gm_tc"], 100.0);
  EXPECT_EQ(m["bias"], 3.0);
  EXPECT_EQ(m["input_rate"], 12.0);
  EXPECT_EQ(m["temp_coefs"], json::array({0.2, 0.01}));
  for (const char* k : {"N", "B", "K", "R", "Q", "gm_sigma", "gm_tc", "bias", "input_rate",
                        "temp_coefs"}) {
    EXPECT_TRUE(m.contains(k)) << k;
    EXPECT_TRUE(t["units"].contains(k)) << k;
  }
  EXPECT_EQ(t["units"]["N"], "deg/h/sqrt(Hz)");
  EXPECT_EQ(t["preset"], "class-tactical");
  EXPECT_EQ(t["sample_rate_hz"], 10.0);
  EXPECT_EQ(t["duration_s"], 180.0);
  EXPECT_EQ(t["samples"], 1800);
  EXPECT_EQ(t["seed"], 42);
  EXPECT_EQ(t["stream"], 3);
  EXPECT_EQ(t["temperature"]["kind"], "ramp");
  EXPECT_EQ(t["temperature"]["start_c"], 20.0);
  EXPECT_EQ(t["temperature"]["span_c"], 10.0);
  EXPECT_EQ(t["temperature"]["reference_c"], 25.0);
  EXPECT_TRUE(t["foglab_version"].is_string());
  EXPECT_EQ(t["output"]["variables"], json::array({"f", "t", "Y1", "T1"}));
  EXPECT_TRUE(t["theory"]["bias_instability_deg_h"].is_number());
}

TEST(CliGenerate, BadOptionsAreUsageErrorsWithAMessage) {
  test::TempDir dir;
  const std::string out = " --out " + quote(dir / "x.mat");
  struct Case {
    std::string args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"generate --N 1 --hours 1" + out, "--fs is required"},
      {"generate --N 1 --fs 10" + out, "--hours"},
      {"generate --N 1 --fs 0 --hours 1" + out, "--fs must be from 1e-06 to 1e+09 Hz"},
      {"generate --N 1 --fs 10 --hours -2" + out, "--hours must be in (0, 1e6]"},
      {"generate --N 1 --fs 10 --hours 1 --out " + quote(dir / "x.txt"),
       "unknown output type '.txt'"},
      {"generate --preset nope --fs 10 --hours 1" + out, "unknown preset 'nope'"},
      {"generate --N 1 --fs 10 --hours 1 --temp-coef 1,x" + out, "'x' is not a number"},
      {"generate --N -1 --fs 10 --hours 0.01" + out, "N"},
      {"generate --N 1 --fs 10 --hours 0.01 --temperature bogus" + out, "bogus"},
      {"generate --N 1 --fs 10 --hours 0.01 --out " + quote(dir / "no" / "x.mat"), "cannot write"},
  };
  for (const Case& c : cases) {
    const test::CliRun r = run_foglab(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
  }
  EXPECT_FALSE(fs::exists(dir / "x.mat"));
}

TEST(CliLab2Data, WritesTwelveFilesAndTheAnswerKey) {
  test::TempDir dir;
  const auto out = dir / "new" / "lab2";  // created, parents too
  const test::CliRun r = run_foglab("lab2-data --out " + quote(out) + " --seed 7 --hours 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int g = 1; g <= 2; ++g) {
    for (int k = 1; k <= 6; ++k) {
      const std::string path = (out / ("FOG" + std::to_string(g) + "_" + std::to_string(k) +
                                       ".mat")).string();
      ASSERT_TRUE(fs::exists(path)) << path;
      EXPECT_THAT(io::list_channels(path),
                  ::testing::ElementsAre("t", "Y1", "Y2", "T1", "T2"));
      EXPECT_THAT(r.out, HasSubstr(fs::path(path).filename().string()));
    }
  }
  const json a = json::parse(test::read_file(out / "answers.json"));
  EXPECT_EQ(a["seed"], 7);
  EXPECT_EQ(a["runs"].size(), 24u);
  EXPECT_EQ(a["gyros"].size(), 12u);
  const json& first = a["runs"][0];
  EXPECT_EQ(first["file"], "FOG1_1.mat");
  for (const char* k : {"polyfit_p", "lab_constant_term_deg_h", "bias_at_t_ref_deg_h", "N",
                        "arw_deg_per_sqrt_h", "random_bias_process", "K", "gm_sigma", "gm_tc",
                        "bias_instability_deg_h", "bias_instability_tau_s", "accuracy_class"}) {
    EXPECT_TRUE(first["expected"].contains(k)) << k;
  }
  const std::string csv = test::read_file(out / "answers.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2 + 24);
  EXPECT_THAT(csv, HasSubstr("FOG2_6.mat,FOG2,6,ramp,Y2,T2"));
}

TEST(CliLab2Data, MissingOutIsAUsageError) {
  const test::CliRun r = run_foglab("lab2-data");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--out"));
}

}  // namespace
}  // namespace foglab
