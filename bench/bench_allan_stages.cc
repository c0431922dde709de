// The stages of allan_deviation() (OADEV, octave taus down to 2 clusters, noise
// identification, edf and 68/95 % intervals), each timed on its own and set
// against its memory bound: the time of one parallel read of the record,
// times the number of times the stage must stream it (issue 19, item 3).
//
//   ./build/bench/bench_allan_stages [--samples 20000000] [--repeat 7]
//
// Prints each stage's median wall time, its bound and their ratio; the whole
// call is timed too, so the stages' sum can be checked against it.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <set>
#include <vector>

#include "bench_support.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/confidence.h"
#include "foglab/stats/edf.h"
#include "foglab/stats/noise_id.h"

namespace {

using namespace foglab;

double median_seconds(int repeat, const std::function<void()>& stage) {
  std::vector<double> times;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    stage();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

volatile double sink = 0.0;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The stages of allan_deviation() against their memory bounds"};
  std::size_t samples = 20'000'000;
  int repeat = 7;
  app.add_option("--samples", samples, "rate samples (white noise at 100 Hz)");
  app.add_option("--repeat", repeat, "timed runs per stage (the median is printed)");
  CLI11_PARSE(app, argc, argv);

  const double rate_hz = 100.0;
  const std::vector<double> y = bench::gyro_record(samples);
  const std::vector<double> x = stats::detail::to_phase(y, rate_hz, InputKind::rate);
  stats::AllanOptions options;
  options.grid.min_clusters = 1;
  const auto n = static_cast<std::int64_t>(x.size());
  const std::vector<std::int64_t> factors = stats::averaging_factors(
      options.grid, n, rate_hz, stats::max_factor(stats::AllanKind::oadev, n));
  std::set<std::int64_t> offsets = {0};
  for (const auto m : factors) {
    offsets.insert(m);
    offsets.insert(2 * m);
  }

  const double read_s = median_seconds(repeat, [&] { sink = bench::read_once(y); });
  struct Row {
    const char* stage;
    double seconds;
    double reads;  // the bound, in reads of the record
    const char* bound;
  };
  std::vector<Row> rows;
  rows.push_back({"one parallel read of the record", read_s, 1.0, "1 read"});
  rows.push_back(
      {"integration into fresh memory (sums, then the angle points)",
       median_seconds(repeat,
                      [&] {
                        const auto p = std::make_unique_for_overwrite<double[]>(x.size());
                        advise_huge_pages(p.get(), x.size());
                        stats::detail::to_phase_into(y, rate_hz, InputKind::rate, p.get());
                        sink = p[x.size() / 2];
                      }),
       3.0, "2 reads + 1 write"});
  rows.push_back({"OADEV deviations",
                  median_seconds(repeat,
                                 [&] {
                                   sink = stats::detail::deviations_from_phase(
                                       x, stats::AllanKind::oadev, factors)[0];
                                 }),
                  static_cast<double>(offsets.size()), "one read per offset stream {0, m, 2m}"});
  rows.push_back(
      {"noise identification (lag-1, B1)",
       median_seconds(repeat, [&] { sink = stats::identify_noise(x, factors, 2)[0].rho; }), 4.0,
       "2 passes, decimated: sum over m of 2/m reads"});
  const std::vector<std::int64_t> stretch = {n};
  rows.push_back({"edf and chi-square intervals",
                  median_seconds(repeat,
                                 [&] {
                                   double s = 0.0;
                                   for (const auto m : factors) {
                                     const double edf = stats::pooled_edf(0, m, stretch);
                                     s += stats::chi2_interval(1.0, edf, stats::kConfidence68).low +
                                          stats::chi2_interval(1.0, edf, stats::kConfidence95).low;
                                   }
                                   sink = s;
                                 }),
                  0.0, "no data"});
  rows.push_back(
      {"allan_deviation(), copying API (Python)",
       median_seconds(
           repeat,
           [&] { sink = stats::allan_deviation(y, rate_hz, InputKind::rate, options).dev[0]; }),
       0.0, ""});

  fmt::print(
      "record: {} rate samples at {} Hz; OADEV, {} octave factors 1 .. {} ({} offset "
      "streams); median of {} runs\n\n",
      samples, rate_hz, factors.size(), factors.back(), offsets.size(), repeat);
  fmt::print("| stage | time | memory bound | time / bound |\n|---|---|---|---|\n");
  for (const Row& r : rows) {
    if (r.reads > 0.0) {
      fmt::print("| {} | {:.4f} s | {:.4f} s ({}) | {:.2f} |\n", r.stage, r.seconds,
                 r.reads * read_s, r.bound, r.seconds / (r.reads * read_s));
    } else {
      fmt::print("| {} | {:.4f} s | {} | |\n", r.stage, r.seconds, r.bound);
    }
  }
  return 0;
}
