// `foglab analyze` on real gyros: three ADIS16405 MEMS IMUs, 100 Hz, 2.78 h
// (../shared/data/real/, CC BY-NC-SA test data, never copied into the
// repository; the test skips, saying so, without them). Their output is
// low-pass filtered and quantised in 0.05 deg/s steps; the Allan deviation
// falls with slope -1/2 from about 0.1 s to 10 s and flattens at some tens
// of deg/h. docs/validation.md has the table of every channel.
//
// Every axis: N is the white level of the -1/2 region within 3 %, B is
// resolved (the Allan deviation flattens on every axis), the fitted curve
// lies inside the Allan deviation's 95 % intervals at all but at most 2 of
// its 17 taus, the filter is reported as the sensor bandwidth and never as
// a Gauss-Markov random bias below the tau range, the class is consumer.
// The z axes carry a broad resonance near 20 Hz, reported as a spectral
// line and kept out of the noise terms; x and y have none.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/cli.h"
#include "support/files.h"

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

// The white level of the -1/2 region: the geometric mean of ADEV sqrt(tau)
// over the longest run of taus whose local slopes all lie within 0.05 of
// -1/2 (at least three taus). Not the graphical reading
// (`readings.adev.N`, slopes within 0.2): on the z axes that run reaches
// the 20 Hz line's bump at 0.08 s (ADEV sqrt(tau) 152 against 138) and the
// flicker at 10-20 s, and stands 3-4 % above the white noise.
double white_level(const json& allan) {
  const auto tau = allan["tau_s"].get<std::vector<double>>();
  const auto dev = allan["adev_deg_h"].get<std::vector<double>>();
  auto on_slope = [&](std::size_t i) {
    return std::fabs(std::log(dev[i + 1] / dev[i]) / std::log(tau[i + 1] / tau[i]) + 0.5) <= 0.05;
  };
  std::size_t best_begin = 0, best_end = 0;
  for (std::size_t i = 0; i + 1 < tau.size();) {
    if (!on_slope(i)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < tau.size() && on_slope(j)) ++j;  // points i .. j
    if (j + 1 - i > best_end - best_begin) best_begin = i, best_end = j + 1;
    i = j;
  }
  if (best_end - best_begin < 3) return std::nan("");
  double sum = 0.0;
  for (std::size_t i = best_begin; i < best_end; ++i) sum += std::log(dev[i] * std::sqrt(tau[i]));
  return std::exp(sum / static_cast<double>(best_end - best_begin));
}

// How many taus' 95 % intervals the fitted curve leaves.
bool contains_note(const json& j, const std::string& text) {
  for (const json& note : j["notes"]) {
    if (note.get<std::string>().find(text) != std::string::npos) return true;
  }
  return false;
}

