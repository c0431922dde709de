// Lab 1's commands end to end: `coil`, `sweep` (docs/json.md's fields),
// `simulate` and `lab1`, with the theory they must reproduce and their
// errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quote;
using test::run_foglab;
using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 299792458.0;

using test::run_json;

TEST(CliCoil, Variant6HasTheManualsFormulasInCliJsonFields) {
  // Table 4 variant 6: L = 5 km, R = 20 cm, lambda = 1550 nm.
  const json j = run_json("coil --variant 6 --json -");
  const double ks = 4.0 * kPi * 0.2 * 5000.0 / (1550e-9 * kC);
  EXPECT_NEAR(j["scale_factor_s"].get<double>(), ks, 1e-12 * ks);
  EXPECT_NEAR(j["omega_pi2_rad_s"].get<double>(), kPi / 2.0 / ks, 1e-12);
  EXPECT_NEAR(j["omega_pi2_deg_s"].get<double>(), kPi / 2.0 / ks * 180.0 / kPi, 1e-10);
  EXPECT_NEAR(j["transit_time_s"].get<double>(), 5000.0 / kC, 1e-18);
  EXPECT_NEAR(j["modulation_frequency_hz"].get<double>(), kC / 10000.0, 1e-6);
}

TEST(CliCoil, AnyCoilAndTheGroupIndex) {
  const json j = run_json(
      "coil --length 1000 --radius 0.05 --wavelength 1550e-9 "
      "--group-index 1.47 --json -");
  EXPECT_NEAR(j["transit_time_s"].get<double>(), 1.47 * 1000.0 / kC, 1e-18);
  EXPECT_NEAR(j["scale_factor_s"].get<double>(), 4.0 * kPi * 0.05 * 1000.0 / (1550e-9 * kC), 1e-12);
  // The text form names the quantities with their units.
  const test::CliRun r = run_foglab("coil --variant 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("deg/s"));
  EXPECT_THAT(r.out, HasSubstr("kHz"));
}

TEST(CliCoil, BadCoilsAreUsageErrors) {
  for (const char* args :
       {"coil", "coil --variant 7", "coil --length 1000 --radius 0.05",
        "coil --length -1 --radius 0.05 --wavelength 1e-6", "coil --variant 1 --length 100"}) {
    const test::CliRun r = run_foglab(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_THAT(r.err, ::testing::Not(HasSubstr("internal")));
  }
}

TEST(CliSweep, OpenLoopSweepIsTheSineLawWithThe30PercentRange) {
  const json coil = run_json("coil --variant 3 --json -");
  const double range = coil["omega_pi2_deg_s"].get<double>();
  const json j = run_json("sweep open-loop --variant 3 --json -");
  ASSERT_EQ(j["rates_deg_s"].size(), 10u);
  EXPECT_NEAR(j["rates_deg_s"][0].get<double>(), -range, 1e-9 * range);
  EXPECT_NEAR(j["rates_deg_s"][9].get<double>(), range, 1e-9 * range);
  // S = 2 gamma sin(phi_s) with 2 gamma = 1: sin(pi/2 * rate / range).
  for (std::size_t i = 0; i < 10; ++i) {
    const double rate = j["rates_deg_s"][i].get<double>();
    EXPECT_NEAR(j["outputs"][i].get<double>(), std::sin(kPi / 2.0 * rate / range), 1e-3);
    EXPECT_NEAR(j["scale_factors"][i].get<double>(), j["outputs"][i].get<double>() / rate, 1e-12);
  }
  double mean = 0.0;
  for (int k = 1; k <= 5; ++k) mean += std::sin(k * kPi / 10.0) / (k * kPi / 10.0) / 5.0;
  const double nl = 100.0 * (std::sin(kPi / 10.0) / (kPi / 10.0) - 2.0 / kPi) / mean;
  EXPECT_NEAR(j["nonlinearity_percent"].get<double>(), nl, 0.01);
  ASSERT_TRUE(j["range_for_30_percent_deg_s"].is_number());
  const double r30 = j["range_for_30_percent_deg_s"].get<double>();
  EXPECT_GT(r30, 0.5 * range);
  EXPECT_LT(r30, range);
}

TEST(CliSweep, ClosedLoopIsLinearWithin10Ppm) {
  const json j = run_json("sweep closed-loop --variant 5 --range 20 --json -");
  EXPECT_LT(j["nonlinearity_percent"].get<double>(), 10e-4);  // 10 ppm
  EXPECT_TRUE(j["range_for_30_percent_deg_s"].is_null());
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_NEAR(j["scale_factors"][i].get<double>(), 1.0, 1e-5);
  }
}

TEST(CliSweep, OutputPhaseGivesTheManualsFormWithScaleFactorMinusKs) {
  // Variant 3's -K_s is the manual's -4.040 s; the nonlinearity is the rate form's.
  const json coil = run_json("coil --variant 3 --json -");
  const double ks = coil["scale_factor_s"].get<double>();
  const json rate = run_json("sweep closed-loop --variant 3 --json -");
  const json phase = run_json("sweep closed-loop --variant 3 --output phase --json -");
  EXPECT_EQ(phase["output"], "phase");
  EXPECT_EQ(rate["output"], "rate");
  EXPECT_THAT(phase["units"]["outputs"].get<std::string>(), HasSubstr("rad"));
  ASSERT_EQ(phase["scale_factors"].size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_NEAR(phase["scale_factors"][i].get<double>(), -4.040, 5e-4) << i;
    EXPECT_NEAR(phase["outputs"][i].get<double>(),
                -ks * phase["rates_deg_s"][i].get<double>() * kPi / 180.0, 1e-5)
        << i;
  }
  EXPECT_NEAR(phase["nonlinearity_percent"].get<double>(),
              rate["nonlinearity_percent"].get<double>(), 1e-9);
  const test::CliRun open = run_foglab("sweep open-loop --variant 3 --output phase");
  EXPECT_EQ(open.exit_code, 2);
  EXPECT_THAT(open.err, HasSubstr("closed loop"));
  const test::CliRun bad = run_foglab("sweep closed-loop --variant 3 --output angle");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("angle"));
}

