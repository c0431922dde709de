// A 6-axis IMU's records in memory (issue 17): the six OADEVs on AllanTools's
// terms (octave taus down to 2 clusters, the records in memory, no
// intervals, then with them), and the six full analyses as `foglab analyze`
// runs them (model::analyze_records: a worker per core). Wall times, the
// median of --repeat runs. Compare with bench/allantools_compare.py on the
// same sizes.
//
//   ./build/bench/bench_imu [--samples 11520000] [--axes 6] [--repeat 3] [--no-analysis]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <vector>

#include "bench_support.h"
#include "foglab/model/analysis.h"
#include "foglab/stats/allan.h"

namespace {

using namespace foglab;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"six OADEVs and six analyses of an IMU's records in memory"};
  std::size_t samples = 11'520'000;  // 8 h at 400 Hz
  int axes = 6, repeat = 3;
  bool no_analysis = false;
  app.add_option("--samples", samples, "samples per axis")->capture_default_str();
  app.add_option("--axes", axes, "axes")->capture_default_str();
  app.add_option("--repeat", repeat, "runs (the median is reported)")->capture_default_str();
  app.add_flag("--no-analysis", no_analysis, "only the OADEVs");
  CLI11_PARSE(app, argc, argv);
  constexpr double kRateHz = 400.0;

  std::vector<std::vector<double>> records;
  for (int a = 0; a < axes; ++a) records.push_back(bench::gyro_record(samples));
  fmt::print("{} axes x {} samples at {} Hz ({:.3g} h)\n", axes, samples, kRateHz,
             static_cast<double>(samples) / kRateHz / 3600.0);

  // In place, as the CLI does (the record read is consumed: no copy, no
  // fresh memory to fault in), and through the copying API.
  for (const bool in_place : {true, false}) {
    for (const bool confidence : {false, true}) {
      stats::AllanOptions o;
      o.grid.min_clusters = 2;  // AllanTools's octave taus go down to 2 clusters
      o.confidence = confidence;
      std::vector<double> totals;
      std::size_t taus = 0;
      for (int r = 0; r < repeat; ++r) {
        std::vector<std::vector<double>> work;
        if (in_place) {
          // not timed: the records as a reader leaves them, with room for
          // the angle record's one point more (so no reallocation)
          for (const auto& y : records) {
            work.emplace_back();
            work.back().reserve(y.size() + 1);
            work.back().assign(y.begin(), y.end());
          }
        }
        const auto t0 = Clock::now();
        for (std::size_t a = 0; a < records.size(); ++a) {
          taus = in_place
                     ? stats::allan_deviation_in_place(work[a], kRateHz, InputKind::rate, o)
                           .tau_s.size()
                     : stats::allan_deviation(records[a], kRateHz, InputKind::rate, o).tau_s.size();
        }
        totals.push_back(seconds_since(t0));
      }
      fmt::print("six OADEVs {} ({} taus, {}): median {:.3f} s, runs {:.3f}\n",
                 in_place ? "in place" : "(copying API)", taus,
                 confidence ? "noise ID, edf, 68/95 % intervals" : "deviations only",
                 median(totals), fmt::join(totals, " / "));
    }
  }
  if (no_analysis) return 0;

  std::vector<double> totals;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = Clock::now();
    const auto results =
        model::analyze_records(records.size(),
                               [&](std::size_t k) {
                                 model::RecordToAnalyse rec;
                                 rec.rate_deg_h = records[k];  // a copy: the analysis consumes it
                                 rec.sample_rate_hz = kRateHz;
                                 return rec;
                               },
                               {});
    totals.push_back(seconds_since(t0));
  }
  fmt::print(
      "six full analyses (analyze_records, a worker per core): median {:.3f} s, runs {:.3f}\n",
      median(totals), fmt::join(totals, " / "));
  return 0;
}
