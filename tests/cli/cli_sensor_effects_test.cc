// Real-sensor effects end to end: `foglab generate` puts them into a
// recording with their truth (--truth: sensor_output), `foglab analyze`
// must find each and keep it out of the noise terms.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using test::read_json;

struct Generated {
  json truth, analysis;
};

Generated generate_and_analyze(const fs::path& dir, const std::string& model, int seed) {
  const fs::path mat = dir / ("rec" + std::to_string(seed) + ".mat");
  const fs::path truth = dir / ("truth" + std::to_string(seed) + ".json");
  const test::CliRun g =
      test::run_foglab("generate " + model + " --seed " + std::to_string(seed) + " --out " +
                       test::quote(mat) + " --truth " + test::quote(truth));
  EXPECT_EQ(g.exit_code, 0) << g.err;
  const test::CliRun a = test::run_foglab("analyze " + test::quote(mat) + " --json -");
  EXPECT_EQ(a.exit_code, 0) << a.err;
  if (g.exit_code != 0 || a.exit_code != 0) return {};
  return {read_json(truth), json::parse(a.out)};
}

TEST(SensorEffects, FilteredQuantisedOutputWithALineIsTakenApart) {
  // An ADIS16405-like axis: white noise through a 5.4 ms low-pass, a 20 Hz
  // disturbance, 0.05 deg/s output steps, flicker 30 deg/h.
  const test::TempDir dir;
  const std::string model =
      "--N 150 --B 30 --fs 100 --hours 2.78 --filter-tc 0.0054 --sine 20:1200 --lsb 180";
  for (int seed = 1; seed <= 2; ++seed) {
    const Generated r = generate_and_analyze(dir.path(), model, seed);
    ASSERT_TRUE(r.analysis.is_object());
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const json& out = r.truth["sensor_output"];
    const json& nm = r.analysis["noise_model"];
    EXPECT_NEAR(nm["N"]["value"].get<double>() / 150.0, 1.0, 0.03);
    EXPECT_EQ(nm["B"]["status"], "resolved");
    const json& bw = r.analysis["sensor_bandwidth"];
    ASSERT_TRUE(bw["resolved"].get<bool>());
    EXPECT_NEAR(bw["lag1_correlation"].get<double>() / out["filter_lag1"].get<double>(), 1.0, 0.1);
    const json& lines = r.analysis["spectral_lines"];
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NEAR(lines[0]["frequency_hz"].get<double>(), 20.0, 0.05);
    EXPECT_NEAR(lines[0]["rms_deg_h"].get<double>() /
                    out["sinusoids"][0]["rms_in_output_deg_h"].get<double>(),
                1.0, 0.05);
    const json& q = r.analysis["output_quantisation"];
    ASSERT_TRUE(q["detected"].get<bool>());
    EXPECT_NEAR(q["lsb_deg_h"].get<double>(), out["lsb_deg_h"].get<double>(), 1e-6);
    if (nm["gm_tc"]["status"] == "resolved") {
      EXPECT_GT(nm["gm_tc"]["value"].get<double>(), 1.0);
    }
  }
}

TEST(SensorEffects, SpikesAreFoundAtTheirTimesAndTakenOut) {
  // 3 spikes an hour of 20,000 deg/h (about 16 sample sd) on a filtered,
  // quantised output: each found at its sample, none invented, N unharmed.
  const test::TempDir dir;
  for (int seed = 7; seed <= 8; ++seed) {
    const Generated r = generate_and_analyze(
        dir.path(),
        "--N 150 --B 30 --fs 100 --hours 2.78 --filter-tc 0.0054 --lsb 180 --spikes 3:20000", seed);
    ASSERT_TRUE(r.analysis.is_object());
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const auto truth = r.truth["sensor_output"]["spike_times_s"].get<std::vector<double>>();
    const auto found = r.analysis["spikes"]["times_s"].get<std::vector<double>>();
    ASSERT_GT(truth.size(), 2u);
    ASSERT_EQ(found.size(), truth.size());
    for (std::size_t k = 0; k < truth.size(); ++k) EXPECT_NEAR(found[k], truth[k], 1e-6);
    EXPECT_TRUE(r.analysis["spikes"]["removed"].get<bool>());
    EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 150.0, 1.0, 0.03);
  }
}

