// The lab's own MATLAB steps, run by GNU Octave on `foglab lab2-data` files:
// load, plot(t, Y1) headless, polyfit(T, Y, 2) — and the fitted ramp-run
// polynomial agrees with the answer key within the random-bias wander.
// Skipped (with a message) when octave-cli is not installed;
// scripts/install-deps.sh installs it, so CI runs it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.h"
#include "support/files.h"

namespace foglab {
namespace {

using nlohmann::json;
using test::quote;
using test::run_foglab;

bool have_octave() { return std::system("command -v octave-cli > /dev/null 2>&1") == 0; }

TEST(OctaveCompat, LabStepsRunHeadlessAndPolyfitMatchesTheAnswerKey) {
  if (!have_octave()) {
    GTEST_SKIP() << "octave-cli is not on PATH (scripts/install-deps.sh installs it); "
                    "the MATLAB-compatibility check of lab2-data files is skipped";
  }
  test::TempDir dir;
  const test::CliRun gen = run_foglab("lab2-data --out " + quote(dir.path()));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  const json answers = json::parse(test::read_file(dir / "answers.json"));

  // The lab manual's steps 1.2-1.4 and 2.1 for every file, with no display:
  // an invisible figure (gnuplot toolkit, the only one without Qt/X).
  const std::string script =
      "files = dir('FOG*_*.mat');\n"
      "for i = 1:numel(files)\n"
      "  clear f t Y1 Y2 T1 T2;\n"
      "  load(files(i).name);\n"
      "  assert(isscalar(f)); assert(iscolumn(t)); assert(iscolumn(Y1)); assert(iscolumn(Y2));\n"
      "  assert(iscolumn(T1)); assert(iscolumn(T2)); assert(numel(Y1) == numel(t));\n"
      "  h = figure('visible', 'off'); plot(t, Y1); grid on; close(h);\n"
      "  p = polyfit(T1, Y1, 2); r = polyfit(T2, Y2, 2);\n"
      "  assert(all(isfinite(p)));\n"
      "  printf('%s %.17g %.17g %.17g %.17g\\n', files(i).name, f, r(1), r(2), r(3));\n"
      "end\n";
  std::ofstream(dir / "lab2_steps.m") << script;
  const auto out = dir / "octave.out";
  const auto err = dir / "octave.err";
  // a non-interactive shell without a display, as in CI
  const std::string command = "cd " + quote(dir.path()) +
                              " && env -u DISPLAY octave-cli --no-gui --no-window-system "
                              "--eval \"lab2_steps; exit(0)\" < /dev/null > " + quote(out) +
                              " 2> " + quote(err);
  const int status = std::system(command.c_str());
  ASSERT_EQ(status, 0) << "octave-cli failed:\n" << test::read_file(err);

  std::map<std::string, std::vector<double>> fitted;
  std::istringstream lines(test::read_file(out));
  std::string name;
  double f = 0.0, r1 = 0.0, r2 = 0.0, r3 = 0.0;
  while (lines >> name >> f >> r1 >> r2 >> r3) fitted[name] = {f, r1, r2, r3};
  ASSERT_EQ(fitted.size(), 12u) << test::read_file(out) << test::read_file(err);

  for (const json& row : answers["runs"]) {
    if (row["run"] != "ramp") continue;
    const std::string file = row["file"];
    ASSERT_TRUE(fitted.count(file)) << file;
    const std::vector<double>& v = fitted[file];
    EXPECT_EQ(v[0], row["sample_rate_hz"].get<double>()) << file;
    const json& e = row["expected"];
    const double tr = row["temperature"]["reference_c"];
    const double half_span = row["temperature"]["span_c"].get<double>() / 2.0;
    // both polynomials about T_ref: c0 + c1 (T - Tr) + c2 (T - Tr)^2
    auto centred = [tr](double a2, double a1, double a0) {
      return std::vector<double>{a0 + a1 * tr + a2 * tr * tr, a1 + 2.0 * a2 * tr, a2};
    };
    const std::vector<double> want =
        centred(e["polyfit_p"][0], e["polyfit_p"][1], e["polyfit_p"][2]);
    const std::vector<double> got = centred(v[1], v[2], v[3]);
    // What the fit cannot separate from the temperature law: the random
    // bias wandering over the run (Wiener K sqrt(D) or Gauss-Markov sigma),
    // the flicker floor and the white noise's mean; 1.5 of them is the
    // tolerance on the bias at T_ref, and on the slope and curvature over
    // the half span.
    const double duration = row["duration_s"];
    const double wander = (e["K"].is_null() ? 0.0 : e["K"].get<double>() * std::sqrt(duration)) +
                          (e["gm_sigma"].is_null() ? 0.0 : e["gm_sigma"].get<double>()) +
                          3.0 * e["flicker_floor_deg_h"].get<double>() +
                          e["N"].get<double>() / std::sqrt(duration);
    const double tol = 1.5 * wander;
    EXPECT_NEAR(got[0], want[0], tol) << file << " bias at T_ref";
    EXPECT_NEAR(got[1], want[1], 2.0 * tol / half_span) << file << " slope";
    EXPECT_NEAR(got[2], want[2], 4.0 * tol / (half_span * half_span)) << file << " curvature";
    // and the temperature law is far outside that: the ramp run shows it
    EXPECT_GT(std::abs(want[1]) * half_span, 0.5 * wander) << file;
  }
}

}  // namespace
}  // namespace foglab
