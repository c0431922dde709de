// `foglab analyze` end to end: recordings made by `foglab generate` with a
// known truth go through the CLI, and the JSON must hold docs/json.md's contract
// (every field, with its JSON type) and find the truth within statistical
// tolerances; temperature pairing, records without temperature and bad
// inputs give the documented notes, messages and exit codes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "foglab/io/writer.h"
#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quote;
using test::run_foglab;
using ::testing::HasSubstr;

// The truth of the ramp recording: N, B, K in the units of docs/conventions.md, a bias
// polynomial 2 (T - T_ref) + 0.01 (T - T_ref)^2 deg/h over a 10 degC ramp.
// The slope is large enough to stand well clear of the random walk's
// confounding (its standard error is about 0.3 deg/h/degC at K = 0.02).
constexpr const char* kModel = "--N 0.5 --B 0.05 --K 0.02 --fs 10 --temp-coef 2,0.01 ";

/// Runs `foglab analyze ARGS --json -` and parses its standard output.
json analyze_json(const std::string& args) {
  return test::run_json("analyze " + args + " --json -");
}

std::string all_notes(const json& j) {
  std::string text;
  for (const auto& n : j["notes"]) text += n.get<std::string>() + "\n";
  if (j["systematic"].contains("note") && j["systematic"]["note"].is_string()) {
    text += j["systematic"]["note"].get<std::string>();
  }
  return text;
}

bool is_number_or_null(const json& v) { return v.is_number() || v.is_null(); }

/// Every element a number (a NaN would have been written as null).
void expect_numbers(const json& array, const std::string& name) {
  ASSERT_TRUE(array.is_array()) << name;
  for (const auto& v : array) EXPECT_TRUE(v.is_number()) << name << ": " << v;
}

/// One recording with a 10 degC ramp and one at constant temperature, made
/// and analysed once for the whole suite (3 h and 2 h at 10 Hz).
class CliAnalyze : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::TempDir>();
    const test::CliRun ramp = run_foglab(
        std::string("generate ") + kModel + "--hours 3 --temperature ramp:10 " + "--seed 7 --out " +
        quote(*dir_ / "ramp.mat") + " --truth " + quote(*dir_ / "truth.json"));
    ASSERT_EQ(ramp.exit_code, 0) << ramp.err;
    const test::CliRun flat =
        run_foglab(std::string("generate ") + kModel +
                   "--hours 2 --temperature const --seed 8 --out " + quote(*dir_ / "const.mat"));
    ASSERT_EQ(flat.exit_code, 0) << flat.err;
    truth_ = json::parse(test::read_file(*dir_ / "truth.json"));
    ramp_auto_ = analyze_json(quote(*dir_ / "ramp.mat"));
    ramp_degree2_ = analyze_json(quote(*dir_ / "ramp.mat") + " --temp-degree 2");
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::unique_ptr<test::TempDir> dir_;
  static json truth_, ramp_auto_, ramp_degree2_;
};

std::unique_ptr<test::TempDir> CliAnalyze::dir_;
json CliAnalyze::truth_, CliAnalyze::ramp_auto_, CliAnalyze::ramp_degree2_;