TEST(SensorEffects, BiasStepsAreFoundAndLevelled) {
  // Two steps of 600 and -400 deg/h (about 20 and 14 times the Allan
  // deviation's floor) on the ADIS16405-like axis.
  const test::TempDir dir;
  const Generated r = generate_and_analyze(
      dir.path(),
      "--N 150 --B 30 --fs 100 --hours 2.78 --filter-tc 0.0054 --lsb 180 --step 3000:600 "
      "--step 7000:-400",
      9);
  ASSERT_TRUE(r.analysis.is_object());
  const json& s = r.analysis["steps"];
  ASSERT_EQ(s["count"], 2);
  EXPECT_NEAR(s["times_s"][0].get<double>(), 3000.0, 2.0);
  EXPECT_NEAR(s["times_s"][1].get<double>(), 7000.0, 2.0);
  EXPECT_NEAR(s["sizes_deg_h"][0].get<double>() / 600.0, 1.0, 0.25);
  EXPECT_NEAR(s["sizes_deg_h"][1].get<double>() / -400.0, 1.0, 0.25);
  EXPECT_TRUE(s["removed"].get<bool>());
  // two glitches, not a process: levelling them takes the wander down
  EXPECT_FALSE(s["left_as_noise"].get<bool>());
  EXPECT_TRUE(s["left_as_noise_because"].is_null());
  EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 150.0, 1.0, 0.03);
}

TEST(SensorEffects, StepsOnATemperatureRampAcrossAGapAreFoundAndTheLawKept) {
  // The ADIS16405-like axis warming by 10 degC with a curved law (c1 900
  // deg/h/degC, c2 15), two steps, and a 10 min gap during the ramp (the
  // rate moves by 750 deg/h while nothing is recorded). The steps were
  // sought on the raw rate: the law's curvature and the jump across the
  // gap passed for up to 20 steps, the levelling took part of the law
  // with it, and c1 came out 1.5-3 standard errors low.
  const test::TempDir dir;
  for (int seed = 1; seed <= 2; ++seed) {
    const Generated r = generate_and_analyze(
        dir.path(),
        "--N 150 --B 30 --fs 100 --hours 2 --temperature ramp:10@20 --temp-coef 900,15 "
        "--step 2000:750 --step 5000:-600 --drop 3000:600",
        seed);
    ASSERT_TRUE(r.analysis.is_object());
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const json& s = r.analysis["steps"];
    ASSERT_EQ(s["count"], 2);
    EXPECT_NEAR(s["times_s"][0].get<double>(), 2000.0, 2.0);
    EXPECT_NEAR(s["times_s"][1].get<double>(), 5000.0, 2.0);
    EXPECT_NEAR(s["sizes_deg_h"][0].get<double>() / 750.0, 1.0, 0.25);
    EXPECT_NEAR(s["sizes_deg_h"][1].get<double>() / -600.0, 1.0, 0.25);
    EXPECT_EQ(r.analysis["input"]["gaps"]["count"], 1);
    // the law's move across the gap (750 deg/h) is no bias jump
    ASSERT_EQ(s["across_gaps"].size(), 1u);
    EXPECT_FALSE(s["across_gaps"][0]["significant"].get<bool>());
    EXPECT_LT(std::fabs(s["across_gaps"][0]["size_deg_h"].get<double>()), 250.0);
    const json& fit = r.analysis["systematic"];
    const double c1 = fit["coefficients"][1].get<double>();
    const double se = fit["standard_errors"][1].get<double>();
    EXPECT_LT(std::fabs(c1 - 900.0), 3.0 * se) << c1 << " +- " << se;
    EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 150.0, 1.0, 0.03);
  }
}

TEST(SensorEffects, ABiasJumpAcrossAGapIsMeasuredAndNotLevelled) {
  // Tactical-grade noise with three dropouts; the bias jumps by -3 deg/h
  // (one sample spread) during the 0.5 s one. The jump is measured across
  // it (10 seeds: -2.81 to -3.27, 18-21 robust spreads), and no jump is
  // found across the 30 s and 15 min ones, across which the random walk
  // alone moves the bias by 0.1 and 0.6 deg/h (10 seeds without the jump:
  // none beyond 4.1 spreads there).
  const test::TempDir dir;
  const Generated r = generate_and_analyze(
      dir.path(),
      "--N 0.3 --B 0.1 --K 0.02 --fs 100 --hours 2 --drop 600:30 --drop 3000:0.5 "
      "--drop 5000:900 --step 3000.2:-3",
      1);
  ASSERT_TRUE(r.analysis.is_object());
  const json& s = r.analysis["steps"];
  EXPECT_EQ(s["count"], 0);
  const json& jumps = s["across_gaps"];
  ASSERT_EQ(jumps.size(), 3u);
  const json& gaps = r.analysis["input"]["gaps"]["list"];
  for (std::size_t g = 0; g < 3; ++g) {
    EXPECT_EQ(jumps[g]["before_sample"], gaps[g]["before_sample"]);
    EXPECT_EQ(jumps[g]["significant"].get<bool>(), g == 1) << g;
  }
  EXPECT_NEAR(jumps[1]["size_deg_h"].get<double>(), -3.0, 0.5);
  EXPECT_NEAR(jumps[1]["time_s"].get<double>(), 3000.5, 0.011);
  EXPECT_NE(r.analysis["notes"].dump().find("1 bias jump(s) across gaps"), std::string::npos)
      << r.analysis["notes"];
  // The stretches are analysed apart: N as without the jump.
  EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 0.3, 1.0, 0.03);
}

