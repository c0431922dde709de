// `foglab analyze` on real gyros: three ADIS16405 MEMS IMUs, 100 Hz, 2.78 h
// (../shared/data/real/, CC BY-NC-SA test data, never copied into the
// repository; the test skips, saying so, without them). Their output is
// low-pass filtered and quantised in 0.05 deg/s steps; the Allan deviation
// falls with slope -1/2 from about 0.1 s to 10 s and flattens at some tens
// of deg/h. docs/validation.md has the table of every channel.
//
// Every axis: N is the white level of the -1/2 region (the graphical
// reading) within 5 %, the filter is reported as the sensor bandwidth and
// never as a Gauss-Markov random bias below the tau range, the class is
// consumer. The z axes carry a resonance near 20 Hz, reported as a spectral
// line and kept out of the noise terms; x and y have none.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kRealData = fs::path(FOGLAB_SOURCE_DIR) / ".." / "shared" / "data" / "real";

struct Channel {
  int imu;
  const char* axis;
};

class RealGyro : public ::testing::TestWithParam<Channel> {};

TEST_P(RealGyro, WhiteLevelBandwidthAndClass) {
  const Channel c = GetParam();
  const fs::path file = kRealData / ("adis_16405_imu" + std::to_string(c.imu) + "_gyro.csv");
  if (!fs::exists(file)) {
    GTEST_SKIP() << "the real recordings are not here (" << file.string()
                 << "): they live in ../shared/data/real beside the checkout";
  }
  const test::CliRun run = test::run_foglab("analyze " + test::quote(file) + " --channel gyro_" +
                                            c.axis + "_dps --fs 100 --units deg/s --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json j = json::parse(run.out);

  const double n = j["noise_model"]["N"]["value"].get<double>();
  const double white_level = j["readings"]["adev"]["N"].get<double>();
  EXPECT_NEAR(n / white_level, 1.0, 0.05) << "N " << n << ", ADEV reading " << white_level;
  // The interval holds the estimate and is not degenerate.
  const auto& ci = j["noise_model"]["N"]["ci95"];
  EXPECT_LT(ci[0].get<double>(), n);
  EXPECT_GT(ci[1].get<double>(), n);

  const json& bw = j["sensor_bandwidth"];
  ASSERT_TRUE(bw["resolved"].get<bool>());
  EXPECT_FALSE(bw["at_search_bound"].get<bool>());
  EXPECT_GT(bw["cutoff_hz"].get<double>(), 5.0);
  EXPECT_LT(bw["cutoff_hz"].get<double>(), 50.0);  // below Nyquist
  // The samples' own lag-1 correlation is about 0.18 on these records.
  EXPECT_GT(bw["lag1_correlation"].get<double>(), 0.1);
  EXPECT_LT(bw["lag1_correlation"].get<double>(), 0.3);

  // No Gauss-Markov term with Tc below the tau range.
  if (j["noise_model"]["gm_tc"]["status"] == "resolved") {
    EXPECT_GE(j["noise_model"]["gm_tc"]["value"].get<double>(),
              j["allan"]["tau_s"][0].get<double>());
  }
  const json& lines = j["spectral_lines"];
  if (std::string(c.axis) == "z") {
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NEAR(lines[0]["frequency_hz"].get<double>(), 20.0, 1.0);
  } else {
    EXPECT_TRUE(lines.empty()) << lines.dump();
  }
  // The output word: 0.05 deg/s = 180 deg/h per LSB.
  ASSERT_TRUE(j["output_quantisation"]["detected"].get<bool>());
  EXPECT_NEAR(j["output_quantisation"]["lsb_deg_h"].get<double>(), 180.0, 1e-6);
  EXPECT_EQ(j["accuracy_class"], "consumer");
  EXPECT_EQ(j["fit"]["status"], "converged");
}

INSTANTIATE_TEST_SUITE_P(Adis16405, RealGyro,
                         ::testing::Values(Channel{1, "x"}, Channel{1, "y"}, Channel{1, "z"},
                                           Channel{2, "x"}, Channel{2, "y"}, Channel{2, "z"},
                                           Channel{3, "x"}, Channel{3, "y"}, Channel{3, "z"}),
                         [](const auto& info) {
                           return "imu" + std::to_string(info.param.imu) + "_" + info.param.axis;
                         });

}  // namespace
}  // namespace foglab