TEST_F(CliAnalyze, JsonHoldsEveryContractFieldWithItsType) {
  const json& j = ramp_auto_;
  ASSERT_TRUE(j.is_object());

  const json& in = j["input"];
  EXPECT_TRUE(in["path"].is_string());
  EXPECT_EQ(in["channel"], "Y1");
  EXPECT_EQ(in["sample_rate_hz"], 10.0);
  EXPECT_TRUE(in["samples"].is_number_integer());
  EXPECT_EQ(in["samples"], 108000);
  EXPECT_EQ(in["temperature_channel"], "T1");

  const json& s = j["systematic"];
  ASSERT_TRUE(s.is_object());
  ASSERT_TRUE(s["degree"].is_number_integer());
  const std::size_t terms = s["degree"].get<std::size_t>() + 1;
  expect_numbers(s["coefficients"], "systematic.coefficients");
  EXPECT_EQ(s["coefficients"].size(), terms);
  ASSERT_TRUE(s["standard_errors"].is_array());
  EXPECT_EQ(s["standard_errors"].size(), terms);
  for (const char* k : {"t_ref_c", "bias_deg_h", "lab_constant_term_deg_h", "temperature_span_c"}) {
    EXPECT_TRUE(s[k].is_number()) << k;
  }
  EXPECT_DOUBLE_EQ(s["bias_deg_h"].get<double>(), s["coefficients"][0].get<double>());
  expect_numbers(s["lab_polyfit"], "systematic.lab_polyfit");
  EXPECT_EQ(s["lab_polyfit"].size(), 3u);
  for (const char* k : {"constant_fallback", "degree_chosen", "lab_constant_meaningful"}) {
    EXPECT_TRUE(s[k].is_boolean()) << k;
  }
  EXPECT_TRUE(s["note"].is_string());

  const json& a = j["allan"];
  EXPECT_EQ(a["kind"], "oadev");
  const std::size_t points = a["tau_s"].size();
  EXPECT_GE(points, 10u);
  for (const char* k : {"tau_s", "adev_deg_h", "ci95_low", "ci95_high", "model_adev_deg_h", "edf",
                        "edf_reduction"}) {
    expect_numbers(a[k], std::string("allan.") + k);
    EXPECT_EQ(a[k].size(), points) << k;
  }
  EXPECT_EQ(a["n"].size(), points);
  for (std::size_t k = 0; k < points; ++k) {
    EXPECT_GE(a["edf_reduction"][k].get<double>(), 1.0);
    EXPECT_LT(a["ci95_low"][k].get<double>(), a["adev_deg_h"][k].get<double>());
    EXPECT_GT(a["ci95_high"][k].get<double>(), a["adev_deg_h"][k].get<double>());
  }

  const json& p = j["psd"];
  EXPECT_EQ(p["sided"], "two");
  EXPECT_GT(p["frequency_hz"].size(), 10u);
  for (const char* k : {"frequency_hz", "sqrt_psd_deg_h_per_sqrt_hz", "psd_deg2_h2_per_hz"}) {
    expect_numbers(p[k], std::string("psd.") + k);
    EXPECT_EQ(p[k].size(), p["frequency_hz"].size()) << k;
  }

  const std::set<std::string> statuses = {"resolved", "upper_bound", "absent"};
  for (const char* k : {"N", "B", "K", "R", "Q", "gm_sigma", "gm_tc"}) {
    const json& e = j["noise_model"][k];
    ASSERT_TRUE(e.is_object()) << k;
    EXPECT_TRUE(is_number_or_null(e["value"])) << k;
    EXPECT_TRUE(is_number_or_null(e["upper_95"])) << k;
    ASSERT_TRUE(e["status"].is_string()) << k;
    EXPECT_TRUE(statuses.count(e["status"].get<std::string>())) << k << ": " << e["status"];
    if (e["status"] == "resolved") {
      ASSERT_TRUE(e["ci95"].is_array()) << k;
      ASSERT_EQ(e["ci95"].size(), 2u) << k;
      EXPECT_LE(e["ci95"][0].get<double>(), e["value"].get<double>()) << k;
      // null: an end the data do not close (a Gauss-Markov Tc like a random walk's)
      if (!e["ci95"][1].is_null()) {
        EXPECT_GE(e["ci95"][1].get<double>(), e["value"].get<double>()) << k;
      }
    } else if (e["upper_95"].is_number()) {
      // A term left out: the one-sided interval [0, bound].
      ASSERT_TRUE(e["ci95"].is_array()) << k;
      EXPECT_EQ(e["ci95"][0].get<double>(), 0.0) << k;
      EXPECT_EQ(e["ci95"][1].get<double>(), e["upper_95"].get<double>()) << k;
    } else if (std::string(k) == "gm_tc" && !e["ci95"].is_null()) {
      // A Gauss-Markov process left out: Tc's interval under the close
      // Gauss-Markov candidates (noise_fit.h), its upper end possibly open.
      ASSERT_EQ(e["ci95"].size(), 2u) << k;
      EXPECT_GE(e["ci95"][0].get<double>(), 0.0) << k;
    } else {
      EXPECT_TRUE(e["ci95"].is_null()) << k;
    }
    if (e["status"] == "absent") {
      EXPECT_TRUE(e["value"].is_null()) << k;
    }
  }

  EXPECT_TRUE(j["arw_deg_per_sqrt_h"].is_number());
  EXPECT_TRUE(j["bias_instability_deg_h"].is_number());
  EXPECT_TRUE(j["bias_instability_tau_s"].is_number());
  EXPECT_THAT(j["random_bias_process"].get<std::string>(),
              ::testing::AnyOf("none", "wiener", "gauss_markov"));
  EXPECT_TRUE(is_number_or_null(j["readings"]["adev"]["N"]));
  EXPECT_TRUE(is_number_or_null(j["readings"]["adev"]["K"]));
  EXPECT_TRUE(j["readings"]["adev"]["B"].is_number());
  EXPECT_TRUE(is_number_or_null(j["readings"]["psd"]["N"]));
  EXPECT_TRUE(is_number_or_null(j["readings"]["psd"]["K"]));
  const auto classes =
      ::testing::AnyOf("strategic", "navigation", "intermediate", "tactical", "consumer");
  EXPECT_THAT(j["accuracy_class"].get<std::string>(), classes);
  EXPECT_THAT(j["class_by_bias_instability"].get<std::string>(), classes);
  EXPECT_THAT(j["class_by_arw"].get<std::string>(), classes);
  EXPECT_THAT(j["accuracy_class_decided_by"].get<std::string>(),
              ::testing::AnyOf("bias_instability", "arw", "both"));

  const json& ev = j["random_bias_evidence"];
  for (const char* k : {"deviance_none", "deviance_wiener", "deviance_gauss_markov",
                        "criterion_none", "criterion_wiener", "criterion_gauss_markov",
                        "adev_end_slope", "psd_low_frequency_slope"}) {
    EXPECT_TRUE(ev.contains(k) && is_number_or_null(ev[k])) << k;
  }
  EXPECT_FALSE(ev["summary"].get<std::string>().empty());

  const json& f = j["fit"];
  // The reweighting loop's outcome, as NoiseFitResult states it.
  EXPECT_EQ(f["status"], "converged");
  EXPECT_THAT(
      f["message"].get<std::string>(),
      ::testing::StartsWith("converged: the chosen model " + f["terms"].get<std::string>()));
  EXPECT_GE(f["iterations"].get<int>(), 1);
  EXPECT_LE(f["iterations"].get<int>(), f["max_iterations"].get<int>());
  EXPECT_EQ(f["max_iterations"], 200);
  EXPECT_EQ(f["tolerance"], 1e-10);
  EXPECT_TRUE(f["terms"].is_string());
  EXPECT_TRUE(f["deviance"].is_number());
  EXPECT_TRUE(f["points"].is_number_integer());
  EXPECT_TRUE(f["parameters"].is_number_integer());
  EXPECT_TRUE(f["dispersion"].is_number());
  ASSERT_TRUE(f["candidates"].is_array());
  EXPECT_GE(f["candidates"].size(), 1u);
  EXPECT_LE(f["candidates"].size(), 8u);
  for (const auto& c : f["candidates"]) {
    EXPECT_TRUE(c["terms"].is_string());
    EXPECT_TRUE(c["deviance"].is_number());
    EXPECT_TRUE(c["criterion"].is_number());
    EXPECT_TRUE(c["parameters"].is_number_integer());
    EXPECT_THAT(c["status"].get<std::string>(), ::testing::AnyOf("converged", "iteration_limit"));
    EXPECT_TRUE(c["iterations"].is_number_integer());
  }

  EXPECT_TRUE(j["notes"].is_array());
  for (const auto& n : j["notes"]) EXPECT_TRUE(n.is_string());
  for (const char* k :
       {"N", "B", "K", "R", "Q", "gm_sigma", "gm_tc", "arw_deg_per_sqrt_h",
        "systematic.coefficients", "allan.adev_deg_h", "psd.sqrt_psd_deg_h_per_sqrt_hz"}) {
    EXPECT_TRUE(j["units"].contains(k)) << k;
  }
  EXPECT_EQ(j["units"]["N"], "deg/h/sqrt(Hz)");
  EXPECT_EQ(j["units"]["K"], "deg/h/sqrt(s)");
  EXPECT_TRUE(j["foglab_version"].is_string());
}