TEST(SensorEffects, AStepSmallerThanAFineOutputWordsStepIsFound) {
  // An output word of half the sample spread is noise-like: the mean moves
  // by any amount, so a step of two thirds of the word's step is a step
  // (the word's step had been a floor for every step).
  const test::TempDir dir;
  const Generated r = generate_and_analyze(
      dir.path(), "--N 0.3 --B 0.1 --K 0.02 --fs 100 --hours 2 --lsb 1.5 --step 3600:1.0", 1);
  ASSERT_TRUE(r.analysis.is_object());
  ASSERT_TRUE(r.analysis["output_quantisation"]["noise_like"].get<bool>());
  const json& s = r.analysis["steps"];
  ASSERT_EQ(s["count"], 1);
  EXPECT_NEAR(s["times_s"][0].get<double>(), 3600.0, 5.0);
  EXPECT_NEAR(s["sizes_deg_h"][0].get<double>(), 1.0, 0.3);
}

TEST(SensorEffects, AQuantisedTemperatureChannelLeavesTheNoiseModelAsItWas) {
  // The tactical grade warming by 10 degC in 2 h (c1 3 deg/h/degC), its
  // temperature read in steps of 0.25 degC (a staircase of 3 min steps;
  // the rate follows the temperature itself, generate --temp-lsb).
  // Against the staircase the law had left c1 times a +-0.125 degC
  // sawtooth in the residual: B 42 % high, with a rate ramp and Q that are
  // not there. Against the temperature between the steps the analysis is
  // the unrounded channel's.
  const test::TempDir dir;
  const std::string model =
      "--N 0.3 --B 0.1 --K 0.02 --fs 100 --hours 2 --temperature ramp:10@20 --temp-coef 3";
  const Generated plain = generate_and_analyze(dir.path(), model, 1);
  const Generated stepped = generate_and_analyze(dir.path(), model + " --temp-lsb 0.25", 1);
  ASSERT_TRUE(plain.analysis.is_object() && stepped.analysis.is_object());
  EXPECT_EQ(stepped.truth["temperature"]["lsb_c"], 0.25);
  EXPECT_FALSE(plain.analysis["temperature_quantisation"]["detected"].get<bool>());
  const json& q = stepped.analysis["temperature_quantisation"];
  ASSERT_TRUE(q["detected"].get<bool>());
  EXPECT_NEAR(q["lsb_c"].get<double>(), 0.25, 1e-9);
  EXPECT_EQ(q["distinct_values"], 41);
  EXPECT_EQ(stepped.analysis["fit"]["terms"], plain.analysis["fit"]["terms"]);
  for (const char* term : {"N", "B", "K"}) {
    EXPECT_NEAR(stepped.analysis["noise_model"][term]["value"].get<double>() /
                    plain.analysis["noise_model"][term]["value"].get<double>(),
                1.0, 0.01)
        << term;
  }
  EXPECT_NEAR(stepped.analysis["systematic"]["coefficients"][1].get<double>(),
              plain.analysis["systematic"]["coefficients"][1].get<double>(), 0.01);
  EXPECT_EQ(stepped.analysis["random_bias_process"], plain.analysis["random_bias_process"]);
  EXPECT_EQ(stepped.analysis["steps"]["count"], 0);
}

TEST(SensorEffects, MovingAverageIsFoundWithItsLength) {
  const test::TempDir dir;
  const Generated r =
      generate_and_analyze(dir.path(), "--N 150 --B 30 --fs 100 --hours 2 --moving-average 4", 3);
  ASSERT_TRUE(r.analysis.is_object());
  const json& bw = r.analysis["sensor_bandwidth"];
  ASSERT_TRUE(bw["resolved"].get<bool>());
  EXPECT_EQ(bw["kind"], "moving_average");
  EXPECT_EQ(bw["moving_average_samples"], 4);
  EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 150.0, 1.0, 0.03);
}

