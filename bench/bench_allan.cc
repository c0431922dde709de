// OADEV on an octave grid over 10^8 samples, against the streaming bound
// measured in the same run: the time to read the record once (both cores)
// times the number of distinct offset streams {0, m, 2m} the grid needs;
// and analyze's stationarity check of the short taus (BM_AllanDrift).
//
//   ./build/bench/bench_allan [--benchmark_filter=...]
// FOGLAB_BENCH_SAMPLES overrides the record length (default 10^8).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <set>
#include <string>

#include "bench_support.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/allan_drift.h"

namespace {

using namespace foglab;

std::size_t samples() {
  if (const char* env = std::getenv("FOGLAB_BENCH_SAMPLES")) return std::stoull(env);
  return 100'000'000;
}

const std::vector<double>& record() {
  static const std::vector<double> y = bench::gyro_record(samples());
  return y;
}

const std::vector<double>& phase() {
  static const std::vector<double> x = stats::detail::to_phase(record(), 100.0, InputKind::rate);
  return x;
}

std::vector<std::int64_t> octave_factors(std::size_t phase_points) {
  stats::TauGrid grid;  // octave, >= 10 clusters
  return stats::averaging_factors(grid, static_cast<std::int64_t>(phase_points), 100.0,
                                  stats::max_factor(stats::AllanKind::oadev,
                                                    static_cast<std::int64_t>(phase_points)));
}

double seconds_of_read(const std::vector<double>& x) {
  double best = 1e30;
  for (int r = 0; r < 5; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(bench::read_once(x));
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

void BM_ReadOnce(benchmark::State& state) {
  const auto& x = phase();
  for (auto _ : state) benchmark::DoNotOptimize(bench::read_once(x));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * x.size() * 8));
}

void BM_OadevOctaveFromPhase(benchmark::State& state) {
  const auto& x = phase();
  const auto factors = octave_factors(x.size());
  std::set<std::int64_t> offsets = {0};
  for (const auto m : factors) {
    offsets.insert(m);
    offsets.insert(2 * m);
  }
  double best_s = 1e30;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(
        stats::detail::deviations_from_phase(x, stats::AllanKind::oadev, factors));
    best_s = std::min(best_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                                  .count());
  }
  const double read_s = seconds_of_read(x);
  const double bound_s = read_s * static_cast<double>(offsets.size());
  state.counters["taus"] = static_cast<double>(factors.size());
  state.counters["streams"] = static_cast<double>(offsets.size());
  state.counters["read_s"] = read_s;
  state.counters["bound_s"] = bound_s;
  state.counters["best_s"] = best_s;
  state.counters["best_over_bound"] = best_s / bound_s;
}

void BM_ToPhase(benchmark::State& state) {
  const auto& y = record();
  for (auto _ : state) benchmark::DoNotOptimize(stats::detail::to_phase(y, 100.0, InputKind::rate));
}

void BM_AllanDeviation(benchmark::State& state) {
  const auto& y = record();
  stats::AllanOptions options;
  options.kind = static_cast<stats::AllanKind>(state.range(0));
  options.confidence = state.range(1) != 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(stats::allan_deviation(y, 100.0, InputKind::rate, options));
  }
  state.SetLabel(std::string(stats::to_string(options.kind)) +
                 (options.confidence ? " +CI" : " no CI"));
}

// analyze's stationarity check of the short taus (allan_drift.h) on the
// whole record, no gaps.
void BM_AllanDrift(benchmark::State& state) {
  const auto& y = record();
  for (auto _ : state) benchmark::DoNotOptimize(stats::allan_drift(y, 0.01));
}

BENCHMARK(BM_ReadOnce)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();
BENCHMARK(BM_OadevOctaveFromPhase)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_ToPhase)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)->UseRealTime();
BENCHMARK(BM_AllanDrift)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_AllanDeviation)
    ->Args({static_cast<int>(stats::AllanKind::oadev), 0})
    ->Args({static_cast<int>(stats::AllanKind::oadev), 1})
    ->Args({static_cast<int>(stats::AllanKind::adev), 1})
    ->Args({static_cast<int>(stats::AllanKind::mdev), 1})
    ->Args({static_cast<int>(stats::AllanKind::ohdev), 1})
    ->Args({static_cast<int>(stats::AllanKind::totdev), 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