TEST_F(CliAnalyze, RampRecordingFindsTheTruth) {
  const json& j = ramp_auto_;
  const json& m = truth_["model"];
  ASSERT_EQ(j["noise_model"]["N"]["status"], "resolved");
  EXPECT_NEAR(j["noise_model"]["N"]["value"].get<double>(), m["N"].get<double>(),
              0.05 * m["N"].get<double>());
  ASSERT_EQ(j["noise_model"]["K"]["status"], "resolved");
  EXPECT_NEAR(j["noise_model"]["K"]["value"].get<double>(), m["K"].get<double>(),
              0.5 * m["K"].get<double>());
  EXPECT_NEAR(j["arw_deg_per_sqrt_h"].get<double>(),
              j["noise_model"]["N"]["value"].get<double>() / 60.0, 1e-12);

  const json& s = j["systematic"];
  ASSERT_GE(s["degree"].get<int>(), 1);
  EXPECT_FALSE(s["constant_fallback"].get<bool>());
  EXPECT_TRUE(s["lab_constant_meaningful"].get<bool>());
  EXPECT_NEAR(s["temperature_span_c"].get<double>(), 10.0, 0.5);
  EXPECT_NEAR(s["t_ref_c"].get<double>(), truth_["temperature"]["reference_c"].get<double>(), 0.1);
  const double c1 = s["coefficients"][1].get<double>();
  const double se1 = s["standard_errors"][1].get<double>();
  EXPECT_GT(se1, 0.0);
  EXPECT_NEAR(c1, m["temp_coefs"][0].get<double>(), 5.0 * se1) << "standard error " << se1;

  // Automatic degree: the one whose criterion is smallest, from degree 1 up
  // (SystematicOptions::min_degree: the ramp measures the linear term).
  ASSERT_TRUE(s["degree_chosen"].get<bool>());
  const auto& crit = s["criterion"];
  ASSERT_EQ(crit.size(), 4u);
  std::size_t best = 1;
  for (std::size_t d = 2; d < crit.size(); ++d) {
    if (crit[d].get<double>() < crit[best].get<double>()) best = d;
  }
  EXPECT_EQ(s["degree"].get<std::size_t>(), best) << "criterion " << crit;
}