int taus_outside(const json& allan) {
  int outside = 0;
  for (std::size_t i = 0; i < allan["tau_s"].size(); ++i) {
    const double model = allan["model_adev_deg_h"][i].get<double>();
    outside +=
        model < allan["ci95_low"][i].get<double>() || model > allan["ci95_high"][i].get<double>();
  }
  return outside;
}

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
  const double level = white_level(j["allan"]);
  EXPECT_NEAR(n / level, 1.0, 0.03) << "N " << n << ", the -1/2 region's level " << level;
  EXPECT_EQ(j["noise_model"]["B"]["status"], "resolved") << j["fit"]["terms"];
  // The fitted curve against the Allan deviation's intervals.
  const json& allan = j["allan"];
  EXPECT_LE(taus_outside(allan), 2) << "of " << allan["tau_s"].size() << " taus";
  // The interval holds the estimate, is not degenerate, and is narrow: a
  // million samples fix the white level to well under 1 % (on the z axes it
  // had been -23/+58 % while the 20 Hz resonance's skirts were left out and
  // the bandwidths the first taus could not tell apart spread it).
  const auto& ci = j["noise_model"]["N"]["ci95"];
  EXPECT_LT(ci[0].get<double>(), n);
  EXPECT_GT(ci[1].get<double>(), n);
  EXPECT_LT(ci[1].get<double>() / ci[0].get<double>(), 1.03) << ci;

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
  // Every candidate model converges too (1 to 4 had stopped at the
  // iteration limit on each channel before the reweighting loop halved
  // the steps that raise the deviance).
  for (const auto& candidate : j["fit"]["candidates"]) {
    EXPECT_EQ(candidate["status"], "converged") << candidate["terms"];
  }
  EXPECT_NE(j["fit"]["message"].get<std::string>().find("every candidate converged"),
            std::string::npos)
      << j["fit"]["message"];

  // The short taus' stationarity (stats/allan_drift.h). The z axes'
  // resonance moves by 1-2.3 Hz over the run (imu1 z: from about 22 to
  // 20 Hz in the first hour), and their Allan variance at 0.02-0.08 s
  // rises 6-18 % from the first eighth of the record to the last; the x and
  // y axes' white level changes by 5 % at most (imu2 x and imu3 x: called
  // drifting at 0.01-0.02 s).
  const json& drift = j["allan_drift"];
  ASSERT_EQ(drift["blocks"], 32);
  ASSERT_GE(drift["tau_s"].size(), 4u);
  EXPECT_DOUBLE_EQ(drift["tau_s"][1].get<double>(), 0.02);
  // The blocks' values (the report's drift plot): 32 blocks through the
  // 2.73 h run, and the last eighth's Allan variance over the first
  // eighth's from them is the ratio reported.
  ASSERT_EQ(drift["block_time_s"].size(), 32u);
  EXPECT_NEAR(drift["block_time_s"][0].get<double>(),
              0.5 / 32.0 * j["input"]["duration_s"].get<double>(), 1.0);
  EXPECT_NEAR(drift["block_time_s"][31].get<double>(),
              31.5 / 32.0 * j["input"]["duration_s"].get<double>(), 1.0);
  ASSERT_EQ(drift["block_adev_deg_h"].size(), drift["tau_s"].size());
  for (std::size_t k = 0; k < drift["tau_s"].size(); ++k) {
    const json& adev = drift["block_adev_deg_h"][k];
    ASSERT_EQ(adev.size(), 32u);
    double first = 0.0, last = 0.0;
    for (std::size_t b = 0; b < 4; ++b) {
      first += std::pow(adev[b].get<double>(), 2);
      last += std::pow(adev[28 + b].get<double>(), 2);
    }
    EXPECT_NEAR(last / first, drift["last_to_first_ratio"][k].get<double>(), 1e-9);
  }
  if (std::string(c.axis) == "z") {
    EXPECT_TRUE(drift["drifting"][1].get<bool>()) << drift.dump();
    EXPECT_GT(drift["last_to_first_ratio"][2].get<double>(), 1.05) << drift.dump();
    EXPECT_TRUE(contains_note(j, "changes over the record")) << j["notes"].dump();
  } else {
    // At 0.01-0.08 s, where four blocks' mean scatters by under 1.5 %.
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_NEAR(drift["last_to_first_ratio"][k].get<double>(), 1.0, 0.07) << drift.dump();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Adis16405, RealGyro,
                         ::testing::Values(Channel{1, "x"}, Channel{1, "y"}, Channel{1, "z"},
                                           Channel{2, "x"}, Channel{2, "y"}, Channel{2, "z"},
                                           Channel{3, "x"}, Channel{3, "y"}, Channel{3, "z"}),
                         [](const auto& info) {
                           return "imu" + std::to_string(info.param.imu) + "_" + info.param.axis;
                         });

