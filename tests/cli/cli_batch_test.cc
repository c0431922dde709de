// foglab batch and generate --fleet: a fleet with known spread and planted
// outliers analysed, interrupted and resumed; failures listed while the
// rest go on; IMU files giving a unit per gyroscope; bad invocations.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using test::quote;
using ::testing::HasSubstr;

using test::read_json;

std::size_t json_files(const fs::path& dir) {
  if (!fs::exists(dir)) return 0;
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".json" && !name.starts_with(".")) ++n;
  }
  return n;
}

/// The median and 1.4826 MAD of log10 of `values` (model/fleet.h's statistics, computed
/// here independently).
std::pair<double, double> log_median_spread(std::vector<double> values) {
  for (double& v : values) v = std::log10(v);
  auto median = [](std::vector<double> x) {
    std::sort(x.begin(), x.end());
    const std::size_t n = x.size();
    return n % 2 == 1 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
  };
  const double m = median(values);
  std::vector<double> deviations;
  for (const double v : values) deviations.push_back(std::fabs(v - m));
  return {m, 1.4826 * median(deviations)};
}

// 200 units (30 under AddressSanitizer, which runs ten times slower: 200 took 7 minutes
// there; it checks the resume, the Release run the statistics too), 1 h at 10 Hz,
// N and B scattered by a factor 10^0.1 = 1.26 (sigma of log10) about N = 0.06
// deg/h/sqrt(Hz), B = 0.02 deg/h; three outliers with N or B five times theirs.
TEST(CliBatch, AFleetIsResumedAfterAnInterruptionAndFindsThePlantedOutliersAndTheSpread) {
  const test::TempDir dir;
  const int units = test::kUnderAddressSanitizer ? 30 : 200;
  const double spread = 0.1, nominal_n = 0.06, nominal_b = 0.02;
  const test::CliRun made = test::run_foglab(fmt::format(
      "generate --N {} --B {} --fs 10 --hours 1 --fleet {} --spread {} --outliers 3 --seed 11 "
      "--out {}",
      nominal_n, nominal_b, units, spread, quote(dir / "fleet" / "unit.mat")));
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const nlohmann::json truth = read_json(dir / "fleet" / "fleet_truth.json");
  ASSERT_EQ(truth["units"].size(), static_cast<std::size_t>(units));
  ASSERT_EQ(truth["outliers"].size(), 3u);

  // Interrupted once ten units are done (of 200, at one unit at a time: under a second each,
  // under AddressSanitizer a few): the units written stay whole.
  const fs::path out = dir / "batch";
  const pid_t pid = test::start_foglab(
      "batch " + quote(dir / "fleet") + " --workers 1 --no-plots --out " + quote(out), dir / "err");
  ASSERT_GT(pid, 0);
  const bool midway = test::wait_until(pid, [&] { return json_files(out / "units") >= 10; });
  ::kill(pid, SIGINT);
  const int code = test::wait_for(pid);
  ASSERT_TRUE(midway) << test::read_file(dir / "err");
  ASSERT_EQ(code, 128 + SIGINT) << test::read_file(dir / "err");
  EXPECT_TRUE(test::temporaries(out).empty());
  EXPECT_FALSE(fs::exists(out / "fleet.json"));
  const std::size_t done = json_files(out / "units");
  ASSERT_LT(done, static_cast<std::size_t>(units));
  std::map<std::string, std::string> kept;
  for (const auto& e : fs::directory_iterator(out / "units")) {
    kept[e.path().string()] = test::read_file(e.path());
  }

  // The rerun keeps those and analyses the rest.
  const test::CliRun rerun =
      test::run_foglab("batch " + quote(dir / "fleet" / "*.mat") + " --out " + quote(out));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_THAT(rerun.out, HasSubstr(fmt::format("{} analysed, {} kept from an earlier run",
                                               units - static_cast<int>(done), done)));
  for (const auto& [path, content] : kept) EXPECT_EQ(test::read_file(path), content) << path;
  for (const char* name : {"fleet.json", "fleet.csv", "fleet.md", "fleet.html"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  const nlohmann::json fleet = read_json(out / "fleet.json");
  ASSERT_EQ(fleet["units"].size(), static_cast<std::size_t>(units));
  EXPECT_TRUE(fleet["failures"].empty());

  if (test::kUnderAddressSanitizer) return;  // too few units for the fleet's statistics

  // The outliers: exactly the planted units on N and B. A five-fold N or B also
  // raises the unit's ADEV minimum, so the bias instability may flag them too,
  // and only them.
  std::set<std::pair<std::string, std::string>> planted, found_nb;
  std::set<std::string> planted_units;
  for (const auto& o : truth["outliers"]) {
    planted.insert({o["unit"].get<std::string>(), o["parameter"].get<std::string>()});
    planted_units.insert(o["unit"].get<std::string>());
  }
  for (const auto& o : fleet["fleet"]["outliers"]) {
    const std::string parameter = o["parameter"], unit = o["unit"];
    if (parameter == "N" || parameter == "B") {
      found_nb.insert({unit, parameter});
    } else if (parameter == "bias_instability") {
      EXPECT_TRUE(planted_units.contains(unit)) << o.dump();
    }
  }
  EXPECT_EQ(found_nb, planted);

  // The fleet's median and spread of N and B against the truth's. Each unit's
  // estimate has its own error (sd e of log10(estimate/truth), measured here), which
  // widens the spread the batch sees to sqrt(s^2 + e^2) and moves the median by
  // about e/sqrt(units); the tolerances are 3 standard errors of the median
  // (1.2533 s/sqrt(n)) and of the MAD sigma (1.166 s/sqrt(n)) of a normal sample.
  std::map<std::string, nlohmann::json> truth_of;
  for (const auto& u : truth["units"]) truth_of[u["unit"].get<std::string>()] = u;
  for (const std::string p : {"N", "B"}) {
    SCOPED_TRACE(p);
    std::vector<double> true_values, estimates;
    double error_sq = 0.0;
    for (const auto& u : fleet["units"]) {
      const std::string unit = u["unit"];
      if (planted_units.contains(unit) || u[p]["status"] != "resolved") continue;
      const double t = truth_of.at(unit)["model"][p], e = u[p]["value"];
      true_values.push_back(t);
      estimates.push_back(e);
      error_sq += std::pow(std::log10(e / t), 2);
    }
    ASSERT_GE(true_values.size(), static_cast<std::size_t>(units * 9 / 10));
    const double n = static_cast<double>(true_values.size());
    const double error = std::sqrt(error_sq / n);
    const auto [true_median, true_spread] = log_median_spread(true_values);
    const nlohmann::json* stats = nullptr;
    for (const auto& s : fleet["fleet"]["parameters"]) {
      if (s["name"] == p) stats = &s;
    }
    ASSERT_NE(stats, nullptr);
    const double seen = std::hypot(true_spread, error);
    EXPECT_NEAR(std::log10((*stats)["median"].get<double>()), true_median,
                3.0 * 1.2533 * seen / std::sqrt(n));
    EXPECT_NEAR((*stats)["spread_log10"].get<double>(), seen, 3.0 * 1.166 * seen / std::sqrt(n));
    // And the drawn fleet follows its spec (the generator's truth against the spec).
    EXPECT_NEAR(true_median, std::log10(p == "N" ? nominal_n : nominal_b),
                3.0 * 1.2533 * spread / std::sqrt(n));
    EXPECT_NEAR(true_spread, spread, 3.0 * 1.166 * spread / std::sqrt(n));
  }

  // The CSV has a row per unit; the Markdown names the outliers.
  const std::string csv = test::read_file(out / "fleet.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), units + 1);
  const std::string md = test::read_file(out / "fleet.md");
  for (const auto& [unit, parameter] : planted) EXPECT_THAT(md, HasSubstr("| " + unit + " | "));
}

TEST(CliBatch, AFailedRecordIsListedAndTheRestGoOn) {
  const test::TempDir dir;
  fs::create_directory(dir / "in");
  for (int k = 1; k <= 3; ++k) {
    const test::CliRun g = test::run_foglab(
        fmt::format("generate --N 0.3 --B 0.05 --fs 10 --hours 0.2 --seed {} --out {}", k,
                    quote(dir / "in" / fmt::format("good{}.csv", k))));
    ASSERT_EQ(g.exit_code, 0) << g.err;
  }
  std::ofstream(dir / "in" / "broken.csv") << "t,rate\n0,1\n0.1,oops\n";
  std::ofstream(dir / "in" / "short.csv") << "t,rate\n0,1\n0.1,2\n0.2,3\n";
  std::ofstream(dir / "in" / "notes.json") << "{}\n";  // not a recording: left out

  const fs::path out = dir / "out";
  const test::CliRun first =
      test::run_foglab("batch " + quote(dir / "in") + " --out " + quote(out));
  EXPECT_EQ(first.exit_code, 3) << first.err;
  EXPECT_THAT(first.err, HasSubstr("2 of 5 record(s) failed"));
  EXPECT_THAT(first.out, HasSubstr("3 unit(s) from 5 recording(s)"));
  const nlohmann::json fleet = read_json(out / "fleet.json");
  EXPECT_EQ(fleet["units"].size(), 3u);
  ASSERT_EQ(fleet["failures"].size(), 2u);
  EXPECT_THAT(fleet["failures"][0]["input"].get<std::string>(), HasSubstr("broken.csv"));
  EXPECT_THAT(fleet["failures"][0]["error"].get<std::string>(), HasSubstr("line 3"));
  EXPECT_THAT(fleet["failures"][1]["input"].get<std::string>(), HasSubstr("short.csv"));
  EXPECT_EQ(fleet["failures"][1]["exit_code"], 3);
  const std::string md = test::read_file(out / "fleet.md");
  EXPECT_THAT(md, HasSubstr("## Records that failed"));
  EXPECT_THAT(md, HasSubstr("broken.csv"));

  // Each unit's JSON is analyze's: the same document as `analyze --json` of its file.
  const test::CliRun alone = test::run_foglab("analyze " + quote(dir / "in" / "good2.csv") +
                                              " --json " + quote(dir / "good2.json"));
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  nlohmann::json a = read_json(dir / "good2.json"), b = read_json(out / "units" / "good2.json");
  a.erase("notes");  // batch adds the reader's notes, which analyze prints instead
  b.erase("notes");
  EXPECT_EQ(a, b);

  // A rerun keeps the three and tries the failed two again; other options redo all.
  const test::CliRun again =
      test::run_foglab("batch " + quote(dir / "in") + " --out " + quote(out));
  EXPECT_EQ(again.exit_code, 3);
  EXPECT_THAT(again.out, HasSubstr("0 analysed, 3 kept from an earlier run, 2 failed"));
  const test::CliRun decade = test::run_foglab("batch " + quote(dir / "in" / "good*.csv") +
                                               " --taus decade --out " + quote(out));
  EXPECT_EQ(decade.exit_code, 0) << decade.err;
  EXPECT_THAT(decade.out, HasSubstr("3 analysed, 0 kept from an earlier run, 0 failed"));
}

TEST(CliBatch, AnImuRecordingGivesAUnitPerGyroscope) {
  const test::TempDir dir;
  const test::CliRun g =
      test::run_foglab("generate --imu --hours 0.05 --seed 4 --out " + quote(dir / "imu.csv") +
                       " --truth " + quote(dir / "truth.json"));
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const fs::path out = dir / "out";
  const test::CliRun r =
      test::run_foglab("batch " + quote(dir / "imu.csv") + " --no-plots --out " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json fleet = read_json(out / "fleet.json");
  ASSERT_EQ(fleet["units"].size(), 3u);
  const nlohmann::json truth = read_json(dir / "truth.json");
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string channel = std::string("gyro_") + "xyz"[k];
    const auto& u = fleet["units"][k];
    EXPECT_EQ(u["unit"], "imu." + channel);
    EXPECT_EQ(u["channel"], channel);
    EXPECT_TRUE(fs::exists(out / "units" / ("imu." + channel + ".json")));
    // Each axis's white noise, against that axis's truth (the axes differ by up to 15 %).
    const double n_true = truth["axes"][channel]["N"];
    EXPECT_NEAR(u["N"]["value"].get<double>() / n_true, 1.0, 0.05) << channel;
  }
}

// A gyro whose white noise is not yet steady (its variance rising 30 % over
// the record, as in a warm-up) beside two steady ones, 2^16 samples at
// 10 Hz: the short taus' stationarity check (stats/allan_drift.h) marks it
// in the fleet (JSON, CSV, the units' table, the summary's count) and in the
// IMU form's summary table, and leaves the steady ones as "none".
TEST(CliBatch, AUnitWhoseShortTauNoiseTrendsIsMarkedInTheFleetAndTheImuTable) {
  const test::TempDir dir;
  const fs::path file = dir / "imu.csv";
  {
    std::mt19937_64 rng(2026);
    std::normal_distribution<double> white(0.0, 0.1);
    std::ofstream out(file);
    out << "gyro_x,gyro_y,gyro_z\n";
    constexpr int n = 1 << 16;
    for (int i = 0; i < n; ++i) {
      const double rising = std::sqrt(1.0 + 0.3 * i / n);
      out << fmt::format("{:.6g},{:.6g},{:.6g}\n", white(rng), white(rng), white(rng) * rising);
    }
  }
  const fs::path out = dir / "out";
  const test::CliRun r = test::run_foglab("batch " + quote(file) +
                                          " --fs 10 --units deg/h --no-plots --out " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json fleet = read_json(out / "fleet.json");
  ASSERT_EQ(fleet["units"].size(), 3u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_TRUE(fleet["units"][k]["short_tau_trend_tau_s"].empty()) << k;
  }
  const auto trend = fleet["units"][2]["short_tau_trend_tau_s"].get<std::vector<double>>();
  ASSERT_FALSE(trend.empty());
  EXPECT_DOUBLE_EQ(trend.front(), 0.1);  // the white level's rise shows from the first tau
  EXPECT_EQ(fleet["units_of"]["short_tau_trend_tau_s"], "s");
  const std::string csv = test::read_file(out / "fleet.csv");
  EXPECT_THAT(csv, HasSubstr(",short_tau_trend_tau_s\n"));
  EXPECT_THAT(csv, HasSubstr(",none\n"));
  EXPECT_THAT(csv, HasSubstr(",0.1 0.2"));
  const std::string md = test::read_file(out / "fleet.md");
  EXPECT_THAT(md, HasSubstr("the short-tau noise trends over the run on 1 "));
  EXPECT_THAT(md, HasSubstr("| 0.1, 0.2"));
  EXPECT_THAT(md, HasSubstr("| none (z within ±"));

  const test::CliRun imu = test::run_foglab("analyze " + quote(file) + " --fs 10 --units deg/h");
  ASSERT_EQ(imu.exit_code, 0) << imu.err;
  EXPECT_THAT(imu.out, HasSubstr("| short-tau trend over the run |"));
  for (const char* axis : {"gyro_x", "gyro_y", "gyro_z"}) {
    const std::size_t row = imu.out.find(std::string("| ") + axis + " |");
    ASSERT_NE(row, std::string::npos) << axis;
    const std::string line = imu.out.substr(row, imu.out.find('\n', row) - row);
    EXPECT_THAT(line, HasSubstr(axis == std::string("gyro_z") ? "| 0.1, 0.2" : "| none (z within"))
        << line;
  }
}

TEST(CliBatch, BadInvocationsAreUsageErrorsNamingTheInput) {
  const test::TempDir dir;
  fs::create_directory(dir / "empty");
  std::ofstream(dir / "file.txt") << "1\n";
  struct Case {
    std::string args;
    std::string words;
  };
  const Case cases[] = {
      {quote(dir / "missing.csv") + " --out " + quote(dir / "o"), "missing.csv': no such file"},
      {quote(dir / "empty") + " --out " + quote(dir / "o"), "holds no recording"},
      {quote(dir / "nothing*.mat") + " --out " + quote(dir / "o"), "matches no file"},
      {quote(dir / "file.txt") + " --fs 1 --out " + quote(dir / "file.txt"), "not a folder"},
      {quote(dir / "file.txt") + " --fs 1 --outlier-z 0 --out " + quote(dir / "o"), "--outlier-z"},
      {"- --out " + quote(dir / "o"), "batch reads files"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const test::CliRun r = test::run_foglab("batch " + c.args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.words));
  }
  EXPECT_FALSE(fs::exists(dir / "o"));
  EXPECT_EQ(test::read_file(dir / "file.txt"), "1\n");
}

TEST(CliGenerateFleet, BadFleetOptionsAreUsageErrors) {
  const test::TempDir dir;
  struct Case {
    std::string args;
    std::string words;
  };
  const std::string base = "generate --N 0.1 --fs 10 --hours 0.01 ";
  const Case cases[] = {
      {base + "--fleet 10 --outliers 2 --out " + quote(dir / "f" / "u.mat"), "at most a tenth"},
      {base + "--outliers 1 --out " + quote(dir / "u.mat"), "need --fleet"},
      {base + "--fleet 10 --out u.mat", "FOLDER/NAME.EXT"},
      {base + "--fleet 10 --spread -1 --out " + quote(dir / "f" / "u.mat"), "spread"},
      {base + "--fleet 10 --truth t.json --out " + quote(dir / "f" / "u.mat"), "fleet_truth.json"},
      {"generate --R 1 --fs 10 --hours 0.01 --fleet 10 --out " + quote(dir / "f" / "u.mat"),
       "none of N, B, K"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const test::CliRun r = test::run_foglab(c.args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.words));
  }
  EXPECT_FALSE(fs::exists(dir / "f"));
}

}  // namespace
}  // namespace foglab