TEST_F(CliAnalyze, LabConstantTermIsTheRawPolyfitAndMatchesTheTruth) {
  // The lab's number, polyfit(T, Y, 2)'s constant in raw degC, is the same
  // quadratic as the centred degree-2 fit, evaluated at T = 0; the truth's
  // raw polynomial is bias + c1 (T - T_ref) + c2 (T - T_ref)^2 at T = 0.
  const json& s = ramp_degree2_["systematic"];
  ASSERT_EQ(s["degree"], 2);
  EXPECT_FALSE(s["degree_chosen"].get<bool>());
  const double t0 = s["t_ref_c"].get<double>();
  const auto c = s["coefficients"].get<std::vector<double>>();
  const double lab = s["lab_constant_term_deg_h"].get<double>();
  EXPECT_NEAR(lab, c[0] - c[1] * t0 + c[2] * t0 * t0, 1e-6 * (1.0 + std::abs(lab)));
  EXPECT_DOUBLE_EQ(lab, s["lab_polyfit"][2].get<double>());
  // The automatic run reports the same lab number (from the quadratic in every case).
  EXPECT_NEAR(ramp_auto_["systematic"]["lab_constant_term_deg_h"].get<double>(), lab,
              1e-9 * (1.0 + std::abs(lab)));

  const json& m = truth_["model"];
  const double tr = truth_["temperature"]["reference_c"].get<double>();
  const double truth = m["bias"].get<double>() - m["temp_coefs"][0].get<double>() * tr +
                       m["temp_coefs"][1].get<double>() * tr * tr;
  // The standard error of a sum is at most the sum of the standard errors.
  const auto se = s["standard_errors"].get<std::vector<double>>();
  const double bound = se[0] + se[1] * tr + se[2] * tr * tr;
  EXPECT_NEAR(lab, truth, 5.0 * bound) << "bound " << bound;
  EXPECT_NEAR(s["coefficients"][1].get<double>(), m["temp_coefs"][0].get<double>(), 5.0 * se[1]);
  EXPECT_NEAR(s["coefficients"][2].get<double>(), m["temp_coefs"][1].get<double>(), 5.0 * se[2]);
  EXPECT_THAT(all_notes(ramp_degree2_), HasSubstr("degree 2"));
}