// The three axes of one IMU in one run (issue 17): found by their names,
// analysed in parallel, each with exactly the numbers of its own run.
TEST(RealImu, ThreeAxesInOneRunGiveEachAxisItsOwnAnalysis) {
  const fs::path file = kRealData / "adis_16405_imu1_gyro.csv";
  if (!fs::exists(file)) {
    GTEST_SKIP() << "the real recordings are not here (" << file.string()
                 << "): they live in ../shared/data/real beside the checkout";
  }
  const test::CliRun all =
      test::run_foglab("analyze " + test::quote(file) + " --fs 100 --units deg/s --json -");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const json j = json::parse(all.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  const test::CliRun one = test::run_foglab(
      "analyze " + test::quote(file) + " --channel gyro_z_dps --fs 100 --units deg/s --json -");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const json z = json::parse(one.out);
  const json& z_in_all = j["channels"][2];
  EXPECT_EQ(z_in_all["input"]["channel"], "gyro_z_dps");
  EXPECT_EQ(z_in_all["sensor"], "gyroscope");
  // The same analysis; only the order of the parallel sums differs (a core
  // per axis here, both cores there).
  for (const char* p : {"N", "B", "K", "gm_sigma"}) {
    SCOPED_TRACE(p);
    EXPECT_EQ(z_in_all["noise_model"][p]["status"], z["noise_model"][p]["status"]);
    const json &a = z_in_all["noise_model"][p]["value"], &b = z["noise_model"][p]["value"];
    ASSERT_EQ(a.is_null(), b.is_null());
    if (!a.is_null()) {
      EXPECT_NEAR(a.get<double>(), b.get<double>(), 1e-6 * std::fabs(b.get<double>()));
    }
  }
  const auto adev_all = z_in_all["allan"]["adev_deg_h"].get<std::vector<double>>();
  const auto adev_one = z["allan"]["adev_deg_h"].get<std::vector<double>>();
  ASSERT_EQ(adev_all.size(), adev_one.size());
  for (std::size_t k = 0; k < adev_one.size(); ++k) {
    EXPECT_NEAR(adev_all[k], adev_one[k], 1e-9 * adev_one[k]);
  }
  EXPECT_EQ(z_in_all["accuracy_class"], z["accuracy_class"]);
  // Kalibr's gyroscope density: the root mean square of the three axes' N.
  double sum = 0.0;
  for (const json& c : j["channels"])
    sum += std::pow(c["noise_model"]["N"]["value"].get<double>(), 2);
  EXPECT_NEAR(j["kalibr"]["gyroscope_noise_density"].get<double>(),
              std::sqrt(sum / 3.0) * M_PI / 180.0 / 3600.0, 1e-12);
  EXPECT_TRUE(j["kalibr"]["accelerometer_noise_density"].is_null());
}

// The three columns (x, y, z) of real recording `imu` as written.
std::array<std::vector<std::string>, 3> read_axes(int imu) {
  const fs::path file = kRealData / ("adis_16405_imu" + std::to_string(imu) + "_gyro.csv");
  std::array<std::vector<std::string>, 3> axes;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    const std::size_t a = line.find(','), b = line.find(',', a + 1);
    if (b == std::string::npos) {
      ADD_FAILURE() << file.string() << ": " << line;
      return {};
    }
    axes[0].push_back(line.substr(0, a));
    axes[1].push_back(line.substr(a + 1, b - a - 1));
    axes[2].push_back(line.substr(b + 1));
  }
  return axes;
}

// Derived records: skipped, saying so, without the real recordings; each
// test's files go to `dir`.
class RealGyroDerived : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kRealData / "adis_16405_imu1_gyro.csv")) {
      GTEST_SKIP() << "the real recordings are not here (" << kRealData.string()
                   << "): they live in ../shared/data/real beside the checkout";
    }
  }
  test::TempDir dir;
};

// `foglab analyze --json` of the CSV file at `path` with `options`.
json analyse_file(const fs::path& path, const std::string& options) {
  const test::CliRun run =
      test::run_foglab("analyze " + test::quote(path) + " " + options + " --units deg/s --json -");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return run.exit_code == 0 ? json::parse(run.out) : json();
}

// `foglab analyze --json` of `rows` (deg/s) at `rate_hz`, written to `dir`
// as `name`.csv.
json analyse_rows(const fs::path& dir, const std::string& name,
                  const std::vector<std::string>& rows, double rate_hz) {
  const fs::path path = dir / (name + ".csv");
  {
    std::ofstream out(path);
    out << "rate_dps\n";
    for (const std::string& r : rows) out << r << '\n';
  }
  return analyse_file(path, "--fs " + fmt::format("{:g}", rate_hz));
}

