// `foglab allan` end to end: the published references through the CLI's
// JSON, the JSON/CSV contract of docs/json.md, and every input route.
#include <gtest/gtest.h>
#include <matio.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "support/cli.h"
#include "support/reference_data.h"

namespace foglab {
namespace {

using nlohmann::json;
using test::quote;
using test::run_foglab;

// A tau as the CLI reads it back exactly: Theo1's 0.75 m are not integers.
std::string fmt_tau(double tau_s) {
  std::ostringstream out;
  out.precision(17);
  out << tau_s;
  return out.str();
}

// `foglab ARGS --json -`, parsed.
json allan_json(const std::string& args) { return test::run_json(args + " --json -"); }

struct OctaveCase {
  std::string file;
  std::string kind;
};

void PrintTo(const OctaveCase& c, std::ostream* os) { *os << c.file; }

class CliStable32 : public ::testing::TestWithParam<OctaveCase> {};

TEST_P(CliStable32, JsonReproducesTheOctaveTableWithIntervals) {
  const OctaveCase& c = GetParam();
  const json j =
      allan_json("allan " + quote(test::data_path("stable32-phasedat/PHASE.DAT")) +
                 " --input phase --fs 1 --kind " + c.kind + " --taus octave --min-clusters 1");
  EXPECT_EQ(j["kind"], c.kind);
  EXPECT_EQ(j["input"], "phase");
  std::map<double, std::size_t> index;
  for (std::size_t k = 0; k < j["tau_s"].size(); ++k) index[j["tau_s"][k].get<double>()] = k;
  for (const auto& row : test::read_stable32(c.file)) {
    ASSERT_TRUE(index.count(row.tau_s)) << c.file << " tau " << row.tau_s;
    const std::size_t k = index[row.tau_s];
    EXPECT_NEAR(j["dev"][k].get<double>() / row.sigma, 1.0, 2e-4) << c.file << " AF " << row.af;
    EXPECT_EQ(j["n"][k].get<std::int64_t>(), row.n) << c.file << " AF " << row.af;
    EXPECT_EQ(j["alpha"][k].get<int>(), row.alpha) << c.file << " AF " << row.af;
    EXPECT_NEAR(j["ci68_low"][k].get<double>() / row.min_sigma, 1.0, 0.01) << c.file;
    EXPECT_NEAR(j["ci68_high"][k].get<double>() / row.max_sigma, 1.0, 0.01) << c.file;
    EXPECT_LT(j["ci95_low"][k].get<double>(), j["ci68_low"][k].get<double>());
    EXPECT_GT(j["ci95_high"][k].get<double>(), j["ci68_high"][k].get<double>());
  }
}

INSTANTIATE_TEST_SUITE_P(OctaveTables, CliStable32,
                         ::testing::Values(OctaveCase{"phase_dat_adev_octave.txt", "adev"},
                                           OctaveCase{"phase_dat_oadev_octave.txt", "oadev"},
                                           OctaveCase{"phase_dat_mdev_octave.txt", "mdev"},
                                           OctaveCase{"phase_dat_tdev_octave.txt", "tdev"},
                                           OctaveCase{"phase_dat_hdev_octave.txt", "hdev"},
                                           OctaveCase{"phase_dat_ohdev_octave.txt", "ohdev"},
                                           OctaveCase{"phase_dat_totdev_octave.txt", "totdev"}),
                         [](const auto& info) { return info.param.kind; });

TEST(CliAllan, EveryStable32AllTauTableThroughAnExplicitTauList) {
  const std::map<std::string, std::string> tables = {
      {"adev", "phase_dat_adev.txt"},   {"oadev", "phase_dat_oadev.txt"},
      {"mdev", "phase_dat_mdev.txt"},   {"tdev", "phase_dat_tdev.txt"},
      {"hdev", "phase_dat_hdev.txt"},   {"ohdev", "phase_dat_ohdev.txt"},
      {"totdev", "phase_dat_totdev.txt"}};
  for (const auto& [kind, file] : tables) {
    const auto rows = test::read_stable32(file);
    std::string taus;
    for (const auto& row : rows) taus += (taus.empty() ? "" : ",") + std::to_string(row.af);
    const json j = allan_json("allan " + quote(test::data_path("stable32-phasedat/PHASE.DAT")) +
                              " --input phase --fs 1 --kind " + kind + " --taus " + taus);
    ASSERT_EQ(j["dev"].size(), rows.size()) << file;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      EXPECT_NEAR(j["dev"][k].get<double>() / rows[k].sigma, 1.0, 2e-4) << file << " AF "
                                                                         << rows[k].af;
      EXPECT_EQ(j["n"][k].get<std::int64_t>(), rows[k].n) << file << " AF " << rows[k].af;
    }
  }
}

TEST(CliAllan, MtieAndTieRmsReproduceStable32AndTakeTheRateAsItsIntegral) {
  const std::string phase_dat = quote(test::data_path("stable32-phasedat/PHASE.DAT"));
  for (const auto& [kind, file] :
       {std::pair{"mtie", "phase_dat_mtie.txt"}, std::pair{"tierms", "phase_dat_tierms.txt"}}) {
    const auto rows = test::read_stable32_values(file);
    std::string taus;
    for (const auto& row : rows) taus += (taus.empty() ? "" : ",") + std::to_string(row.af);
    const json j = allan_json("allan " + phase_dat + " --input phase --fs 1 --kind " +
                              std::string(kind) + " --taus " + taus);
    EXPECT_EQ(j["kind"], kind);
    EXPECT_EQ(j["unit"], "deg/h*s");
    ASSERT_EQ(j["value"].size(), rows.size()) << file;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      EXPECT_NEAR(j["value"][k].get<double>() / rows[k].sigma, 1.0, 2e-4)
          << file << " AF " << rows[k].af;
      EXPECT_EQ(j["n"][k].get<std::int64_t>(), rows[k].n) << file << " AF " << rows[k].af;
    }
  }
  // A rate record at 4 Hz is integrated as it is (its bias kept): the same
  // values as its angle record x_{k+1} = x_k + y_k / 4 given as phase.
  const test::TempDir dir;
  const std::vector<double> y = test::nbs14_1000();
  std::ofstream rate(dir / "rate.csv"), angle(dir / "angle.csv");
  rate.precision(17);
  angle.precision(17);
  double x = 0.0;
  angle << x << "\n";
  for (const double v : y) {
    rate << 1000.0 + v << "\n";
    x += (1000.0 + v) / 4.0;
    angle << x << "\n";
  }
  rate.close();
  angle.close();
  for (const char* kind : {"mtie", "tierms"}) {
    const json from_rate = allan_json("allan " + quote(dir / "rate.csv") + " --fs 4 --kind " +
                                      kind + " --min-clusters 3");
    const json from_angle =
        allan_json("allan " + quote(dir / "angle.csv") + " --input phase --fs 4 --kind " + kind +
                   " --min-clusters 3");
    ASSERT_EQ(from_rate["value"].size(), from_angle["value"].size()) << kind;
    for (std::size_t k = 0; k < from_rate["value"].size(); ++k) {
      EXPECT_NEAR(from_rate["value"][k].get<double>() / from_angle["value"][k].get<double>(), 1.0,
                  1e-9)
          << kind << " tau " << from_rate["tau_s"][k];
    }
  }
  // MTIE of a rate with a bias grows with it: 250 deg/h for 1 s at least.
  const json biased =
      allan_json("allan " + quote(dir / "rate.csv") + " --fs 4 --kind mtie --taus 1");
  EXPECT_GT(biased["value"][0].get<double>(), 250.0);
}