TEST_F(CliAnalyze, ThermostatRunFallsBackToAConstant) {
  const json j = analyze_json(quote(*dir_ / "const.mat"));
  const json& s = j["systematic"];
  EXPECT_EQ(s["degree"], 0);
  EXPECT_TRUE(s["constant_fallback"].get<bool>());
  EXPECT_FALSE(s["lab_constant_meaningful"].get<bool>());
  EXPECT_LT(s["temperature_span_c"].get<double>(), 0.5);
  EXPECT_EQ(s["coefficients"].size(), 1u);
  // The note says why: the temperature's span is too small for a slope.
  const std::string note = s["note"].get<std::string>();
  EXPECT_THAT(note, HasSubstr("degC"));
  EXPECT_THAT(note, HasSubstr("constant"));
  // Asking for a quadratic does not produce a wild one on a thermostat run.
  const json forced = analyze_json(quote(*dir_ / "const.mat") + " --temp-degree 2");
  EXPECT_EQ(forced["systematic"]["degree"], 0);
  EXPECT_TRUE(forced["systematic"]["constant_fallback"].get<bool>());
}

TEST_F(CliAnalyze, CsvHoldsTheAllanTableWithTheFittedModel) {
  const auto csv = *dir_ / "allan.csv";
  const test::CliRun r =
      run_foglab("analyze " + quote(*dir_ / "const.mat") + " --csv " + quote(csv));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = test::read_file(csv);
  EXPECT_EQ(text.rfind("tau_s,m,n,adev_deg_h,edf,ci95_low_deg_h,ci95_high_deg_h,"
                       "model_adev_deg_h,",
                       0),
            0u)
      << text.substr(0, 200);
  EXPECT_GE(std::count(text.begin(), text.end(), '\n'), 10);
  // The Markdown summary goes to stdout: parameters, units, class.
  EXPECT_THAT(r.out, HasSubstr("| parameter | value | 95 % interval | status | unit |"));
  EXPECT_THAT(r.out, HasSubstr("deg/h/sqrt(Hz)"));
  EXPECT_THAT(r.out, HasSubstr("resolved"));
  EXPECT_THAT(r.out, HasSubstr("random bias:"));
  EXPECT_THAT(r.out, HasSubstr("accuracy class:"));
}

TEST_F(CliAnalyze, ReportAndKalibrFilesAreWrittenWithTheFit) {
  const fs::path html = *dir_ / "ramp.html", yaml = *dir_ / "imu.yaml", out = *dir_ / "r.json";
  const test::CliRun r =
      run_foglab("analyze " + quote(*dir_ / "ramp.mat") + " --report " + quote(html) +
                 " --kalibr " + quote(yaml) + " --json " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = test::read_file(html);
  EXPECT_THAT(page, HasSubstr("<!DOCTYPE html>"));
  EXPECT_THAT(page, HasSubstr("ramp.mat"));
  EXPECT_THAT(page, HasSubstr("deg/h"));
  if (r.err.find("plots were skipped") == std::string::npos) {  // gnuplot installed
    std::size_t svgs = 0;
    for (std::size_t at = page.find("<svg"); at != std::string::npos;
         at = page.find("<svg", at + 1))
      ++svgs;
    EXPECT_EQ(svgs, 4u);  // record, bias against temperature, PSD, ADEV
  }
  // Kalibr's noise density is N in rad/s/sqrt(Hz): N [deg/h/sqrt(Hz)] * pi/180/3600.
  const json j = json::parse(test::read_file(out));
  const double n = j["noise_model"]["N"]["value"].get<double>();
  const std::string text = test::read_file(yaml);
  const std::string key = "gyroscope_noise_density:";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos) << text;
  const double density = std::stod(text.substr(at + key.size()));
  EXPECT_NEAR(density, n * M_PI / 180.0 / 3600.0, 1e-6 * density);
  EXPECT_THAT(text, HasSubstr("gyroscope_random_walk:"));
  EXPECT_THAT(text, HasSubstr("update_rate: 10"));
}

