// Optical signal chain speed (sim/optics.h, lab 1). The goal: the
// closed-loop time simulation runs faster than real time for every Table 4
// variant at 16 samples per modulation period (the default M = 8 samples
// per transit) on one core. Each benchmark simulates FOGLAB_BENCH_OPTICS_S
// seconds of gyro time (0.2 s by default) with a rate ramp from 0 to
// 2 Omega_pi/2; the argument is the variant 1..6.
//
// Counters: items_per_second = simulated samples per wall second;
// samples_per_sim_s = samples per simulated second (16 f_m);
// realtime_factor = simulated seconds per wall second (> 1: faster than
// real time); wall_s_per_sim_s = its inverse.
//
//   ./build/bench/bench_optics
//   FOGLAB_BENCH_OPTICS_S=1 ./build/bench/bench_optics   (longer records)
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdlib>

#include "foglab/sim/optics.h"

namespace {

namespace sim = foglab::sim;

double simulated_seconds() {
  if (const char* text = std::getenv("FOGLAB_BENCH_OPTICS_S")) return std::atof(text);
  return 0.2;
}

void run(benchmark::State& state, bool closed_loop, sim::Modulation modulation) {
  const sim::Coil coil = sim::lab1_coil(static_cast<int>(state.range(0)));
  const sim::CoilNumbers numbers = sim::coil_numbers(coil);
  const double duration = simulated_seconds();
  const sim::RateInput rate =
      sim::RateInput::ramp(0.0, 2.0 * numbers.omega_pi2_rad_s, 0.5 * duration);
  sim::OpticsOptions options;  // M = 8: 16 samples per period at f_m; no trace
  options.modulation = modulation;
  std::int64_t samples = 0;
  double simulated = 0.0;
  for (auto _ : state) {
    const sim::OpticsResult r = closed_loop
                                    ? sim::simulate_closed_loop(coil, rate, duration, options)
                                    : sim::simulate_open_loop(coil, rate, duration, options);
    benchmark::DoNotOptimize(r.periods.output.back());
    samples += r.samples;
    simulated += static_cast<double>(r.samples) * r.sample_interval_s;
  }
  state.SetItemsProcessed(samples);
  state.counters["samples_per_sim_s"] = 16.0 * numbers.modulation_frequency_hz;
  state.counters["realtime_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["wall_s_per_sim_s"] =
      benchmark::Counter(simulated, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_ClosedLoop(benchmark::State& state) { run(state, true, sim::Modulation::square); }
void BM_OpenLoopSine(benchmark::State& state) { run(state, false, sim::Modulation::sine); }
void BM_OpenLoopSquare(benchmark::State& state) { run(state, false, sim::Modulation::square); }

BENCHMARK(BM_ClosedLoop)
    ->DenseRange(1, sim::kLab1Variants)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OpenLoopSine)
    ->DenseRange(1, sim::kLab1Variants)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OpenLoopSquare)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