TEST(CliAllan, TimeErrorRefusesGapsAndUnknownKindsAreNamed) {
  const test::TempDir dir;
  const std::string out = quote(dir / "gaps.csv");
  ASSERT_EQ(run_foglab("generate --N 0.2 --fs 10 --hours 0.05 --drop 60:5 --out " + out).exit_code,
            0);
  const test::CliRun gaps = run_foglab("allan " + out + " --kind mtie");
  EXPECT_EQ(gaps.exit_code, 3) << gaps.err;
  EXPECT_NE(gaps.err.find("1 gap(s)"), std::string::npos) << gaps.err;
  EXPECT_NE(gaps.err.find("gaps.csv"), std::string::npos) << gaps.err;
  const test::CliRun unknown = run_foglab("allan " + out + " --kind mtiex");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("'mtiex'"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("mtie or tierms"), std::string::npos) << unknown.err;
}

TEST(CliAllan, TotalAndTheoFamilyReproduceStable32WithTheirOptions) {
  // Stable32 1.60's decade MTOTDEV/TTOTDEV (its noise types: --noise-id
  // stable32), its HTOTDEV with and without the bias factor, its white-FM
  // Theo1 (taus 0.75 m), each to the table's printed digits; the time-like
  // TTOTDEV carries (deg/h)*s in the JSON unit and the CSV header.
  const std::string phase_dat = quote(test::data_path("stable32-phasedat/PHASE.DAT"));
  struct Case {
    std::string kind, file, options;
  };
  const std::vector<Case> cases = {
      {"mtotdev", "phase_dat_mtotdev_decade.txt", "--noise-id stable32"},
      {"ttotdev", "phase_dat_ttotdev_decade.txt", "--noise-id stable32"},
      {"htotdev", "phase_dat_htotdev_octave.txt", ""},
      {"htotdev", "phase_dat_htotdev_octave_nobias.txt", "--no-bias-correction --no-ci"},
      {"theo1", "phase_dat_theo1_alpha0_decade.txt", "--no-ci"}};
  for (const Case& c : cases) {
    const auto rows = test::read_stable32(c.file);
    std::string taus;
    for (const auto& row : rows) taus += (taus.empty() ? "" : ",") + fmt_tau(row.tau_s);
    const json j = allan_json("allan " + phase_dat + " --input phase --fs 1 --kind " + c.kind +
                              " --taus " + taus + " " + c.options);
    EXPECT_EQ(j["kind"], c.kind);
    EXPECT_EQ(j["unit"], c.kind == "ttotdev" ? "deg/h*s" : "deg/h");
    EXPECT_EQ(j["bias_correction"], c.kind == "htotdev" && c.options.empty()) << c.file;
    ASSERT_EQ(j["dev"].size(), rows.size()) << c.file;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      EXPECT_EQ(j["m"][k].get<std::int64_t>(), rows[k].af) << c.file;
      EXPECT_NEAR(j["dev"][k].get<double>() / rows[k].sigma, 1.0, 2e-4)
          << c.file << " AF " << rows[k].af;
      if (c.options.find("--no-ci") != std::string::npos) continue;
      EXPECT_EQ(j["alpha"][k].get<int>(), rows[k].alpha) << c.file << " AF " << rows[k].af;
      EXPECT_NEAR(j["ci68_low"][k].get<double>() / rows[k].min_sigma, 1.0, 0.01) << c.file;
    }
  }
  const test::CliRun csv =
      run_foglab("allan " + phase_dat + " --input phase --fs 1 --kind ttotdev --csv -");
  EXPECT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out.substr(0, csv.out.find('\n')),
            "tau_s,m,n,dev_deg_h_s,alpha,edf,ci68_low_deg_h_s,ci68_high_deg_h_s,"
            "ci95_low_deg_h_s,ci95_high_deg_h_s");
  const test::CliRun bad_rules =
      run_foglab("allan " + phase_dat + " --input phase --fs 1 --noise-id stable33");
  EXPECT_EQ(bad_rules.exit_code, 2);
  EXPECT_NE(bad_rules.err.find("foglab or stable32"), std::string::npos) << bad_rules.err;
  const test::CliRun odd_theo1 =
      run_foglab("allan " + phase_dat + " --input phase --fs 1 --kind theo1 --taus 800");
  EXPECT_EQ(odd_theo1.exit_code, 3) << odd_theo1.err;
  EXPECT_NE(odd_theo1.err.find("theo1 taus up to 750 s"), std::string::npos) << odd_theo1.err;
}