// Records derived from the real ones, which the short-tau models were not
// built on (bench/real_variants.py has all 39; docs/validation.md their
// table): each half of the x and y channels (1.4 h, the flicker floor on half
// the data) and their samples averaged in pairs (50 Hz: a filter no channel
// has, on a half-step output grid). Issue 16's done-when on each: N within
// 5 % of the -1/2 region's white level, B resolved, the curve inside the
// intervals at all but at most 2 taus, the bandwidth resolved and not at
// the search bound, no Gauss-Markov Tc below the taus, the class consumer.
// The z axes and every fourth sample, where they still fail, are left to
// the study (and the next test).
TEST_F(RealGyroDerived, HalvesAndAveragedPairsOfTheXAndYAxesMeetTheDoneWhen) {
  for (int imu = 1; imu <= 3; ++imu) {
    const auto axes = read_axes(imu);
    for (const auto& [axis, values] : {std::pair{"x", &axes[0]}, std::pair{"y", &axes[1]}}) {
      const std::size_t n = values->size(), half = n / 2;
      struct Derived {
        std::string name;
        double rate_hz;
        std::vector<std::string> rows;
      };
      std::vector<Derived> derived{{"half1", 100.0, {}}, {"half2", 100.0, {}}, {"avg2", 50.0, {}}};
      for (std::size_t i = 0; i < n; ++i) derived[i < half ? 0 : 1].rows.push_back((*values)[i]);
      for (std::size_t i = 0; i + 1 < n; i += 2) {
        derived[2].rows.push_back(
            fmt::format("{:.9g}", (std::stod((*values)[i]) + std::stod((*values)[i + 1])) / 2.0));
      }
      for (const Derived& d : derived) {
        const std::string name = "imu" + std::to_string(imu) + "_" + axis + "_" + d.name;
        SCOPED_TRACE(name);
        const json j = analyse_rows(dir.path(), name, d.rows, d.rate_hz);
        ASSERT_FALSE(j.is_null());
        const double n_fit = j["noise_model"]["N"]["value"].get<double>();
        EXPECT_NEAR(n_fit / white_level(j["allan"]), 1.0, 0.05);
        EXPECT_EQ(j["noise_model"]["B"]["status"], "resolved") << j["fit"]["terms"];
        const json& allan = j["allan"];
        EXPECT_LE(taus_outside(allan), 2);
        EXPECT_TRUE(j["sensor_bandwidth"]["resolved"].get<bool>());
        EXPECT_FALSE(j["sensor_bandwidth"]["at_search_bound"].get<bool>());
        if (j["noise_model"]["gm_tc"]["status"] == "resolved") {
          EXPECT_GE(j["noise_model"]["gm_tc"]["value"].get<double>(),
                    allan["tau_s"][0].get<double>());
        }
        EXPECT_EQ(j["accuracy_class"], "consumer");
        EXPECT_EQ(j["fit"]["status"], "converged");
      }
    }
  }
}

