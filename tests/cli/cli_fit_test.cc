// `foglab fit TABLE`: the noise model from an Allan table alone, against the
// truth of a generated record, Stable32's printed tables, tables without
// counts, and bad tables.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/cli.h"
#include "support/reference_data.h"

namespace foglab {
namespace {

using nlohmann::json;
using test::quote;
using test::run_foglab;

json fit_json(const std::string& table) { return test::run_json("fit " + table + " --json -"); }

// Keeps the first `columns` comma-separated columns of every line.
void keep_columns(const std::string& from, const std::string& to, int columns) {
  std::ifstream in(from);
  std::ofstream out(to);
  std::string line;
  while (std::getline(in, line)) {
    std::size_t end = 0;
    for (int k = 0; k < columns && end != std::string::npos; ++k) end = line.find(',', end + 1);
    out << line.substr(0, end) << "\n";
  }
}

TEST(CliFit, RecoversTheGeneratedModelFromItsOwnAllanTable) {
  // 4 h at 100 Hz with N = 0.1 deg/h/sqrt(Hz), B = 0.05 deg/h, K = 0.01
  // deg/h/sqrt(s): the fit of `allan --csv`'s table (its edf column) finds
  // N within 3 % and B, K inside their 95 % intervals (issue 4's goals);
  // with the counts alone it finds nearly the same; with tau and the
  // deviation alone it says it cannot give intervals.
  const test::TempDir dir;
  const std::string record = quote(dir / "run.f32");
  ASSERT_EQ(
      run_foglab("generate --N 0.1 --B 0.05 --K 0.01 --fs 100 --hours 4 --seed 6 --out " + record)
          .exit_code,
      0);
  const std::string table = (dir / "allan.csv").string();
  ASSERT_EQ(run_foglab("allan " + record + " --fs 100 --csv " + quote(table)).exit_code, 0);
  const json full = fit_json(quote(table));
  EXPECT_EQ(full["edf_source"], "edf_column");
  EXPECT_EQ(full["source"]["layout"], "header");
  const json& model = full["noise_model"];
  EXPECT_NEAR(model["N"]["value"].get<double>() / 0.1, 1.0, 0.03);
  for (const auto& [name, truth] : {std::pair{"B", 0.05}, std::pair{"K", 0.01}}) {
    EXPECT_EQ(model[name]["status"], "resolved") << name;
    EXPECT_LE(model[name]["ci95"][0].get<double>(), truth) << name;
    EXPECT_GE(model[name]["ci95"][1].get<double>(), truth) << name;
  }
  EXPECT_EQ(model["N"]["unit"], "deg/h/sqrt(Hz)");
  EXPECT_EQ(full["accuracy_class"], "intermediate");

  const std::string counts = (dir / "counts.csv").string();
  keep_columns(table, counts, 4);  // tau_s, m, n, dev
  const json from_counts = fit_json(quote(counts));
  EXPECT_EQ(from_counts["edf_source"], "counts");
  EXPECT_NEAR(
      from_counts["noise_model"]["B"]["value"].get<double>() / model["B"]["value"].get<double>(),
      1.0, 0.05);

  const std::string bare = (dir / "bare.csv").string();
  {
    std::ifstream in(table);
    std::ofstream out(bare);
    std::string line;
    while (std::getline(in, line)) {  // tau_s and dev_deg_h: columns 1 and 4
      std::stringstream fields(line);
      std::string f[4];
      for (std::string& v : f) std::getline(fields, v, ',');
      out << f[0] << "," << f[3] << "\n";
    }
  }
  const json from_bare = fit_json(quote(bare));
  EXPECT_EQ(from_bare["edf_source"], "assumed");
  EXPECT_TRUE(from_bare["noise_model"]["B"]["ci95"].is_null());
  ASSERT_EQ(from_bare["notes"].size(), 1u);
  EXPECT_NE(from_bare["notes"][0].get<std::string>().find("no intervals"), std::string::npos);
}

TEST(CliFit, ReadsStable32TablesAndTheirBoundsGiveBackTheEdf) {
  // Stable32's OADEV octave table on PHASE.DAT: seven unlabelled columns;
  // the edf recovered from its 68 % bounds is the edf foglab's own
  // `allan` finds for the same taus, within 2 %.
  const std::string file = test::data_path("stable32-phasedat/phase_dat_oadev_octave.txt");
  const json j = fit_json(quote(file));
  EXPECT_EQ(j["source"]["layout"], "stable32");
  EXPECT_EQ(j["edf_source"], "bounds");
  const test::CliRun own =
      run_foglab("allan " + quote(test::data_path("stable32-phasedat/PHASE.DAT")) +
                 " --input phase --fs 1 --min-clusters 1 --json -");
  ASSERT_EQ(own.exit_code, 0) << own.err;
  const json allan = json::parse(own.out);
  ASSERT_EQ(j["edf"].size(), test::read_stable32("phase_dat_oadev_octave.txt").size());
  for (std::size_t k = 0; k < j["edf"].size(); ++k) {
    EXPECT_NEAR(j["edf"][k].get<double>() / allan["edf"][k].get<double>(), 1.0, 0.02)
        << "tau " << j["tau_s"][k];
  }
}

TEST(CliFit, BadTablesAreDataErrorsThatNameTheLine) {
  const test::TempDir dir;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return quote(dir / name);
  };
  const test::CliRun text_row =
      run_foglab("fit " + write("a.csv", "tau_s,adev\n1,0.3\n2,oops\n4,0.1\n"));
  EXPECT_EQ(text_row.exit_code, 3);
  EXPECT_NE(text_row.err.find("line 3"), std::string::npos) << text_row.err;
  EXPECT_NE(text_row.err.find("a.csv"), std::string::npos) << text_row.err;
  const test::CliRun falling =
      run_foglab("fit " + write("b.csv", "tau,sigma\n1,0.3\n4,0.2\n2,0.1\n"));
  EXPECT_EQ(falling.exit_code, 3);
  EXPECT_NE(falling.err.find("taus must increase"), std::string::npos) << falling.err;
  const test::CliRun no_dev = run_foglab("fit " + write("c.csv", "tau_s,value\n1,2\n2,3\n4,5\n"));
  EXPECT_EQ(no_dev.exit_code, 3);
  EXPECT_NE(no_dev.err.find("deviation column"), std::string::npos) << no_dev.err;
  const test::CliRun two = run_foglab("fit " + write("d.csv", "tau_s,adev\n1,0.3\n2,0.2\n"));
  EXPECT_EQ(two.exit_code, 3);
  EXPECT_NE(two.err.find("at least 3"), std::string::npos) << two.err;
  // Another statistic's table, by its column name or Stable32's "Sigma Type".
  const test::CliRun mdev =
      run_foglab("fit " + write("e.csv", "tau_s,mdev\n1,0.3\n2,0.2\n4,0.1\n"));
  EXPECT_EQ(mdev.exit_code, 3);
  EXPECT_NE(mdev.err.find("'mdev' is not an Allan deviation"), std::string::npos) << mdev.err;
  const test::CliRun modified =
      run_foglab("fit " + quote(test::data_path("stable32-phasedat/phase_dat_mdev_octave.txt")));
  EXPECT_EQ(modified.exit_code, 3);
  EXPECT_NE(modified.err.find("Modified Allan"), std::string::npos) << modified.err;
  const test::CliRun missing = run_foglab("fit " + quote(dir / "none.csv"));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("none.csv"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace foglab