TEST(SensorEffects, ButterworthIsFoundWithItsCutoff) {
  // A second-order anti-alias filter at a quarter of the sample rate: the
  // truth names it, analyze finds the kind and f_c, and the report says so.
  const test::TempDir dir;
  const Generated r =
      generate_and_analyze(dir.path(), "--N 150 --B 30 --fs 100 --hours 2 --butterworth 25", 4);
  ASSERT_TRUE(r.analysis.is_object());
  EXPECT_EQ(r.truth["sensor_output"]["butterworth_cutoff_hz"], 25.0);
  const json& bw = r.analysis["sensor_bandwidth"];
  ASSERT_TRUE(bw["resolved"].get<bool>());
  EXPECT_EQ(bw["kind"], "butterworth_second_order");
  EXPECT_TRUE(bw["time_constant_s"].is_null());
  EXPECT_NEAR(bw["cutoff_hz"].get<double>() / 25.0, 1.0, 0.05);
  EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 150.0, 1.0, 0.01);
}

TEST(SensorEffects, FiltersNoKindFollowsLeaveTheFirstTausOutAndSaySo) {
  // A first-order low-pass behind a 3-sample moving average: the JSON says
  // how many taus were left out and why (in the fit and in the notes); a
  // single modelled filter leaves none out.
  const test::TempDir dir;
  const Generated r = generate_and_analyze(
      dir.path(), "--N 0.3 --B 0.1 --fs 100 --hours 2 --filter-tc 0.01 --moving-average 3", 1);
  ASSERT_TRUE(r.analysis.is_object());
  const json& fit = r.analysis["fit"];
  EXPECT_GE(fit["first_taus_left_out"].get<int>(), 1);
  ASSERT_TRUE(fit["first_taus_left_out_why"].is_string());
  const std::string why = fit["first_taus_left_out_why"];
  bool noted = false;
  for (const json& n : r.analysis["notes"])
    noted = noted || n.get<std::string>().find(why) != std::string::npos;
  EXPECT_TRUE(noted) << why;
  EXPECT_NEAR(r.analysis["noise_model"]["N"]["value"].get<double>() / 0.3, 1.0, 0.01);
  // The rest fitted with the filter known beyond its memory: its c (the
  // cascade's is 2.006 samples) and no lag-1 correlation (its shape inside
  // the memory is not known).
  const json& bw = r.analysis["sensor_bandwidth"];
  ASSERT_TRUE(bw["resolved"].get<bool>());
  EXPECT_EQ(bw["kind"], "beyond_memory");
  EXPECT_NEAR(bw["memory_constant_samples"].get<double>() / 2.006, 1.0, 0.08);
  EXPECT_TRUE(bw["lag1_correlation"].is_null());
  EXPECT_TRUE(bw["time_constant_s"].is_null());

  const Generated single =
      generate_and_analyze(dir.path(), "--N 0.3 --B 0.1 --fs 100 --hours 2 --filter-tc 0.01", 2);
  EXPECT_EQ(single.analysis["fit"]["first_taus_left_out"], 0);
  EXPECT_TRUE(single.analysis["fit"]["first_taus_left_out_why"].is_null());
  // The intervals also span the fit that assumes no kind: the low-pass of
  // one sample has c = 3 rho / (1 - rho^2) = 1.28 (rho = 1/e), so the taus
  // of 1 and 2 samples are inside 3 c (two more if that c still wants the
  // first kept one); with the first taus already left out, none.
  const json& shape_free = single.analysis["fit"]["shape_free_taus_left_out"];
  ASSERT_TRUE(shape_free.is_number_integer());
  EXPECT_GE(shape_free.get<int>(), 2);
  EXPECT_LE(shape_free.get<int>(), 4);
  EXPECT_TRUE(fit["shape_free_taus_left_out"].is_null());
  EXPECT_TRUE(fit["shape_free_N"].is_null());
  // That fit's N, beside the kind's: where the kind is right, the same
  // white level (its interval is the wider: about +-0.8 % at 100 Hz, 2 h).
  const json& shape_free_n = single.analysis["fit"]["shape_free_N"];
  ASSERT_TRUE(shape_free_n.is_number());
  EXPECT_NEAR(shape_free_n.get<double>() / 0.3, 1.0, 0.03);

  // A low-pass of 0.4 sample (c = 3 rho / (1 - rho^2) = 0.25 with
  // rho = e^-2.5, under a third of a sample): no tau lies inside its
  // memory, so that fit keeps every tau, and the summary says so (it had
  // read "the first 0 tau(s), inside its memory, left out").
  const fs::path mat = dir.path() / "short_memory.mat", out = dir.path() / "short_memory.json";
  ASSERT_EQ(test::run_foglab("generate --N 0.3 --B 0.1 --fs 100 --hours 0.5 --filter-tc 0.004 "
                             "--out " +
                             test::quote(mat))
                .exit_code,
            0);
  const test::CliRun a =
      test::run_foglab("analyze " + test::quote(mat) + " --json " + test::quote(out));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const json short_memory = read_json(out);
  ASSERT_EQ(short_memory["sensor_bandwidth"]["kind"], "first_order");
  EXPECT_EQ(short_memory["fit"]["shape_free_taus_left_out"], 0);
  EXPECT_NE(a.out.find("no tau lies inside its memory, and every tau is taken as"),
            std::string::npos);
  EXPECT_EQ(a.out.find("the first 0 tau(s)"), std::string::npos);
  EXPECT_NE(a.out.find("taken as N^2/tau (1 - c tau0/tau), which gives N = "), std::string::npos);
  EXPECT_EQ(a.out.find("decides N"), std::string::npos);  // the right kind: the same N
}