TEST_F(CliAnalyze, JsonToStdoutIsOnlyJson) {
  const test::CliRun r = run_foglab("analyze " + quote(*dir_ / "const.mat") + " --json -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);  // throws (fails the test) on anything else
  EXPECT_EQ(j["input"]["channel"], "Y1");
  EXPECT_EQ(j["input"]["temperature_channel"], "T1");
}

TEST(CliAnalyzeInputs, RecordWithoutTemperatureIsAnalysedWithANote) {
  test::TempDir dir;
  const auto raw = dir / "rate.f64";
  ASSERT_EQ(run_foglab("generate --N 0.5 --K 0.01 --fs 10 --hours 1 --seed 3 --out " + quote(raw))
                .exit_code,
            0);
  const test::CliRun r = run_foglab("analyze " + quote(raw) + " --fs 10 --json -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("no temperature"));
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["input"]["temperature_channel"].is_null());
  const json& s = j["systematic"];
  EXPECT_EQ(s["degree"], 0);
  ASSERT_EQ(s["coefficients"].size(), 1u);
  EXPECT_TRUE(s["bias_deg_h"].is_number());
  EXPECT_DOUBLE_EQ(s["bias_deg_h"].get<double>(), s["coefficients"][0].get<double>());
  EXPECT_TRUE(s["t_ref_c"].is_null());
  EXPECT_TRUE(s["lab_constant_term_deg_h"].is_null());
  EXPECT_THAT(all_notes(j), HasSubstr("no temperature"));
  EXPECT_NEAR(j["noise_model"]["N"]["value"].get<double>(), 0.5, 0.05 * 0.5);
}

TEST(CliAnalyzeInputs, BuiltInSampleHasNoTemperatureAndSaysSo) {
  const test::CliRun r = run_foglab("analyze");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("built-in sample"));
  EXPECT_THAT(r.err, HasSubstr("no temperature"));
  EXPECT_THAT(r.out, HasSubstr("accuracy class:"));
  EXPECT_THAT(r.out, HasSubstr("only the record mean, "));  // with its value
}

TEST(CliAnalyzeInputs, TemperaturePairsByNameY2WithT2AndRateWithTemperature) {
  test::TempDir dir;
  // Y1/Y2 white noise; T1 constant, T2 a 10 degC ramp: Y2 must pair with T2.
  const std::size_t n = 20000;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> y1(n), y2(n), t1(n, 20.0), t2(n);
  for (std::size_t k = 0; k < n; ++k) {
    y1[k] = normal(rng);
    y2[k] = normal(rng);
    t2[k] = 20.0 + 10.0 * static_cast<double>(k) / static_cast<double>(n);
  }
  const double f = 10.0;
  const std::string mat = dir.file("two.mat");
  const std::vector<io::NamedVector> vars = {
      {"f", {&f, 1}}, {"Y1", y1}, {"Y2", y2}, {"T1", t1}, {"T2", t2}};
  io::write_mat(mat, vars);
  const json j = analyze_json(quote(mat) + " --channel Y2");
  EXPECT_EQ(j["input"]["channel"], "Y2");
  EXPECT_EQ(j["input"]["temperature_channel"], "T2");
  EXPECT_NEAR(j["systematic"]["temperature_span_c"].get<double>(), 10.0, 0.5);  // block means
  // --temp overrides the pairing.
  const json k = analyze_json(quote(mat) + " --channel Y2 --temp T1");
  EXPECT_EQ(k["input"]["temperature_channel"], "T1");
  EXPECT_TRUE(k["systematic"]["constant_fallback"].get<bool>());

  // generate's CSV: the column "rate" pairs with "temperature".
  const auto csv = dir / "run.csv";
  ASSERT_EQ(
      run_foglab("generate --N 0.5 --fs 10 --hours 0.5 --temperature ramp:5 --out " + quote(csv))
          .exit_code,
      0);
  const json c = analyze_json(quote(csv) + " --channel rate");
  EXPECT_EQ(c["input"]["temperature_channel"], "temperature");
  EXPECT_NEAR(c["systematic"]["temperature_span_c"].get<double>(), 5.0, 0.5);
}

TEST(CliAnalyzeInputs, MissingTemperatureChannelIsAUsageErrorAndWritesNothing) {
  test::TempDir dir;
  const auto mat = dir / "run.mat";
  ASSERT_EQ(
      run_foglab("generate --N 0.5 --fs 10 --hours 0.2 --temperature ramp:5 --out " + quote(mat))
          .exit_code,
      0);
  const auto out = dir / "out.json";
  const test::CliRun r =
      run_foglab("analyze " + quote(mat) + " --temp NOSUCH --json " + quote(out));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("run.mat"));
  EXPECT_THAT(r.err, HasSubstr("NOSUCH"));
  EXPECT_THAT(r.err, HasSubstr("T1"));  // the channels it does have
  EXPECT_FALSE(fs::exists(out));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u);  // no temporary file either
}

