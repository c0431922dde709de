// Example 3: the truth round trip through the library API. A static gyro
// recording is generated with a known error model (sim::generate), then
// identified (model::analyze), and each parameter is printed beside the
// value it was made with, with its 95 % interval.
//
//   ./build/examples/example_03_identify_generated [HOURS] [SEED]
//
// It says for each generated term whether the fit found it and whether its
// 95 % interval covers the truth (for one record a miss happens now and
// then: a 95 % interval misses one time in twenty), and at the end whether
// every generated term was found. Exit status 0 when it ran, 2 for a bad
// argument, 3 for data it could not analyse.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/noise_model.h"
#include "foglab/model/analysis.h"
#include "foglab/sim/generator.h"

namespace {

double positive_argument(const char* text, const char* what) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(value > 0.0) || !std::isfinite(value)) {
    throw foglab::UsageError(std::string(what) + " '" + text + "': expected a positive number");
  }
  return value;
}

int run(int argc, char** argv) {
  using namespace foglab;

  // A tactical-grade gyro: white noise, bias instability and a rate random
  // walk, sampled at 100 Hz; at constant temperature, so no systematic part.
  sim::ErrorModel truth;
  truth.noise.N = 3.0;                  // [deg/h/sqrt(Hz)]: ARW 0.05 deg/sqrt(h)
  truth.noise.B = 0.5;                  // [deg/h]: ADEV floor 0.664 B = 0.33 deg/h
  truth.noise.K = 0.05;                 // [deg/h/sqrt(s)]: ADEV K sqrt(tau/3), 1 deg/h at 20 min
  sim::TemperatureProfile temperature;  // constant 25 degC

  sim::GeneratorOptions options;
  options.sample_rate_hz = 100.0;
  options.duration_s = 3600.0 * (argc > 1 ? positive_argument(argv[1], "HOURS") : 4.0);
  options.seed = argc > 2 ? static_cast<std::uint64_t>(positive_argument(argv[2], "SEED")) : 1;

  sim::Recording recording = sim::generate(truth, temperature, options);
  std::printf("generated %zu samples at %g Hz (%g h)\n", recording.rate_deg_h.size(),
              recording.sample_rate_hz, options.duration_s / 3600.0);

  // No temperature given: the record is analysed as it is.
  const model::AnalysisResult result =
      model::analyze(recording.rate_deg_h, {}, recording.sample_rate_hz);
  std::printf("noise fit: %s (%s)\n\n", std::string(model::to_string(result.noise.status)).c_str(),
              result.noise.message.c_str());

  int generated = 0, found = 0;
  std::printf("%-9s %-16s %10s %10s %24s\n", "term", "unit", "truth", "estimate", "95 % interval");
  for (const NoiseParameter& p : kNoiseParameters) {
    const double true_value = truth.noise.*p.value;
    const model::ParameterEstimate& e = result.noise.estimate(p);
    const bool resolved = e.status == model::TermStatus::resolved;
    if (true_value == 0.0 && !resolved) continue;  // neither made nor found
    const char* verdict = "found, but not generated";
    if (true_value > 0.0) {
      ++generated;
      found += resolved ? 1 : 0;
      verdict = !resolved ? "missed"
                : e.ci95_low <= true_value && true_value <= e.ci95_high
                    ? "found, interval covers the truth"
                    : "found, interval misses the truth";
    }
    std::printf("%-9s %-16s %10.4g %10.4g   [%9.4g, %9.4g]  %s\n", std::string(p.name).c_str(),
                std::string(p.unit).c_str(), true_value, resolved ? e.value : 0.0, e.ci95_low,
                e.ci95_high, verdict);
  }
  std::printf("\nARW %.4g deg/sqrt(h), bias instability %.4g deg/h at %.4g s: %s class\n",
              result.arw_deg_sqrt_h, result.bias_instability_deg_h, result.bias_instability_tau_s,
              std::string(to_string(result.verdict.accuracy_class)).c_str());
  std::printf("%d of %d generated terms found\n", found, generated);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const foglab::UsageError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return foglab::kExitUsage;
  } catch (const foglab::DataError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return foglab::kExitData;
  }
}