TEST(SensorEffects, GapsAreFoundAndTheStretchesAnalysed) {
  // Three dropouts (30 s, half a second and 15 min) in a CSV and a MAT file:
  // the time column shows them, analyze and allan use the stretches, and N,
  // B and K stay within what the lost data allow.
  const test::TempDir dir;
  const std::string model =
      "--N 0.2 --B 0.02 --K 0.002 --fs 100 --hours 2 --drop 600:30 --drop 3000:0.5 "
      "--drop 5000:900";
  for (const char* ext : {".csv", ".mat"}) {
    SCOPED_TRACE(ext);
    const fs::path out = dir.path() / (std::string("gaps") + ext);
    const fs::path truth_path = dir.path() / "gaps.json";
    const test::CliRun g =
        test::run_foglab("generate " + model + " --seed 4 --out " + test::quote(out) + " --truth " +
                         test::quote(truth_path));
    ASSERT_EQ(g.exit_code, 0) << g.err;
    const json truth = read_json(truth_path)["sensor_output"]["dropouts"]["gaps"];
    ASSERT_EQ(truth.size(), 3u);
    const test::CliRun a = test::run_foglab("analyze " + test::quote(out) + " --json -");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_NE(a.err.find("3 gap(s)"), std::string::npos) << a.err;
    const json r = json::parse(a.out);
    const json& gaps = r["input"]["gaps"];
    ASSERT_EQ(gaps["count"], 3);
    EXPECT_EQ(gaps["missing_samples"], 3000 + 50 + 90000);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(gaps["list"][k]["before_sample"], truth[k]["before_sample"]);
      EXPECT_EQ(gaps["list"][k]["missing_samples"], truth[k]["missing_samples"]);
    }
    EXPECT_NEAR(gaps["list"][2]["start_s"].get<double>(), 4999.99, 1e-6);
    EXPECT_NEAR(gaps["list"][2]["end_s"].get<double>(), 5900.0, 1e-6);
    const json& nm = r["noise_model"];
    EXPECT_NEAR(nm["N"]["value"].get<double>() / 0.2, 1.0, 0.03);
    EXPECT_LE(nm["B"]["ci95"][0].get<double>(), 0.02);
    EXPECT_GE(nm["B"]["ci95"][1].get<double>(), 0.02);
    EXPECT_LE(nm["K"]["ci95"][0].get<double>(), 0.002);
    EXPECT_GE(nm["K"]["ci95"][1].get<double>(), 0.002);
    EXPECT_NEAR(r["input"]["samples"].get<double>(), 720000 - 93050, 0.5);
    // the Allan deviation of the stretches: as many terms at tau0 as the
    // stretches hold (the record less one per stretch)
    const test::CliRun allan = test::run_foglab("allan " + test::quote(out) + " --json -");
    ASSERT_EQ(allan.exit_code, 0) << allan.err;
    EXPECT_EQ(json::parse(allan.out)["n"][0], 720000 - 93050 - 4);
  }
  // a raw file has no time column for the gaps
  const test::CliRun raw = test::run_foglab("generate " + model + " --drop-mark time --out " +
                                            test::quote(dir.path() / "x.f64"));
  EXPECT_EQ(raw.exit_code, 2);
  EXPECT_NE(raw.err.find("--drop-mark"), std::string::npos) << raw.err;
}