// Every fourth sample of the z axes (25 Hz, no anti-alias filter): the
// 20 Hz resonance aliases to a hump at 5 Hz, 3-4 Hz wide, that lifts the
// line finder's narrow floor; the broad pass finds it on all three
// (spectral_lines.h), and it is reported as a line there. Before, none was
// found and an angle quantisation Q stood in for it, with B an upper bound
// on imu1. N within 5 % of the white level, B resolved, no bandwidth at a
// search bound (with the hump found, two of them ask for a Butterworth at
// 0.45 fs, the highest cut-off searched, which is a bound and not
// resolved), no Gauss-Markov Tc below the taus, the class consumer. The curve still
// leaves the intervals at 2-4 of the first taus (docs/validation.md), which
// is not asserted.
TEST_F(RealGyroDerived, EveryFourthSampleOfTheZAxesShowsTheAliasedResonance) {
  for (int imu = 1; imu <= 3; ++imu) {
    const auto axes = read_axes(imu);
    std::vector<std::string> rows;
    for (std::size_t i = 0; i < axes[2].size(); i += 4) rows.push_back(axes[2][i]);
    const std::string name = "imu" + std::to_string(imu) + "_z_pick4";
    SCOPED_TRACE(name);
    const json j = analyse_rows(dir.path(), name, rows, 25.0);
    ASSERT_FALSE(j.is_null());
    ASSERT_EQ(j["spectral_lines"].size(), 1u);
    const json& line = j["spectral_lines"][0];
    EXPECT_NEAR(line["frequency_hz"].get<double>(), 5.0, 0.5);
    EXPECT_GT(line["width_hz"].get<double>(), 2.0);
    const double n_fit = j["noise_model"]["N"]["value"].get<double>();
    EXPECT_NEAR(n_fit / white_level(j["allan"]), 1.0, 0.05);
    EXPECT_EQ(j["noise_model"]["B"]["status"], "resolved") << j["fit"]["terms"];
    if (j["sensor_bandwidth"]["resolved"].get<bool>()) {  // not at the highest cut-off
      EXPECT_LT(j["sensor_bandwidth"]["cutoff_hz"].get<double>(), 0.45 * 25.0 * 0.99);
    }
    if (j["noise_model"]["gm_tc"]["status"] == "resolved") {
      EXPECT_GE(j["noise_model"]["gm_tc"]["value"].get<double>(),
                j["allan"]["tau_s"][0].get<double>());
    }
    EXPECT_EQ(j["accuracy_class"], "consumer");
    EXPECT_EQ(j["fit"]["status"], "converged");
  }
}

