// Generator throughput (issue 3): the full error model, every term on, at
// 100 Hz, end to end, with and without writing the rate as raw float64 to a
// temporary file through the block sink (foglab::io::RawFileWriter). Goal: >= 25e6 samples/s
// with writing on the 2-core lab machine. Items processed = samples.
//
//   ./build/bench/bench_generate [--benchmark_repetitions=3]
//   FOGLAB_BENCH_SAMPLES=1e7 ./build/bench/bench_generate   (shorter record)
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "foglab/io/writer.h"
#include "foglab/sim/generator.h"

namespace {

double bench_samples() {
  if (const char* text = std::getenv("FOGLAB_BENCH_SAMPLES")) return std::atof(text);
  return 1e8;
}

foglab::sim::ErrorModel full_model() {
  foglab::sim::ErrorModel m;
  m.noise.N = 0.3;
  m.noise.B = 0.05;
  m.noise.K = 0.01;
  m.noise.R = 1e-5;
  m.noise.Q = 0.02;
  m.noise.gm_sigma = 0.1;
  m.noise.gm_tc = 300.0;
  m.bias = 1.5;
  m.input_rate = 9.7;
  m.temp_coefs = {0.02, -0.001};
  return m;
}

foglab::sim::TemperatureProfile ramp() {
  foglab::sim::TemperatureProfile t;
  t.kind = foglab::sim::TemperatureKind::ramp;
  t.start_c = 20.0;
  t.span_c = 10.0;
  t.jitter_c = 0.01;
  return t;
}

foglab::sim::GeneratorOptions options() {
  foglab::sim::GeneratorOptions o;
  o.sample_rate_hz = 100.0;
  o.duration_s = bench_samples() / o.sample_rate_hz;
  o.seed = 42;
  return o;
}

void run(benchmark::State& state, bool write, int threads) {
  const int previous = omp_get_max_threads();
  if (threads > 0) omp_set_num_threads(threads);
  const auto model = full_model();
  const auto temperature = ramp();
  const auto opts = options();
  const std::string path =
      (std::filesystem::temp_directory_path() / fmt::format("foglab_bench_{}.f64", getpid())).string();
  std::int64_t samples = 0;
  for (auto _ : state) {
    // foglab's own raw writer (atomic, O_DIRECT where possible), as the CLI uses.
    std::optional<foglab::io::RawFileWriter> file;
    if (write) file.emplace(path, foglab::io::RawType::f64);
    double checksum = 0.0;
    foglab::sim::generate(model, temperature, opts, [&](const foglab::sim::Block& b) {
      if (file) {
        file->append(b.rate_deg_h);
      } else {
        checksum += b.rate_deg_h.back();
      }
      samples += static_cast<std::int64_t>(b.rate_deg_h.size());
    });
    if (file) file->commit();
    benchmark::DoNotOptimize(checksum);
  }
  if (write) std::filesystem::remove(path);
  state.SetItemsProcessed(samples);
  state.counters["threads"] = threads > 0 ? threads : omp_get_max_threads();
  omp_set_num_threads(previous);
}

void BM_GenerateFullModelWriteF64(benchmark::State& state) { run(state, true, 0); }
void BM_GenerateFullModelNoWrite(benchmark::State& state) { run(state, false, 0); }
void BM_GenerateFullModelWriteF64OneThread(benchmark::State& state) { run(state, true, 1); }
void BM_GenerateFullModelNoWriteOneThread(benchmark::State& state) { run(state, false, 1); }

BENCHMARK(BM_GenerateFullModelWriteF64)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_GenerateFullModelNoWrite)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_GenerateFullModelWriteF64OneThread)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK(BM_GenerateFullModelNoWriteOneThread)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
