// `foglab rate-table` and `foglab calibrate`: a generated run calibrated through the CLI,
// against the truth file the generator wrote; bad runs and bad options.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli.h"

namespace foglab {
namespace {

using nlohmann::json;
using test::quote;
using test::run_foglab;

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

bool holds(const json& v, double truth) {
  return v["ci95_low"].get<double>() <= truth && truth <= v["ci95_high"].get<double>();
}

TEST(CliCalibrate, AWhiteNoiseRunIsCalibratedWithinItsIntervals) {
  // A MAT run at two temperatures (linear temperature terms), white noise only: every
  // coefficient inside its 95 % interval, S within 10 ppm, the nonlinearity within 5 ppm of
  // full scale.
  const test::TempDir dir;
  const std::string run = quote(dir / "run.mat"), truth = quote(dir / "truth.json");
  const test::CliRun made =
      run_foglab("rate-table --out " + run + " --truth " + truth +
                 " --temps 10,40 --full-scale 200 --rates 4 --plateau 40 --N 0.3 --B 0 --seed 4"
                 " --sf-temp -8e-5 --bias-temp 0.4");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const test::CliRun r = run_foglab("calibrate " + run + " --json -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json c = json::parse(r.out);
  const json t = read_json(dir / "truth.json");
  EXPECT_EQ(c["plateaus"].size(), 2u * 17u);
  EXPECT_EQ(c["temperatures_c"].size(), 2u);
  const double s = t["scale_factor_lsb_per_deg_s"];
  EXPECT_TRUE(holds(c["scale_factor_lsb_per_deg_s"], s)) << c["scale_factor_lsb_per_deg_s"];
  EXPECT_LT(std::abs(c["scale_factor_lsb_per_deg_s"]["value"].get<double>() / s - 1.0), 10e-6);
  EXPECT_TRUE(holds(c["bias_lsb"], t["bias_lsb"])) << c["bias_lsb"];
  // Two temperatures: linear polynomials.
  ASSERT_EQ(c["scale_factor_temp_coefs_per_degc_k"].size(), 1u);
  ASSERT_EQ(c["bias_temp_coefs_lsb_per_degc_k"].size(), 1u);
  EXPECT_TRUE(holds(c["scale_factor_temp_coefs_per_degc_k"][0], -8e-5));
  EXPECT_TRUE(holds(c["bias_temp_coefs_lsb_per_degc_k"][0], 0.4));
  for (std::size_t k = 0; k < 2; ++k) {
    const double a = t["nonlinearity_coefs_per_deg_s_k"][k];
    const json& fit = c["nonlinearity_coefs_per_deg_s_k"][k];
    EXPECT_TRUE(holds(fit, a)) << "a_" << k + 1 << " " << fit;
    EXPECT_LT(std::abs(fit["value"].get<double>() - a) * std::pow(200.0, k + 1.0) * 1e6, 5.0);
  }
  EXPECT_TRUE(holds(c["asymmetry"], t["asymmetry"])) << c["asymmetry"];
  EXPECT_NEAR(c["white_noise_deg_h_rt_hz"].get<double>(), 0.3, 0.015);
  EXPECT_NE(c["corrected_rate_equation"].get<std::string>().find("dT = T - 25 degC"),
            std::string::npos);
}

TEST(CliCalibrate, ATriadOnThreeMountingsGivesItsMisalignment) {
  // rate-table --triad writes RUN-x, RUN-y, RUN-z; calibrate --triad reads them back: the
  // misalignment matrix within 0.05 mrad of the truth file's, every gyro its own S.
  const test::TempDir dir;
  const std::string truth = quote(dir / "truth.json");
  const test::CliRun made =
      run_foglab("rate-table --triad --out " + quote(dir / "run.csv") + " --truth " + truth +
                 " --temps 25 --rates 3 --plateau 20 --seed 3");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string files =
      quote(dir / "run-x.csv") + " " + quote(dir / "run-y.csv") + " " + quote(dir / "run-z.csv");
  const test::CliRun r = run_foglab("calibrate --triad " + files + " --json -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json c = json::parse(r.out);
  const json t = read_json(dir / "truth.json");
  ASSERT_EQ(c["axes"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const double s = t["gyros"][i]["scale_factor_lsb_per_deg_s"];
    EXPECT_LT(std::abs(c["axes"][i]["scale_factor_lsb_per_deg_s"]["value"].get<double>() / s - 1.0),
              10e-6)
        << "gyro " << i;
    EXPECT_TRUE(c["misalignment_mrad"][i][i].is_null());
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      EXPECT_NEAR(c["misalignment_mrad"][i][j]["value"].get<double>(),
                  t["misalignment_mrad"][i][j].get<double>(), 0.05)
          << "m_" << i << j;
    }
  }
  // The report: the misalignment matrix, then a section per gyro with its four plots.
  const std::string page = dir / "triad.html", md = dir / "triad.md";
  const test::CliRun rep = run_foglab("calibrate --triad " + files + " --report " + quote(page) +
                                      " --markdown " + quote(md));
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  std::ifstream html_in(page), md_in(md);
  const std::string html((std::istreambuf_iterator<char>(html_in)), {});
  const std::string markdown((std::istreambuf_iterator<char>(md_in)), {});
  EXPECT_NE(html.find("<h2>Misalignment</h2>"), std::string::npos);
  for (const char* axis : {"Gyro x", "Gyro y", "Gyro z"}) {
    EXPECT_NE(html.find(axis), std::string::npos) << axis;
    EXPECT_NE(markdown.find(std::string("## ") + axis), std::string::npos) << axis;
  }
  std::size_t figures = 0;
  for (std::size_t at = html.find("<figure>"); at != std::string::npos;
       at = html.find("<figure>", at + 1)) {
    ++figures;
  }
  EXPECT_EQ(figures, 12u);
  EXPECT_NE(markdown.find("| gyro | x | y | z |"), std::string::npos);
  // Weighted alike on request, and said so.
  const test::CliRun alike =
      run_foglab("calibrate " + quote(dir / "run-x.csv") +
                 " --triad-columns a,b,c --output-column output_x_lsb --weigh-alike --json -");
  ASSERT_EQ(alike.exit_code, 0) << alike.err;
  EXPECT_EQ(json::parse(alike.out)["weighting"], "alike");
  // --triad needs three files; two are a usage error.
  const test::CliRun two =
      run_foglab("calibrate --triad " + quote(dir / "run-x.csv") + " " + quote(dir / "run-y.csv"));
  EXPECT_EQ(two.exit_code, 2) << two.err;
  EXPECT_NE(two.err.find("--triad needs the three mountings' files"), std::string::npos) << two.err;
}

TEST(CliCalibrate, TheLabOneOpticsRunGivesTheSweepsNonlinearity) {
  // rate-table --optics: the lab-1 optics of a Table 4 variant on the lab's ten rates; the
  // truth file carries lab 1's sweep figure, which calibrate must reproduce.
  const test::TempDir dir;
  const std::string run = quote(dir / "optics.csv"), truth = quote(dir / "truth.json");
  const test::CliRun made =
      run_foglab("rate-table --optics 2 --plateau 20 --out " + run + " --truth " + truth);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const json t = read_json(dir / "truth.json");
  const double omega_pi2 = t["optics"]["omega_pi2_deg_s"];
  const test::CliRun r = run_foglab("calibrate " + run + " --json -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json c = json::parse(r.out);
  EXPECT_NEAR(c["full_scale_deg_s"].get<double>(), omega_pi2, 1e-9 * omega_pi2);
  EXPECT_EQ(c["temperatures_c"].size(), 1u);
  EXPECT_NEAR(c["nonlinearity_lab1_percent"].get<double>(),
              t["optics"]["lab1_sweep_nonlinearity_percent"].get<double>(), 0.01);
  // --optics and --triad do not go together.
  EXPECT_EQ(run_foglab("rate-table --optics 2 --triad --out " + quote(dir / "x.csv")).exit_code, 2);
}

TEST(CliCalibrate, BadRunsAndOptionsAreRefusedAndWriteNothing) {
  const test::TempDir dir;
  const std::string run = quote(dir / "run.csv"), out = dir / "out.json";
  ASSERT_EQ(run_foglab("rate-table --out " + run + " --temps 25 --rates 2 --plateau 20").exit_code,
            0);
  // No such column: named, exit 3 as for `analyze --channel`.
  test::CliRun r = run_foglab("calibrate " + run + " --rate-column rate --json " + quote(out));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("no channel column 'rate'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(out).good());
  // Standard input is read once: refused before reading, as `analyze --temp` does.
  r = run_foglab("calibrate -", "rate_cmd_deg_s,output_lsb\n1,2\n");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("standard input is read once"), std::string::npos) << r.err;
  // Settling longer than every plateau: no plateau left, a data error naming why.
  r = run_foglab("calibrate " + run + " --settle 30 --json " + quote(out));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("shorter than the settle time"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(out).good());
  // The generator refuses a plateau no longer than its settle time, and an unknown output.
  r = run_foglab("rate-table --out " + quote(dir / "x.csv") + " --plateau 5 --settle 5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("not longer than the settle time"), std::string::npos) << r.err;
  r = run_foglab("rate-table --out " + quote(dir / "x.txt"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(std::ifstream(dir / "x.txt").good());
}

}  // namespace
}  // namespace foglab