TEST(CliAllan, Nbs14TableThroughCsvInputAndJsonOutput) {
  test::TempDir dir;
  {
    std::ofstream csv(dir / "nbs14.csv");
    csv << "# NBS14 1000-point set\nrate\n";
    csv.precision(17);
    for (const double y : test::nbs14_1000()) csv << y << "\n";
  }
  const std::map<std::string, std::vector<double>> expected = {
      {"adev", {2.922319e-01, 9.965736e-02, 3.897804e-02}},
      {"oadev", {2.922319e-01, 9.159953e-02, 3.241343e-02}},
      {"mdev", {2.922319e-01, 6.172376e-02, 2.170921e-02}},
      {"totdev", {2.922319e-01, 9.134743e-02, 3.406530e-02}},
      {"hdev", {2.943883e-01, 1.052754e-01, 3.910860e-02}},
      {"ohdev", {2.943883e-01, 9.581083e-02, 3.237638e-02}},
      {"tdev", {1.687202e-01, 3.563623e-01, 1.253382e+00}},
  };
  for (const auto& [kind, values] : expected) {
    const json j = allan_json("allan " + quote(dir / "nbs14.csv") + " --fs 1 --kind " + kind +
                              " --taus 1,10,100");
    ASSERT_EQ(j["dev"].size(), 3u) << kind;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(j["dev"][k].get<double>() / values[k], 1.0, 1e-6) << kind;
    }
    EXPECT_EQ(j["tau_s"], json::array({1.0, 10.0, 100.0}));
  }
}