// Known effects put into real noise (bench/real_injected.py has every
// channel and each effect alone; docs/validation.md the table). The effects
// study puts them on foglab's own generator, whose noise is the fit's
// model; here the noise is the sensor's: filtered, on its 0.05 deg/s grid,
// and on imu2 z with the resonance that moves. Sized by the channel's
// sample spread sd as in the study, each sum put back on the sensor's grid:
// 3 spikes of 20 sd; a step of +0.5 sd at 2778 s; a power glitch that loses
// 50 samples at 4167 s and comes back 0.4 sd lower; gaps of 41.7 s at 833 s
// and 1250 s at 8333 s (a time column, no --fs); a sine of 3 sd at 7.3 Hz.
// Each is found where it was put, and the record's own N and B intervals
// hold the clean record's estimates. A coarser output word (5 of the
// sensor's steps) is found, with N as it was.
TEST_F(RealGyroDerived, SpikesStepsGapsAndALinePutIntoRealNoiseAreFound) {
  constexpr double kFs = 100.0, kLsb = 0.05, kLineHz = 7.3;
  const std::array<std::pair<std::size_t, double>, 3> spikes{
      {{123457, 20.0}, {456791, -20.0}, {789013, 20.0}}};  // sample, size in sd
  const std::array<std::pair<double, double>, 3> gaps{
      {{833.0, 41.7}, {4167.0, 0.5}, {8333.0, 1250.0}}};  // start, length [s]
  auto on_grid = [](double v, double lsb) { return std::round(v / lsb) * lsb; };
  for (const auto& [imu, axis] : {std::pair{1, 0}, std::pair{2, 2}}) {
    const std::string name = fmt::format("imu{}_{}", imu, "xyz"[axis]);
    SCOPED_TRACE(name);
    const auto text = read_axes(imu)[static_cast<std::size_t>(axis)];
    std::vector<double> x;
    for (const std::string& v : text) x.push_back(std::stod(v));
    double mean = 0.0, sq = 0.0;
    for (double v : x) mean += v / static_cast<double>(x.size());
    for (double v : x) sq += (v - mean) * (v - mean);
    const double sd = std::sqrt(sq / static_cast<double>(x.size() - 1));
    const json clean = analyse_rows(dir.path(), name + "_clean", text, kFs);
    ASSERT_FALSE(clean.is_null());

    std::vector<double> y = x;
    const double up = on_grid(0.5 * sd, kLsb), down = on_grid(-0.4 * sd, kLsb);
    for (std::size_t i = 0; i < y.size(); ++i) {
      const double t = static_cast<double>(i) / kFs;
      y[i] += (t >= 2778.0 ? up : 0.0) + (t >= 4167.0 ? down : 0.0) +
              on_grid(3.0 * sd * std::sin(2.0 * M_PI * kLineHz * t + 0.3), kLsb);
    }
    for (const auto& [i, size] : spikes) y[i] += on_grid(size * sd, kLsb);
    const fs::path path = dir.path() / (name + "_effects.csv");
    {
      std::ofstream out(path);
      out << "time_s,rate_dps\n";
      for (std::size_t i = 0; i < y.size(); ++i) {
        const double t = static_cast<double>(i) / kFs;
        if (std::ranges::any_of(gaps, [&](const auto& g) {
              return t >= g.first - 1e-9 && t < g.first + g.second - 1e-9;
            }))
          continue;
        out << fmt::format("{:.2f},{:.9g}\n", t, y[i]);
      }
    }
    const json j = analyse_file(path, "");
    ASSERT_FALSE(j.is_null());

    EXPECT_EQ(j["input"]["gaps"]["count"], 3);
    const auto spike_times = j["spikes"]["times_s"].get<std::vector<double>>();
    ASSERT_EQ(spike_times.size(), spikes.size());
    for (std::size_t k = 0; k < spikes.size(); ++k) {
      EXPECT_NEAR(spike_times[k], static_cast<double>(spikes[k].first) / kFs, 0.015);
    }
    // The step inside a stretch; the sensor's own (imu1 y has one) would
    // be found in the clean record too, and these two have none.
    ASSERT_EQ(clean["steps"]["count"], 0);
    ASSERT_EQ(j["steps"]["count"], 1);
    EXPECT_NEAR(j["steps"]["times_s"][0].get<double>(), 2778.0, 5.0);
    EXPECT_NEAR(j["steps"]["sizes_deg_h"][0].get<double>() / (up * 3600.0), 1.0, 0.25);
    // The glitch: the bias's jump across the 50-sample gap, and no other.
    const json& across = j["steps"]["across_gaps"];
    ASSERT_EQ(across.size(), 3u);
    for (std::size_t g = 0; g < 3; ++g) EXPECT_EQ(across[g]["significant"], g == 1) << g;
    EXPECT_NEAR(across[1]["size_deg_h"].get<double>() / (down * 3600.0), 1.0, 0.25);
    // The line, beside the lines the clean record has (imu2 z's resonance).
    std::vector<double> new_lines;
    for (const json& l : j["spectral_lines"]) {
      const double f = l["frequency_hz"].get<double>();
      if (std::ranges::none_of(clean["spectral_lines"], [&](const json& c) {
            return std::fabs(c["frequency_hz"].get<double>() - f) < 0.5;
          }))
        new_lines.push_back(f);
    }
    ASSERT_EQ(new_lines.size(), 1u);
    EXPECT_NEAR(new_lines[0], kLineHz, 0.05);
    for (const char* p : {"N", "B"}) {
      SCOPED_TRACE(p);
      const auto interval = j["noise_model"][p]["ci95"].get<std::vector<double>>();
      const double was = clean["noise_model"][p]["value"].get<double>();
      EXPECT_LE(interval[0], was);
      EXPECT_GE(interval[1], was);
    }
    EXPECT_EQ(j["accuracy_class"], clean["accuracy_class"]);

    if (axis != 0) continue;
    std::vector<std::string> coarse;
    for (double v : x) coarse.push_back(fmt::format("{:.9g}", on_grid(v, 5 * kLsb)));
    const json q = analyse_rows(dir.path(), name + "_coarse", coarse, kFs);
    ASSERT_FALSE(q.is_null());
    EXPECT_TRUE(q["output_quantisation"]["detected"].get<bool>());
    EXPECT_NEAR(q["output_quantisation"]["lsb_deg_h"].get<double>(), 5 * kLsb * 3600.0, 1e-6);
    EXPECT_NEAR(q["noise_model"]["N"]["value"].get<double>() /
                    clean["noise_model"]["N"]["value"].get<double>(),
                1.0, 0.005);
  }
}

}  // namespace
}  // namespace foglab