TEST(CliAnalyzeInputs, TemperatureOfADifferentLengthIsADataError) {
  test::TempDir dir;
  std::vector<double> y(1000, 1.0), t(999, 20.0);
  const double f = 10.0;
  const std::string mat = dir.file("uneven.mat");
  const std::vector<io::NamedVector> vars = {{"f", {&f, 1}}, {"Y1", y}, {"T1", t}};
  io::write_mat(mat, vars);
  const test::CliRun r = run_foglab("analyze " + quote(mat) + " --json " + quote(dir / "out.json"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  for (const char* fragment : {"uneven.mat", "Y1", "T1", "1000", "999"}) {
    EXPECT_THAT(r.err, HasSubstr(fragment));
  }
  EXPECT_FALSE(fs::exists(dir / "out.json"));
}

TEST(CliAnalyzeInputs, FiveSamplesAreRejectedWithAClearMessage) {
  test::TempDir dir;
  const auto file = dir / "five.txt";
  std::ofstream(file) << "1\n2\n3\n4\n5\n";
  const test::CliRun r =
      run_foglab("analyze " + quote(file) + " --fs 1 --json " + quote(dir / "out.json"));
  EXPECT_THAT(r.exit_code, ::testing::AnyOf(2, 3)) << r.err;
  EXPECT_THAT(r.err, HasSubstr("five.txt"));
  EXPECT_THAT(r.err, HasSubstr("5 samples"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("internal error")));
  EXPECT_FALSE(fs::exists(dir / "out.json"));
}

TEST(CliAnalyzeInputs, BadTempDegreeIsAUsageError) {
  const test::CliRun r = run_foglab("analyze --temp-degree 5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--temp-degree '5'"));
}

TEST(CliAnalyzeInputs, AnUnknownLanguageIsAUsageErrorNamingTheChoices) {
  test::TempDir dir;
  const test::CliRun r = run_foglab("analyze --lang de --report " + quote(dir / "de.html"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("'en' or 'ru'"));
  EXPECT_THAT(r.err, HasSubstr("'de'"));
  EXPECT_FALSE(fs::exists(dir / "de.html"));
}

TEST(CliAnalyzeInputs, RussianReportAndSummaryOfTheBuiltInSample) {
  // --lang ru: the page and the terminal's summary in the lab manual's terms; without it,
  // English as before.
  test::TempDir dir;
  const test::CliRun r = run_foglab("analyze --lang ru --report " + quote(dir / "ru.html"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("### Модель шума (составляющие "));
  EXPECT_THAT(r.out, HasSubstr("нестабильность смещения нуля"));
  const std::string html = test::read_file(dir / "ru.html");
  EXPECT_THAT(html, HasSubstr("<html lang=\"ru\">"));
  EXPECT_THAT(html, HasSubstr("<h3>Класс точности (пособие, таблица 1)</h3>"));
  const test::CliRun en = run_foglab("analyze --report " + quote(dir / "en.html"));
  ASSERT_EQ(en.exit_code, 0) << en.err;
  EXPECT_THAT(en.out, HasSubstr("### Noise model (terms "));
  EXPECT_THAT(test::read_file(dir / "en.html"), HasSubstr("<html lang=\"en\">"));
}

TEST(CliAnalyzeInputs, TheImuFormRefusesARussianReport) {
  // Its report (report/imu.h) is English only: --lang ru says so rather than mixing them.
  test::TempDir dir;
  const std::string imu = quote(dir / "imu.csv");
  ASSERT_EQ(run_foglab("generate --imu --hours 0.01 --out " + imu).exit_code, 0);
  const test::CliRun r = run_foglab("analyze " + imu + " --lang ru");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--lang ru"));
  EXPECT_THAT(r.err, HasSubstr("--channel"));
  EXPECT_EQ(run_foglab("analyze " + imu + " --lang en").exit_code, 0);
}

}  // namespace
}  // namespace foglab