TEST(CliAllan, JsonAndCsvCarryTheContractFields) {
  test::TempDir dir;
  const std::string data = quote(test::data_path("stable32-phasedat/PHASE.DAT"));
  const test::CliRun r = run_foglab("allan " + data + " --fs 1 --input phase --json " +
                                    quote(dir / "out.json") + " --csv " + quote(dir / "out.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(test::read_file(dir / "out.json"));
  for (const char* field : {"kind", "input", "tau_s", "dev", "n", "alpha", "ci68_low",
                            "ci68_high", "ci95_low", "ci95_high"}) {
    EXPECT_TRUE(j.contains(field)) << field;
  }
  EXPECT_EQ(j["kind"], "oadev");
  EXPECT_EQ(j["unit"], "deg/h");
  // Default octave grid keeps >= 10 clusters: 1000 samples -> m <= 100.
  EXPECT_EQ(j["tau_s"], json::array({1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0}));
  const std::string csv = test::read_file(dir / "out.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "tau_s,m,n,dev_deg_h,alpha,edf,ci68_low_deg_h,ci68_high_deg_h,ci95_low_deg_h,"
            "ci95_high_deg_h");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8);
  EXPECT_NE(r.out.find("tau [s]"), std::string::npos);  // the table on stdout
}

void write_mat(const std::filesystem::path& path, mat_ft version, double fs,
               const std::vector<double>& y) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, version);
  ASSERT_NE(mat, nullptr);
  size_t scalar[2] = {1, 1};
  size_t dims[2] = {y.size(), 1};
  matvar_t* f = Mat_VarCreate("f", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, scalar, &fs, 0);
  matvar_t* v = Mat_VarCreate("Y1", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                              const_cast<double*>(y.data()), 0);
  Mat_VarWrite(mat, f, MAT_COMPRESSION_NONE);
  Mat_VarWrite(mat, v, MAT_COMPRESSION_NONE);
  Mat_VarFree(f);
  Mat_VarFree(v);
  Mat_Close(mat);
}

TEST(CliAllan, MatFilesV5AndV73GiveTheSameResultWithTheRateFromF) {
  test::TempDir dir;
  const std::vector<double> y = test::nbs14_1000();
  write_mat(dir / "v5.mat", MAT_FT_MAT5, 1.0, y);
  write_mat(dir / "v73.mat", MAT_FT_MAT73, 1.0, y);
  const json a = allan_json("allan " + quote(dir / "v5.mat") + " --channel Y1 --taus 10");
  const json b = allan_json("allan " + quote(dir / "v73.mat") + " --taus 10");
  EXPECT_NEAR(a["dev"][0].get<double>() / 9.159953e-02, 1.0, 1e-6);
  EXPECT_EQ(a["dev"], b["dev"]);
  EXPECT_EQ(a["source"]["sample_rate_source"].get<std::string>().find("f") != std::string::npos,
            true);
}

TEST(CliAllan, StdinUnitsAndTheBuiltInSample) {
  std::ostringstream text_stream;
  text_stream.precision(17);
  for (const double y : test::nbs14_1000()) text_stream << y / 3600.0 << "\n";
  const std::string text = text_stream.str();
  // deg/s input: converted to deg/h on reading, so the NBS14 numbers return.
  const test::CliRun r = run_foglab("allan - --fs 1 --units deg/s --taus 1 --json -", text);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(json::parse(r.out)["dev"][0].get<double>() / 2.922319e-01, 1.0, 1e-5);

  const test::CliRun sample = run_foglab("allan");
  EXPECT_EQ(sample.exit_code, 0) << sample.err;
  EXPECT_NE(sample.err.find("built-in sample"), std::string::npos);
  EXPECT_NE(sample.out.find("oadev"), std::string::npos);
}

}  // namespace
}  // namespace foglab