TEST(SensorEffects, ALoggersJitteredTimesGiveTheSameAnalysisAsExactOnes) {
  // The same record written with exact times and with a logger's (+-35 % of a 10 ms step),
  // with a 30 s and a 50 ms dropout: the jittered times are put back on the sensor's grid,
  // so the gaps, the samples and every estimate are those of the exact times.
  const test::TempDir dir;
  const std::string model =
      "--N 0.2 --B 0.02 --K 0.002 --fs 100 --hours 0.5 --drop 600:30 --drop 1000:0.05 "
      "--seed 4";
  json runs[2];
  for (int jittered = 0; jittered < 2; ++jittered) {
    const fs::path out = dir.path() / (jittered ? "jitter.csv" : "exact.csv");
    const fs::path truth = dir.path() / (jittered ? "jitter.json" : "exact.json");
    const test::CliRun g =
        test::run_foglab("generate " + model + (jittered ? " --stamp-jitter 0.0035" : "") +
                         " --out " + test::quote(out) + " --truth " + test::quote(truth));
    ASSERT_EQ(g.exit_code, 0) << g.err;
    const test::CliRun a = test::run_foglab("analyze " + test::quote(out) + " --json -");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    runs[jittered] = json::parse(a.out);
    const json t = read_json(truth)["sensor_output"];
    const json& gaps = runs[jittered]["input"]["gaps"];
    ASSERT_EQ(gaps["count"], 2);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(gaps["list"][k]["before_sample"], t["dropouts"]["gaps"][k]["before_sample"]);
      EXPECT_EQ(gaps["list"][k]["missing_samples"], t["dropouts"]["gaps"][k]["missing_samples"]);
    }
    const json& jitter = runs[jittered]["input"]["time_jitter"];
    if (jittered) {
      ASSERT_TRUE(jitter.is_object()) << runs[jittered]["input"].dump();
      EXPECT_NEAR(jitter["rms_s"].get<double>() / t["time_jitter_rms_s"].get<double>(), 1.0, 0.02);
      EXPECT_EQ(jitter["rows_dropped"], 0);
      EXPECT_NE(a.err.find("uniform sampling grid with jitter"), std::string::npos) << a.err;
    } else {
      EXPECT_TRUE(jitter.is_null());
    }
  }
  EXPECT_EQ(runs[1]["input"]["samples"], runs[0]["input"]["samples"]);
  EXPECT_NEAR(runs[1]["input"]["sample_rate_hz"].get<double>(), 100.0, 1e-5);
  for (const char* term : {"N", "B", "K"}) {
    SCOPED_TRACE(term);
    const json& exact = runs[0]["noise_model"][term];
    const json& jittered = runs[1]["noise_model"][term];
    EXPECT_EQ(jittered["status"], exact["status"]);
    if (exact["value"].is_number()) {
      EXPECT_NEAR(jittered["value"].get<double>() / exact["value"].get<double>(), 1.0, 1e-5);
    }
  }
  // a raw file has no time column to jitter
  const test::CliRun raw = test::run_foglab("generate " + model + " --stamp-jitter 0.003 --out " +
                                            test::quote(dir.path() / "x.f64"));
  EXPECT_EQ(raw.exit_code, 2);
  EXPECT_NE(raw.err.find("--stamp-jitter"), std::string::npos) << raw.err;
  // 0.4 of a step or more is refused, naming the flag
  const test::CliRun wide = test::run_foglab("generate " + model + " --stamp-jitter 0.004 --out " +
                                             test::quote(dir.path() / "x.csv"));
  EXPECT_EQ(wide.exit_code, 2);
  EXPECT_NE(wide.err.find("--stamp-jitter"), std::string::npos) << wide.err;
}

