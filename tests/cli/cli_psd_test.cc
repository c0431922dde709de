// `foglab psd` end to end: the JSON contract and the white-noise level.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli.h"
#include "support/noise.h"

namespace foglab {
namespace {

using nlohmann::json;

TEST(CliPsd, WhiteNoiseLevelIsNSquaredTwoSidedWithTheContractFields) {
  test::TempDir dir;
  constexpr double kFsHz = 200.0;
  constexpr double kN = 0.3;  // deg/h/sqrt(Hz)
  {
    std::ofstream out(dir / "white.f64", std::ios::binary);
    const auto noise = test::white(1 << 18, 31, kN * std::sqrt(kFsHz));
    out.write(reinterpret_cast<const char*>(noise.data()),
              static_cast<std::streamsize>(noise.size() * sizeof(double)));
  }
  const test::CliRun r = test::run_foglab("psd " + test::quote(dir / "white.f64") +
                                          " --fs 200 --segment 4096 --json -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["sided"], "two");
  EXPECT_EQ(j["unit"], "(deg/h)^2/Hz");
  ASSERT_EQ(j["frequency_hz"].size(), 2048u);
  ASSERT_EQ(j["psd"].size(), 2048u);
  ASSERT_EQ(j["sqrt_psd"].size(), 2048u);
  EXPECT_DOUBLE_EQ(j["frequency_hz"][0].get<double>(), 200.0 / 4096);
  double mean = 0.0;
  for (const auto& v : j["psd"]) mean += v.get<double>();
  mean /= static_cast<double>(j["psd"].size());
  // 127 segments x 2048 bins: the mean level is known to well under 1 %.
  EXPECT_NEAR(mean / (kN * kN), 1.0, 0.02);
  EXPECT_NEAR(j["sqrt_psd"][100].get<double>(), std::sqrt(j["psd"][100].get<double>()), 1e-12);
  EXPECT_GT(j["smoothed"]["frequency_hz"].size(), 20u);
  EXPECT_LT(j["smoothed"]["frequency_hz"].size(), 2048u);
}

TEST(CliPsd, CsvHasUnitsInTheHeaderAndTheTableGoesToStdout) {
  test::TempDir dir;
  const test::CliRun r = test::run_foglab("psd --csv " + test::quote(dir / "psd.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = test::read_file(dir / "psd.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "frequency_hz,psd_deg2_h2_per_hz,sqrt_psd_deg_h_per_sqrt_hz");
  EXPECT_NE(r.out.find("sqrt [deg/h/sqrt(Hz)]"), std::string::npos);
  const test::CliRun bad = test::run_foglab("psd --segment 8");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("segment"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace foglab