TEST(CliLab1, OutputPhaseShowsTheClosedLoopTableInTheManualsForm) {
  test::TempDir dir;
  const fs::path out = dir / "lab1";
  const test::CliRun r =
      run_foglab("lab1 --variant 3 --no-plots --output phase --out " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = test::read_file(out / "report.md");
  EXPECT_THAT(md, HasSubstr("| rate [deg/s] | output: feedback phase step u [rad] | scale factor "
                            "u/Omega [s] |"));
  EXPECT_THAT(md, HasSubstr("| 22.276 | -1.57079633 | -4.040"));
  EXPECT_THAT(md, HasSubstr("This table is in the manual's form"));
  // lab1.json keeps the rate form and adds the manual's whatever --output.
  const json j = json::parse(test::read_file(out / "lab1.json"));
  EXPECT_NEAR(j["sweeps"]["closed_loop"]["scale_factors"][0].get<double>(), 1.0, 1e-5);
  EXPECT_NEAR(j["sweeps"]["closed_loop_phase"]["scale_factors"][0].get<double>(), -4.040, 5e-4);
  // The default report says the same in one line beside its rate table.
  const test::CliRun d = run_foglab("lab1 --variant 3 --no-plots --out " + quote(dir / "d"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_THAT(test::read_file(dir / "d" / "report.md"),
              HasSubstr("its scale factor is then -K_s, -4.04018 s over this sweep"));
}

TEST(CliSweep, WithoutModulationThereIsNothingToSweep) {
  const test::CliRun r = run_foglab("sweep open-loop --variant 1 --modulation none");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("none"));
  const test::CliRun m = run_foglab("sweep open-loop --variant 1 --method guess");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_THAT(m.err, HasSubstr("guess"));
}

TEST(CliSimulate, OpenLoopReachesTheAnalyticSteadyState) {
  for (const char* modulation : {"square", "sine"}) {
    const json j = run_json(std::string("simulate open-loop --variant 4 --rate 5 --modulation ") +
                            modulation + " --json -");
    EXPECT_NEAR(j["final_output"].get<double>(), j["steady_state_output"].get<double>(), 1e-6)
        << modulation;
    EXPECT_GT(j["samples"].get<long long>(), 16 * 1000);
  }
}

TEST(CliSimulate, ClosedLoopFollowsARampAndARateFile) {
  test::TempDir dir;
  const fs::path csv = dir / "closed.csv";
  // Variant 1: Omega_pi/2 = 148.5 deg/s; a ramp to 3 Omega_pi/2 over 10 ms.
  const test::CliRun r =
      run_foglab("simulate closed-loop --variant 1 --ramp 0:445:0.01 --duration 0.012 --csv " +
                 quote(csv) + " --json " + quote(dir / "s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(test::read_file(dir / "s.json"));
  EXPECT_NEAR(j["final_output_deg_s"].get<double>(), 445.0, 1e-6 * 445.0);
  const std::string table = test::read_file(csv);
  EXPECT_GE(std::count(table.begin(), table.end(), '\n'), 5000);
  // The feedback phase psi (the manual's Fig. 11) in [0, 2 pi), reset by
  // 2 pi as the staircase leaves it: ever more often as the rate grows.
  std::istringstream rows(table);
  std::string line;
  std::getline(rows, line);  // the comment
  std::getline(rows, line);
  ASSERT_EQ(line, "time_s,rate_deg_s,error,feedback_step_rad,ramp_phase_rad,output_deg_s");
  double before = -1.0;
  int resets = 0;
  while (std::getline(rows, line)) {
    std::istringstream fields(line);
    std::string v;
    for (int k = 0; k < 5; ++k) std::getline(fields, v, ',');
    const double psi = std::stod(v);
    ASSERT_GE(psi, 0.0) << line;
    ASSERT_LT(psi, 2.0 * std::numbers::pi) << line;
    if (before >= 0.0 && std::fabs(psi - before) > std::numbers::pi) ++resets;
    before = psi;
  }
  EXPECT_GE(resets, 100);

  std::ofstream(dir / "profile.csv") << "t,rate\n0,0\n0.002,100\n0.004,100\n";
  const json p = run_json("simulate closed-loop --variant 1 --rate-file " +
                          quote(dir / "profile.csv") + " --duration 0.005 --json -");
  EXPECT_NEAR(p["final_output_deg_s"].get<double>(), 100.0, 1e-6 * 100.0);
  EXPECT_NEAR(p["final_rate_deg_s"].get<double>(), 100.0, 1e-9);

  std::ofstream(dir / "bad.csv") << "t,rate\n0,0\n0.002,100\n0.001,100\n";
  const test::CliRun bad = run_foglab("simulate closed-loop --variant 1 --rate-file " +
                                      quote(dir / "bad.csv") + " --json -");
  EXPECT_EQ(bad.exit_code, 3) << bad.err;
  EXPECT_THAT(bad.err, HasSubstr("bad.csv"));
  EXPECT_THAT(bad.err, HasSubstr("increase"));
}

TEST(CliLab1, WritesTheReportWithEveryPlotAndTheLabsNumbers) {
  test::TempDir dir;
  const fs::path out = dir / "lab1";
  const test::CliRun r = run_foglab("lab1 --variant 2 --out " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"report.html", "report.md", "sweeps.csv", "lab1.json"}) {
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  }
  EXPECT_THAT(r.out, HasSubstr("## The coil (item 1.1)"));
  EXPECT_THAT(r.out, HasSubstr("Report: " + (out / "report.html").string()));
  const json j = json::parse(test::read_file(out / "lab1.json"));
  EXPECT_NEAR(j["sweeps"]["open_loop_square"]["nonlinearity_percent"].get<double>(), 41.60, 0.01);
  EXPECT_LT(j["sweeps"]["closed_loop"]["nonlinearity_percent"].get<double>(), 10e-4);
  EXPECT_LT(j["checks"]["square_worst_deviation_of_full_scale"].get<double>(), 1e-3);
  EXPECT_LT(j["checks"]["sine_worst_deviation_of_full_scale"].get<double>(), 1e-3);
  EXPECT_NEAR(j["checks"]["off_frequency_spike_fraction"].get<double>(), 0.5, 0.01);
  const std::string html = test::read_file(out / "report.html");
  std::size_t svgs = 0;
  for (std::size_t p = html.find("<svg"); p != std::string::npos; p = html.find("<svg", p + 1)) {
    ++svgs;
  }
  EXPECT_EQ(svgs, 11u);
  EXPECT_EQ(html.find("src="), std::string::npos);  // self-contained
}

TEST(CliLab1, BadVariantAndOutAreUsageErrors) {
  test::TempDir dir;
  const test::CliRun v = run_foglab("lab1 --variant 0 --out " + quote(dir / "o"));
  EXPECT_EQ(v.exit_code, 2);
  EXPECT_THAT(v.err, HasSubstr("Table 4"));
  EXPECT_FALSE(fs::exists(dir / "o"));
  std::ofstream(dir / "taken") << "keep";
  const test::CliRun o = run_foglab("lab1 --no-plots --out " + quote(dir / "taken"));
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(test::read_file(dir / "taken"), "keep");
}

TEST(CliLab1, AnUnknownLanguageIsAUsageErrorBeforeTheWork) {
  test::TempDir dir;
  const test::CliRun r = run_foglab("lab1 --lang de --out " + quote(dir / "o"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("'en' or 'ru', got 'de'"));
  EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST(CliLab1, RussianReportOnTheTerminalAndInEveryFile) {
  // `--lang ru`: the Markdown printed and report.md are the Russian report; the CSV and the
  // JSON, interfaces, keep their English names.
  test::TempDir dir;
  const fs::path out = dir / "lab1";
  const test::CliRun r = run_foglab("lab1 --variant 2 --no-plots --lang RU --out " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("# Лабораторная работа № 1: вариант 2\n"));
  EXPECT_THAT(r.out, HasSubstr("## Расчёт параметров ВОГ (п. 1.1)"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("The coil")));
  const std::string md = test::read_file(out / "report.md");
  EXPECT_THAT(md, HasSubstr("## Выводы"));
  EXPECT_THAT(r.out, HasSubstr(md));
  EXPECT_THAT(test::read_file(out / "report.html"), HasSubstr("<html lang=\"ru\">"));
  EXPECT_THAT(test::read_file(out / "sweeps.csv"),
              HasSubstr("scheme,modulation,method,rate_deg_s,output,scale_factor\n"));
  const json j = json::parse(test::read_file(out / "lab1.json"));
  EXPECT_NEAR(j["sweeps"]["open_loop_square"]["nonlinearity_percent"].get<double>(), 41.60, 0.01);
}

}  // namespace
}  // namespace foglab