TEST(SensorEffects, ASampleLostHereAndThereLeavesTheLongTausAndTheirModel) {
  // 1 h at 100 Hz losing 200 single samples at random times (a bag's or a
  // serial link's dropouts): no stretch is longer than a few minutes, and
  // the Allan deviation of the stretches alone ended at a few tens of
  // seconds. Its clusters may miss 1 % of their samples: the taus reach
  // the gap-free record's, with the same deviations, N and floor.
  const test::TempDir dir;
  const std::string model = "--N 0.2 --B 0.02 --K 0.002 --fs 100 --hours 1 --seed 7";
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<int> centisecond(100, 359900);
  std::string drops;
  for (int k = 0; k < 200; ++k) drops += fmt::format(" --drop {}:0.01", centisecond(rng) / 100.0);
  const fs::path whole = dir.path() / "whole.csv", lossy = dir.path() / "lossy.csv";
  const fs::path truth_path = dir.path() / "truth.json";
  ASSERT_EQ(test::run_foglab("generate " + model + " --out " + test::quote(whole)).exit_code, 0);
  const test::CliRun g =
      test::run_foglab("generate " + model + drops + " --out " + test::quote(lossy) + " --truth " +
                       test::quote(truth_path));
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const test::CliRun a = test::run_foglab("analyze " + test::quote(whole) + " --json -");
  const test::CliRun b = test::run_foglab("analyze " + test::quote(lossy) + " --json -");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const json r = json::parse(a.out), q = json::parse(b.out);
  const std::size_t lost = read_json(truth_path)["sensor_output"]["dropouts"]["gaps"].size();
  EXPECT_GE(lost, 190u);  // a few drops fall together
  EXPECT_EQ(q["input"]["gaps"]["count"], lost);
  bool noted = false;
  for (const json& n : q["notes"]) {
    noted =
        noted || n.get<std::string>().find("of the Allan deviation's taus") != std::string::npos;
  }
  EXPECT_TRUE(noted) << q["notes"].dump();
  EXPECT_EQ(q["allan"]["tau_s"], r["allan"]["tau_s"]);
  const auto spanning = q["allan"]["gap_spanning_terms"].get<std::vector<std::int64_t>>();
  ASSERT_EQ(spanning.size(), q["allan"]["tau_s"].size());
  EXPECT_GT(spanning.back(), 0);
  for (std::size_t k = 0; k < spanning.size(); ++k) {
    const double m = q["allan"]["m"][k].get<double>();
    EXPECT_EQ(spanning[k] > 0, m >= 100) << m;
    // the same noise with 0.07 % of it missing: within 0.3 of the
    // interval's half-width (allan_gaps_test.cc says why)
    const double dev = r["allan"]["adev_deg_h"][k].get<double>();
    const double half_width = r["allan"]["ci95_high"][k].get<double>() / dev - 1.0;
    EXPECT_NEAR(q["allan"]["adev_deg_h"][k].get<double>() / dev, 1.0, 0.3 * half_width) << m;
  }
  EXPECT_NEAR(q["bias_instability_deg_h"].get<double>() / r["bias_instability_deg_h"].get<double>(),
              1.0, 0.02);
  EXPECT_NEAR(
      q["noise_model"]["N"]["value"].get<double>() / r["noise_model"]["N"]["value"].get<double>(),
      1.0, 0.005);
  // B or K: an hour barely tells them apart (the criterion picks N+K on
  // the whole record by 0.3, N+B on this one by 0.1); where resolved, each
  // interval holds the truth.
  for (const char* p : {"N", "B", "K"}) {
    SCOPED_TRACE(p);
    const double truth = p == std::string("N") ? 0.2 : p == std::string("B") ? 0.02 : 0.002;
    const json& e = q["noise_model"][p];
    if (e["status"] != "resolved") continue;
    EXPECT_LE(e["ci95"][0].get<double>(), truth);
    EXPECT_GE(e["ci95"][1].get<double>(), truth);
  }
  EXPECT_TRUE(q["noise_model"]["B"]["status"] == "resolved" ||
              q["noise_model"]["K"]["status"] == "resolved");
  EXPECT_EQ(q["options"]["max_missing_percent"], 1.0);

  // --max-missing-percent 0: Stable32's rule, the stretches alone; their
  // taus end where the longest stretch does (a few minutes here).
  const test::CliRun s =
      test::run_foglab("analyze " + test::quote(lossy) + " --max-missing-percent 0 --json -");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const json p = json::parse(s.out);
  EXPECT_EQ(p["options"]["max_missing_percent"], 0.0);
  EXPECT_TRUE(p["allan"]["gap_spanning_terms"].empty());
  EXPECT_LT(p["allan"]["tau_s"].size(), q["allan"]["tau_s"].size());
  for (std::size_t k = 0; k < p["allan"]["tau_s"].size(); ++k) {
    if (q["allan"]["gap_spanning_terms"][k].get<std::int64_t>() > 0) continue;
    EXPECT_EQ(p["allan"]["adev_deg_h"][k], q["allan"]["adev_deg_h"][k]) << k;
  }
  // a share beyond 10 % is refused, naming the option, before reading
  const test::CliRun bad =
      test::run_foglab("analyze " + test::quote(lossy) + " --max-missing-percent 25 --json -");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--max-missing-percent"), std::string::npos) << bad.err;
  EXPECT_TRUE(bad.out.empty());
}

