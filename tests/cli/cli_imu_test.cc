// A whole IMU in one run (issue 17): `foglab generate --imu` writes six axes
// with their truth (CSV, MAT or a ROS bag with jitter and dropped
// messages), `foglab analyze` reads them all, analyses them in parallel and
// writes one JSON, one Markdown table, Kalibr's imu.yaml for both sensors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using test::read_json;

/// A `name: value` line of imu.yaml.
double yaml_value(const std::string& yaml, const std::string& name) {
  const std::regex line("\n" + name + ": ([0-9.eE+-]+)");
  std::smatch m;
  if (!std::regex_search(yaml, m, line)) {
    ADD_FAILURE() << name << " not in imu.yaml";
    return NAN;
  }
  return std::stod(m[1]);
}

constexpr const char* kAxes[] = {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"};

/// The 6-axis records of the tests below, each generated on first use (ctest
/// runs every test in a process of its own: a test makes only what it reads).
class CliImu : public ::testing::Test {
 protected:
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static const fs::path& folder() {
    if (dir_ == nullptr) dir_ = new test::TempDir;
    return dir_->path();
  }
  /// 1.5 h at 50 Hz as a ROS bag, stamps jittered by up to +-3 ms (of a
  /// 20 ms step), 3 + 50 messages dropped at 600 s and 4000 s.
  static fs::path bag() {
    const fs::path path = folder() / "imu.bag";
    if (!fs::exists(path)) {
      const test::CliRun g = test::run_foglab(
          "generate --imu --fs 50 --hours 1.5 --seed 17 --stamp-jitter 0.003 --drop 600:0.06 "
          "--drop 4000:1 --out " +
          test::quote(path) + " --truth " + test::quote(folder() / "truth.json"));
      EXPECT_EQ(g.exit_code, 0) << g.err;
    }
    return path;
  }
  /// Half an hour at 100 Hz as CSV (t, gyro_x..z, accel_x..z, temperature).
  static fs::path csv() {
    const fs::path path = folder() / "imu.csv";
    if (!fs::exists(path)) {
      const test::CliRun g = test::run_foglab(
          "generate --imu --fs 100 --hours 0.5 --seed 18 --out " + test::quote(path) + " --truth " +
          test::quote(folder() / "csv_truth.json"));
      EXPECT_EQ(g.exit_code, 0) << g.err;
    }
    return path;
  }
  static json truth() { return read_json(folder() / "truth.json"); }

  static test::TempDir* dir_;
};
test::TempDir* CliImu::dir_ = nullptr;

TEST_F(CliImu, BagIsAnalysedByOneCommandAgainstEveryAxisTruth) {
  const test::TempDir out;
  const fs::path yaml = out / "imu.yaml";
  const test::CliRun a =
      test::run_foglab("analyze " + test::quote(bag()) + " --json - --kalibr " + test::quote(yaml));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const json j = json::parse(a.out);
  const json t = truth();
  ASSERT_EQ(j["channels"].size(), 6u);
  EXPECT_EQ(j["input"]["format"], "rosbag");
  EXPECT_EQ(j["input"]["topic"], "/imu");

  // The gaps: the messages dropped, reported, not refused; the jitter
  // measured (uniform +-3 ms: rms 3/sqrt(3) ms).
  const json& gaps = j["channels"][0]["input"]["gaps"];
  ASSERT_EQ(gaps["count"], 2) << gaps.dump();
  EXPECT_EQ(gaps["missing_samples"], 53);
  EXPECT_NEAR(j["input"]["timing"]["jitter_rms_s"].get<double>() / (0.003 / std::sqrt(3.0)), 1.0,
              0.05);
  EXPECT_NEAR(j["input"]["sample_rate_hz"].get<double>(), 50.0, 1e-3);
  EXPECT_NE(a.err.find("2 gap(s) with 53 sample(s) missing"), std::string::npos) << a.err;

  for (std::size_t k = 0; k < 6; ++k) {
    const json& c = j["channels"][k];
    const json& axis = t["axes"][kAxes[k]];
    SCOPED_TRACE(kAxes[k]);
    EXPECT_EQ(c["input"]["channel"], kAxes[k]);
    EXPECT_EQ(c["sensor"], k < 3 ? "gyroscope" : "accelerometer");
    // White noise: 270,000 samples put N within a fraction of a percent.
    EXPECT_NEAR(c["noise_model"]["N"]["value"].get<double>() / axis["N"].get<double>(), 1.0, 0.02);
    // Bias instability (the ADEV minimum) against the model's.
    const double bi = c[k < 3 ? "bias_instability_deg_h" : "bias_instability_m_s2"].get<double>();
    EXPECT_NEAR(bi / axis["bias_instability"].get<double>(), 1.0, 0.35);
    // The random walk: the truth lies in the 95 % interval (or under the
    // upper bound of a K the record does not resolve).
    const json& kp = c["noise_model"]["K"];
    const double k_true = axis["K"].get<double>();
    if (kp["status"] == "resolved") {
      EXPECT_GE(k_true, kp["ci95"][0].get<double>());
      EXPECT_LE(k_true, kp["ci95"][1].get<double>());
    } else {
      EXPECT_LE(k_true, kp["upper_95"].get<double>());
    }
  }
  // An accelerometer speaks in its units and has no class.
  const json& ax = j["channels"][3];
  EXPECT_TRUE(ax["allan"].contains("adev_m_s2"));
  EXPECT_FALSE(ax["allan"].contains("adev_deg_h"));
  EXPECT_TRUE(ax["accuracy_class"].is_null());
  EXPECT_NEAR(ax["filter"]["velocity_random_walk_m_s_per_sqrt_h"].get<double>(),
              60.0 * ax["noise_model"]["N"]["value"].get<double>(), 1e-12);
  EXPECT_EQ(ax["units"]["allan.adev_m_s2"], "m/s^2");

  // Kalibr: the four values in its units, against the truth's.
  const std::string y = test::read_file(yaml);
  const json& kt = t["kalibr"];
  EXPECT_NEAR(
      yaml_value(y, "gyroscope_noise_density") / kt["gyroscope_noise_density"].get<double>(), 1.0,
      0.02);
  EXPECT_NEAR(yaml_value(y, "accelerometer_noise_density") /
                  kt["accelerometer_noise_density"].get<double>(),
              1.0, 0.02);
  // The random walks: within a factor 2 of the truth (each axis's interval
  // spans about that at 1.5 h), and the JSON says the same as the file.
  for (const char* name : {"gyroscope_random_walk", "accelerometer_random_walk"}) {
    const double ratio = yaml_value(y, name) / kt[name].get<double>();
    EXPECT_GT(ratio, 0.5) << name;
    EXPECT_LT(ratio, 2.0) << name;
    EXPECT_NEAR(j["kalibr"][name].get<double>(), yaml_value(y, name), 1e-8 * yaml_value(y, name));
  }
  EXPECT_NEAR(yaml_value(y, "update_rate"), 50.0, 1e-3);
  EXPECT_NE(y.find("rostopic: /imu"), std::string::npos);
}

TEST_F(CliImu, CsvChannelsNamedGyroAndAccelAreAnalysedTogether) {
  const test::CliRun a = test::run_foglab("analyze " + test::quote(csv()) + " --json -");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const json j = json::parse(a.out);
  ASSERT_EQ(j["channels"].size(), 6u);
  const json t = read_json(folder() / "csv_truth.json");
  for (std::size_t k = 0; k < 6; ++k) {
    SCOPED_TRACE(kAxes[k]);
    EXPECT_NEAR(j["channels"][k]["noise_model"]["N"]["value"].get<double>() /
                    t["axes"][kAxes[k]]["N"].get<double>(),
                1.0, 0.03);
  }
  // The Markdown table has a row per axis.
  const test::CliRun md = test::run_foglab("analyze " + test::quote(csv()));
  ASSERT_EQ(md.exit_code, 0) << md.err;
  for (const char* axis : kAxes) {
    EXPECT_NE(md.out.find(std::string("| ") + axis + " |"), std::string::npos) << axis;
  }
  EXPECT_NE(md.out.find("For a navigation filter"), std::string::npos);
}

TEST_F(CliImu, UnitsBySensorAndByChannelScaleExactly) {
  // The same samples read as mg instead of m/s^2: 9.80665e-3 times the
  // white level, to rounding; the gyroscopes as deg/s: 3600 times.
  const std::string base = "analyze " + test::quote(csv()) + " --channels gyro_y,accel_x --json -";
  const test::CliRun si = test::run_foglab(base);
  const test::CliRun scaled = test::run_foglab(base + " --units gyro=deg/s,accel_x=mg");
  ASSERT_EQ(si.exit_code, 0) << si.err;
  ASSERT_EQ(scaled.exit_code, 0) << scaled.err;
  const json a = json::parse(si.out), b = json::parse(scaled.out);
  ASSERT_EQ(b["channels"].size(), 2u);
  auto n = [](const json& j, int k) {
    return j["channels"][k]["noise_model"]["N"]["value"].get<double>();
  };
  EXPECT_NEAR(n(b, 0) / n(a, 0), 3600.0, 3600.0 * 1e-6);
  EXPECT_NEAR(n(b, 1) / n(a, 1), 9.80665e-3, 9.80665e-3 * 1e-6);
  EXPECT_EQ(b["channels"][1]["input"]["units"], "mg");
}

TEST_F(CliImu, OneAccelerometerChannelKeepsTheOneChannelLayout) {
  const test::CliRun a =
      test::run_foglab("analyze " + test::quote(csv()) + " --channel accel_z --json -");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const json j = json::parse(a.out);
  EXPECT_FALSE(j.contains("channels"));
  EXPECT_EQ(j["sensor"], "accelerometer");
  EXPECT_TRUE(j["allan"].contains("adev_m_s2"));
  // Gravity is the accel_z bias: the systematic part takes it out.
  EXPECT_NEAR(j["systematic"]["bias_m_s2"].get<double>(), 9.80665, 0.01);
  const test::CliRun md = test::run_foglab("analyze " + test::quote(csv()) + " --channel accel_z");
  EXPECT_NE(md.out.find("m/s/sqrt(h)"), std::string::npos) << md.out;
  EXPECT_EQ(md.out.find("deg/h"), std::string::npos) << md.out;
}

TEST_F(CliImu, MixedUnitsAndBadBagsAreClearErrors) {
  const std::string f = test::quote(csv());
  struct Case {
    std::string args;
    int code;
    std::string says;
  };
  const fs::path cut = folder() / "cut.bag";
  {
    // The first 60 % of the bag: a recording cut short.
    const std::string bytes = test::read_file(bag());
    std::ofstream(cut, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size() * 6 / 10));
  }
  const fs::path text_bag = folder() / "text.bag";
  std::ofstream(text_bag) << "t,gyro_x\n0,1\n";
  const Case cases[] = {
      {"analyze " + f + " --units gyro_x=g", 2, "mixed units"},
      {"analyze " + f + " --channels gyro_x,gyro_y --units g", 2, "mixed units"},
      {"analyze " + f + " --units gyro=g", 2, "not of the gyroscope's angular rate"},
      {"analyze " + f + " --channels gyro_x,nope", 2, "nope"},
      {"analyze " + f + " --channels gyro_x,gyro_x", 2, "named twice"},
      {"analyze " + test::quote(bag()) + " --topic /nope", 2, "/nope"},
      {"analyze " + test::quote(bag()) + " --units deg/s", 2, "rad/s"},
      {"analyze " + test::quote(bag()) + " --temp T", 2, "no temperature"},
      {"analyze " + test::quote(bag()) + " --channels gyro_w", 2, "gyro_w"},
      {"analyze " + test::quote(cut), 3, "cut.bag"},
      {"analyze " + test::quote(text_bag), 3, "text.bag"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const test::CliRun r = test::run_foglab(c.args + " --json -");
    EXPECT_EQ(r.exit_code, c.code) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
  }
}

}  // namespace
}  // namespace foglab
