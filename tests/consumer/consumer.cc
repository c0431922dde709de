// The consumer project's program: one call into each of foglab's libraries
// (io, stats, sim, model, report) through the installed headers, each
// result checked; exit 0 only when every one is as expected.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/io/sample.h"
#include "foglab/model/analysis.h"
#include "foglab/report/report.h"
#include "foglab/sim/generator.h"
#include "foglab/stats/allan.h"

namespace {

int failures = 0;

void expect(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
  if (!ok) ++failures;
}

}  // namespace

int main() {
  using namespace foglab;
  try {
    // io: the built-in sample (10 Hz, four hours).
    const io::Series sample = io::builtin_sample();
    expect(sample.sample_rate_hz == 10.0 && sample.values.size() == 144000,
           "io::builtin_sample() is 144000 samples at 10 Hz");

    // stats: its OADEV on the octave grid falls at short tau (white noise).
    const stats::AllanResult allan =
        stats::allan_deviation(sample.values, sample.sample_rate_hz, InputKind::rate);
    expect(allan.dev.size() > 5 && allan.dev[1] < allan.dev[0],
           "stats::allan_deviation() falls from tau0 to 2 tau0");

    // sim: one hour of white noise N = 6 deg/h/sqrt(Hz) at 10 Hz.
    sim::ErrorModel truth;
    truth.noise.N = 6.0;
    sim::GeneratorOptions options;
    options.sample_rate_hz = 10.0;
    options.duration_s = 3600.0;
    sim::Recording recording = sim::generate(truth, sim::TemperatureProfile{}, options);
    expect(recording.rate_deg_h.size() == 36000, "sim::generate() makes 36000 samples");

    // model: N is found within 5 % (its interval is about 1 % wide).
    const model::AnalysisResult result =
        model::analyze(recording.rate_deg_h, {}, recording.sample_rate_hz);
    expect(result.noise.N.status == model::TermStatus::resolved &&
               std::fabs(result.noise.N.value / 6.0 - 1.0) < 0.05,
           "model::analyze() finds N = " + std::to_string(result.noise.N.value) +
               " deg/h/sqrt(Hz) (truth 6)");

    // report: the Markdown summary names the record.
    report::ReportInput input;
    input.file_name = "consumer";
    const std::string summary = report::markdown_summary(result, input);
    expect(summary.find("consumer") != std::string::npos, "report::markdown_summary() titles it");
  } catch (const std::exception& e) {
    std::printf("FAILED: %s\n", e.what());
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