TEST(SensorEffects, NanSamplesAreTheSameGapsAsTheTimeColumns) {
  // The same three dropouts written as NaN rows (rate and temperature NaN,
  // the time going on) and, in a raw file without a time column, as NaN
  // samples: analyze leaves the rows out and finds the gaps the time
  // column shows. With the same samples and gaps left, the analysis is
  // the time column's, number for number.
  const test::TempDir dir;
  const std::string model =
      "--N 0.2 --B 0.02 --K 0.002 --fs 100 --hours 2 --drop 600:30 --drop 3000:0.5 "
      "--drop 5000:900 --seed 4";
  auto analyse = [&](const std::string& name, const std::string& generate_extra,
                     const std::string& analyze_extra) {
    const fs::path out = dir.path() / name;
    const fs::path truth = dir.path() / (name + ".truth.json");
    const test::CliRun g = test::run_foglab("generate " + model + generate_extra + " --out " +
                                            test::quote(out) + " --truth " + test::quote(truth));
    EXPECT_EQ(g.exit_code, 0) << g.err;
    // the truth says how the file shows the dropouts, and the gaps analyze must find
    const json dropouts = read_json(truth)["sensor_output"]["dropouts"];
    const test::CliRun a =
        test::run_foglab("analyze " + test::quote(out) + analyze_extra + " --json -");
    EXPECT_EQ(a.exit_code, 0) << a.err;
    json r = a.exit_code == 0 ? json::parse(a.out) : json();
    if (r.is_object()) {
      const json& found = r["input"]["gaps"]["list"];
      EXPECT_EQ(found.size(), dropouts["gaps"].size());
      for (std::size_t i = 0; i < std::min(found.size(), dropouts["gaps"].size()); ++i) {
        EXPECT_EQ(found[i]["before_sample"], dropouts["gaps"][i]["before_sample"]) << i;
        EXPECT_EQ(found[i]["missing_samples"], dropouts["gaps"][i]["missing_samples"]) << i;
      }
    }
    return std::make_tuple(a.err, std::move(r), dropouts["mark"]);
  };
  const auto [time_err, by_time, time_mark] = analyse("time.csv", "", "");
  ASSERT_TRUE(by_time.is_object());
  ASSERT_EQ(by_time["input"]["gaps"]["count"], 3);
  EXPECT_EQ(by_time["input"]["gaps"]["missing_value_rows"], 0);
  EXPECT_EQ(time_mark, "time");
  for (const std::string name : {"nan.csv", "nan.mat", "nan.f64"}) {
    SCOPED_TRACE(name);
    const bool raw = name.ends_with(".f64");
    const auto [err, r, mark] =
        analyse(name, raw ? "" : " --drop-mark nan", raw ? " --fs 100" : "");
    EXPECT_EQ(mark, "nan");
    ASSERT_TRUE(r.is_object());
    EXPECT_NE(err.find("93050 NaN or empty sample(s) in 3 stretch(es)"), std::string::npos) << err;
    const json& gaps = r["input"]["gaps"];
    EXPECT_EQ(gaps["missing_value_rows"], 93050);
    EXPECT_EQ(gaps["list"], by_time["input"]["gaps"]["list"]);
    EXPECT_EQ(r["input"]["samples"], by_time["input"]["samples"]);
    const json& nm = r["noise_model"];
    if (raw) {  // no temperature beside it: the analysis differs; N is still right
      EXPECT_NEAR(nm["N"]["value"].get<double>() / 0.2, 1.0, 0.03);
    } else {
      for (const char* term : {"N", "B", "K"}) {
        EXPECT_DOUBLE_EQ(nm[term]["value"].get<double>(),
                         by_time["noise_model"][term]["value"].get<double>())
            << term;
      }
    }
  }
}

TEST(SensorEffects, BadEffectOptionsAreUsageErrorsNamingTheFlag) {
  const test::TempDir dir;
  const std::string out = " --out " + test::quote(dir.path() / "x.mat");
  for (const auto& [args, flag] :
       std::vector<std::pair<std::string, std::string>>{{"--sine 6:1", "--sine"},
                                                        {"--sine 1:x", "--sine"},
                                                        {"--square 6:1", "--square"},
                                                        {"--square 1", "--square"},
                                                        {"--moving-average 0", "--moving-average"},
                                                        {"--butterworth 5", "--butterworth"},
                                                        {"--butterworth -1", "--butterworth"},
                                                        {"--spikes 3", "--spikes"},
                                                        {"--lsb -1", "--lsb"},
                                                        {"--step 10", "--step"}}) {
    const test::CliRun r = test::run_foglab("generate --N 1 --fs 10 --hours 0.1 " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(flag), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "x.mat")) << args;
  }
}

}  // namespace
}  // namespace foglab
