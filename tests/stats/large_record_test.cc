// Numerical care on a long record: 10^9 samples of 1e-3 deg/h white noise on
// a 1e6 deg/h bias give the same deviations as the noise alone, to 1e-6
// relative (issue 2, item 6). Needs about 16 GB of memory.
// FOGLAB_LARGE_SAMPLES overrides the length for quick local runs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "foglab/stats/allan.h"
#include "support/noise.h"

namespace foglab::stats {
namespace {

std::size_t record_length() {
  if (const char* env = std::getenv("FOGLAB_LARGE_SAMPLES")) return std::stoull(env);
  return 1'000'000'000;
}

struct Case {
  AllanKind kind;
  std::vector<std::int64_t> factors;
};

std::vector<std::vector<double>> all_deviations(std::span<const double> rate,
                                                const std::vector<Case>& cases) {
  const std::vector<double> phase = detail::to_phase(rate, 100.0, InputKind::rate);
  std::vector<std::vector<double>> out;
  for (const auto& c : cases)
    out.push_back(detail::deviations_from_phase(phase, c.kind, c.factors));
  return out;
}

TEST(LargeRecord, MillionDegPerHourBiasLeavesDeviationsOfMilliDegNoiseUnchanged) {
  const std::size_t n = record_length();
  constexpr double kBiasDegH = 1e6;
  constexpr double kNoiseDegH = 1e-3;
  const auto phase_points = static_cast<std::int64_t>(n) + 1;

  std::vector<std::int64_t> octave;
  for (std::int64_t m = 1; m <= static_cast<std::int64_t>(n) / 10; m *= 2) octave.push_back(m);
  std::vector<std::int64_t> few;
  for (const std::int64_t m : {std::int64_t{1}, std::int64_t{1000}, std::int64_t{1000000},
                               static_cast<std::int64_t>(n) / 10}) {
    if (m >= 1 && m <= max_factor(AllanKind::hdev, phase_points)) few.push_back(m);
  }
  const std::vector<Case> cases = {
      {AllanKind::oadev, octave}, {AllanKind::adev, few},  {AllanKind::mdev, few},
      {AllanKind::hdev, few},     {AllanKind::ohdev, few}, {AllanKind::totdev, few},
  };

  std::vector<double> rate(n);
  test::fill_normal(rate, 7, kNoiseDegH);
  const auto reference = all_deviations(rate, cases);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) rate[i] += kBiasDegH;
  const auto biased = all_deviations(rate, cases);

  for (std::size_t c = 0; c < cases.size(); ++c) {
    for (std::size_t k = 0; k < cases[c].factors.size(); ++k) {
      EXPECT_NEAR(biased[c][k] / reference[c][k], 1.0, 1e-6)
          << to_string(cases[c].kind) << " at m = " << cases[c].factors[k];
    }
  }
  // The noise really is 1e-3 deg/h: the m = 1 deviation shows it.
  EXPECT_NEAR(reference[0][0] / kNoiseDegH, 1.0, 0.01);
}

}  // namespace
}  // namespace foglab::stats
