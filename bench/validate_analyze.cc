// The accuracy study of issue 4 (docs/validation.md): recordings made by the
// generator with known parameters, analysed by model::analyze(), compared
// with the truth over many seeds.
//
// Scenarios:
//   * "class": one archetype per Table 1 class (N and B from the class's
//     middle, sim/presets), each with no random bias, a Wiener random bias
//     and a Gauss-Markov random bias, with a constant (thermostat) and a
//     10 degC ramp temperature carrying a temperature dependence;
//   * "lab2": the twelve runs of the lab-2 variant sets (sim/lab2_variants),
//     with a fresh seed per repetition.
//
// A term is "visible" when it carries at least half the model's Allan
// variance over at least two octaves of the usable tau range
// [1/fs, duration/10] (the condition); the goals apply to those.
//
//   ./build/bench/validate_analyze [--seeds 20] [--filter TEXT] [--penalty P] [--inflation F]
//                                  [--window W] [--csv runs.csv]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "foglab/model/analysis.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/lab2_variants.h"
#include "foglab/sim/presets.h"

namespace {

using foglab::model::TermStatus;

struct Scenario {
  std::string set, name, process, temperature;
  foglab::sim::ErrorModel model;
  foglab::sim::TemperatureProfile profile;
  double fs = 10.0, duration_s = 3 * 3600.0;
  std::uint64_t stream = 0;
};

// The parameters compared, with the truth's and the estimate's value.
constexpr int kParamCount = 7;

double truth_of(const foglab::sim::ErrorModel& m, int p) {
  const foglab::NoiseParameter& parameter = foglab::kNoiseParameters[static_cast<std::size_t>(p)];
  // A Tc without its sigma is no term.
  if (parameter.term == foglab::NoiseTerm::gauss_markov && !(m.noise.gm_sigma > 0)) return 0.0;
  return m.noise.*parameter.value;
}

const foglab::model::ParameterEstimate& estimate_of(const foglab::model::NoiseFitResult& r, int p) {
  return r.estimate(foglab::kNoiseParameters[static_cast<std::size_t>(p)]);
}

// The truth's term behind parameter p (Tc goes with the Gauss-Markov term).
foglab::NoiseTerm term_of(int p) {
  return foglab::kNoiseParameters[static_cast<std::size_t>(p)].term;
}

std::string process_of(const foglab::sim::ErrorModel& m) {
  if (m.noise.gm_sigma > 0) return "gauss_markov";
  if (m.noise.K > 0) return "wiener";
  return "none";
}

std::vector<Scenario> class_scenarios() {
  std::vector<Scenario> out;
  const char* classes[] = {"strategic", "navigation", "intermediate", "tactical", "consumer"};
  std::uint64_t stream = 100;
  for (const char* cls : classes) {
    const foglab::sim::Preset& preset = foglab::sim::find_preset(fmt::format("class-{}", cls));
    for (const char* process : {"none", "wiener", "gauss_markov"}) {
      for (const char* temperature : {"const", "ramp"}) {
        Scenario s;
        s.set = "class";
        s.fs = 10.0;
        s.duration_s = 12 * 3600.0;
        s.model = preset.model;
        foglab::NoiseModel& n = s.model.noise;
        s.model.bias = 5.0 * n.B;
        const double plateau = foglab::allan_variance(n, foglab::NoiseTerm::flicker, 1.0);
        const double t_usable = s.duration_s / 10.0;
        if (std::string(process) == "wiener") {
          // The random walk equals the flicker plateau at T/160, so it
          // carries most of the variance over the last four octaves.
          n.K = std::sqrt(3.0 * plateau / (t_usable / 16.0));
        } else if (std::string(process) == "gauss_markov") {
          // Tc at T/100 of the usable range's end; its hump (0.433 sigma^2
          // at tau = 1.89 Tc) three times the flicker plateau.
          n.gm_tc = t_usable / 20.0;
          n.gm_sigma = std::sqrt(3.0 * plateau / 0.433);
        }
        if (std::string(temperature) == "ramp") {
          s.profile = foglab::sim::parse_temperature("ramp:10@20");
          s.model.temp_coefs = {30.0 * n.B, 0.5 * n.B};
        } else {
          s.profile = foglab::sim::parse_temperature("const:25");
        }
        s.name = fmt::format("{}/{}/{}", cls, process, temperature);
        s.process = process;
        s.temperature = temperature;
        s.stream = stream++;
        out.push_back(s);
      }
    }
  }
  return out;
}

std::vector<Scenario> lab2_scenarios(std::uint64_t seed) {
  std::vector<Scenario> out;
  foglab::sim::Lab2Options options;
  options.seed = seed;
  for (const auto& variant : foglab::sim::lab2_variants(options)) {
    for (const auto& gyro : variant.gyros) {
      for (const auto& run : gyro.runs) {
        Scenario s;
        s.set = "lab2";
        s.name = fmt::format("lab2/{}/{}", gyro.file_name, run.rate_name);
        s.model = gyro.model;
        s.profile = run.temperature;
        s.fs = run.generator.sample_rate_hz;
        s.duration_s = run.generator.duration_s;
        s.stream = run.generator.stream;
        s.process = process_of(gyro.model);
        s.temperature = run.rate_name == "Y1" ? "const" : "ramp";
        out.push_back(s);
      }
    }
  }
  return out;
}

struct Outcome {
  std::string scenario, set, process, temperature, found_process;
  std::uint64_t seed = 0;
  double truth[kParamCount]{}, value[kParamCount]{}, low[kParamCount]{}, high[kParamCount]{};
  double octaves[kParamCount]{};
  TermStatus status[kParamCount]{};
  int degree = -1;
  double c1 = NAN, c1_se = NAN, c1_truth = NAN;
  std::string candidates;  // "terms:-2lnL:parameters;..." for decision studies
};

foglab::model::AnalysisOptions g_options;

Outcome run(const Scenario& s, std::uint64_t seed) {
  foglab::sim::GeneratorOptions g;
  g.sample_rate_hz = s.fs;
  g.duration_s = s.duration_s;
  g.seed = seed;
  g.stream = s.stream;
  foglab::sim::Recording rec = foglab::sim::generate(s.model, s.profile, g);
  foglab::model::AnalysisResult a =
      foglab::model::analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz, g_options);
  Outcome o;
  o.scenario = s.name;
  o.set = s.set;
  o.process = s.process;
  o.temperature = s.temperature;
  o.seed = seed;
  o.found_process = std::string(foglab::to_string(a.noise.random_bias_process));
  for (const auto& c : a.noise.candidates) {
    o.candidates +=
        fmt::format("{}{}:{:.4f}:{}", o.candidates.empty() ? "" : ";", foglab::to_string(c.terms),
                    c.criterion - g_options.noise_fit.penalty * c.parameters, c.parameters);
  }
  const double tau_min = 1.0 / s.fs, tau_max = s.duration_s / 10.0;
  for (int p = 0; p < kParamCount; ++p) {
    const auto& e = estimate_of(a.noise, p);
    o.truth[p] = truth_of(s.model, p);
    o.value[p] = e.value;
    o.low[p] = e.ci95_low;
    o.high[p] = e.ci95_high;
    o.status[p] = e.status;
    o.octaves[p] = o.truth[p] > 0
                       ? foglab::term_dominance_octaves(s.model.noise, term_of(p), tau_min, tau_max)
                       : 0.0;
  }
  if (a.systematic) {
    o.degree = a.systematic->degree;
    if (a.systematic->coefficients.size() > 1) {
      o.c1 = a.systematic->coefficients[1];
      o.c1_se = a.systematic->standard_errors[1];
    }
    o.c1_truth = s.model.temp_coefs.empty() ? 0.0 : s.model.temp_coefs[0];
  }
  return o;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Tally {
  std::vector<double> errors;  // |relative error| of visible terms (unresolved: 1)
  int visible = 0, covered = 0, resolved = 0;
  int absent_cases = 0, absent_resolved = 0;
};

void report(const std::vector<Outcome>& outcomes, const std::string& title) {
  std::map<std::string, std::vector<const Outcome*>> groups;
  for (const Outcome& o : outcomes) groups[o.scenario].push_back(&o);
  fmt::print("\n### {}\n\n", title);
  fmt::print(
      "| scenario | runs | N med/worst % | B med % | K med % | GM sigma med % | GM Tc med % | "
      "coverage % | decision % | false resolved | degree |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|\n");
  auto summarise = [](const std::vector<const Outcome*>& list) {
    std::array<Tally, kParamCount> t;
    int decisions = 0, decided_right = 0;
    std::map<int, int> degrees;
    for (const Outcome* o : list) {
      bool process_visible = false;
      for (int p = 0; p < kParamCount; ++p) {
        if (o->truth[p] > 0 && o->octaves[p] >= 2.0) {
          ++t[p].visible;
          const bool res = o->status[p] == TermStatus::resolved;
          t[p].resolved += res;
          t[p].errors.push_back(res ? std::fabs(o->value[p] / o->truth[p] - 1.0) : 1.0);
          t[p].covered += o->low[p] <= o->truth[p] && o->truth[p] <= o->high[p];
          if (p == 2 || p == 5) process_visible = true;
        } else if (o->truth[p] == 0) {
          ++t[p].absent_cases;
          t[p].absent_resolved += o->status[p] == TermStatus::resolved;
        }
      }
      if (process_visible || o->process == "none") {
        ++decisions;
        decided_right += o->found_process == o->process;
      }
      ++degrees[o->degree];
    }
    return std::tuple(t, decisions, decided_right, degrees);
  };
  auto cell = [](const Tally& t, bool worst) {
    if (t.visible == 0) return std::string("-");
    const double med = 100.0 * median(t.errors);
    if (!worst) return fmt::format("{:.1f}", med);
    return fmt::format("{:.1f}/{:.1f}", med,
                       100.0 * *std::max_element(t.errors.begin(), t.errors.end()));
  };
  std::array<Tally, kParamCount> total;
  int total_decisions = 0, total_right = 0;
  for (const auto& [name, list] : groups) {
    auto [t, decisions, right, degrees] = summarise(list);
    int visible = 0, covered = 0, absent = 0, false_resolved = 0;
    for (int p = 0; p < kParamCount; ++p) {
      visible += t[p].visible;
      covered += t[p].covered;
      absent += t[p].absent_cases;
      false_resolved += t[p].absent_resolved;
      total[p].errors.insert(total[p].errors.end(), t[p].errors.begin(), t[p].errors.end());
      total[p].visible += t[p].visible;
      total[p].covered += t[p].covered;
      total[p].resolved += t[p].resolved;
      total[p].absent_cases += t[p].absent_cases;
      total[p].absent_resolved += t[p].absent_resolved;
    }
    total_decisions += decisions;
    total_right += right;
    std::string deg;
    for (const auto& [d, count] : degrees) deg += fmt::format("{}:{} ", d, count);
    fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {}/{} | {}|\n", name, list.size(),
               cell(t[0], true), cell(t[1], false), cell(t[2], false), cell(t[5], false),
               cell(t[6], false), visible ? fmt::format("{:.0f}", 100.0 * covered / visible) : "-",
               decisions ? fmt::format("{:.0f}", 100.0 * right / decisions) : "-", false_resolved,
               absent, deg);
  }
  fmt::print("\nOverall ({} runs):\n\n", outcomes.size());
  fmt::print(
      "| parameter | visible cases | resolved % | median error % | worst error % | "
      "coverage % | absent cases | reported resolved % |\n|---|---|---|---|---|---|---|---|\n");
  for (int p = 0; p < kParamCount; ++p) {
    const Tally& t = total[p];
    fmt::print(
        "| {} | {} | {} | {} | {} | {} | {} | {} |\n",
        foglab::kNoiseParameters[static_cast<std::size_t>(p)].name, t.visible,
        t.visible ? fmt::format("{:.1f}", 100.0 * t.resolved / t.visible) : "-",
        t.visible ? fmt::format("{:.1f}", 100.0 * median(t.errors)) : "-",
        t.visible
            ? fmt::format("{:.1f}", 100.0 * *std::max_element(t.errors.begin(), t.errors.end()))
            : "-",
        t.visible ? fmt::format("{:.1f}", 100.0 * t.covered / t.visible) : "-", t.absent_cases,
        t.absent_cases ? fmt::format("{:.1f}", 100.0 * t.absent_resolved / t.absent_cases) : "-");
  }
  fmt::print("\nRandom-bias decision right: {}/{} ({:.1f} %)\n", total_right, total_decisions,
             total_decisions ? 100.0 * total_right / total_decisions : NAN);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Accuracy of foglab analyze against the generator's truth (docs/validation.md)",
               "validate_analyze"};
  int seeds = 20;
  std::string filter, csv_path;
  app.add_option("--seeds", seeds, "seeds per scenario")->check(CLI::Range(1, 100000));
  app.add_option("--filter", filter, "only scenarios whose name contains this");
  app.add_option("--penalty", g_options.noise_fit.penalty, "selection penalty per parameter")
      ->check(CLI::Range(0.0, 1e3));
  app.add_option("--inflation", g_options.noise_fit.correlation_inflation,
                 "correlation inflation of the Allan points")
      ->check(CLI::Range(1e-3, 1e3));
  app.add_option("--window", g_options.noise_fit.interval_window,
                 "criterion window of the candidates whose intervals are joined")
      ->check(CLI::Range(0.0, 1e3));
  app.add_option("--csv", csv_path, "write every run to this CSV file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help is not an error; anything else is a usage error
  }
  std::vector<Outcome> class_outcomes, lab_outcomes;
  const std::vector<Scenario> classes = class_scenarios();
  for (int seed = 1; seed <= seeds; ++seed) {
    for (const Scenario& s : classes) {
      if (!filter.empty() && s.name.find(filter) == std::string::npos) continue;
      class_outcomes.push_back(run(s, 1000 + static_cast<std::uint64_t>(seed)));
    }
    for (const Scenario& s : lab2_scenarios(5000 + static_cast<std::uint64_t>(seed))) {
      if (!filter.empty() && s.name.find(filter) == std::string::npos) continue;
      lab_outcomes.push_back(run(s, 5000 + static_cast<std::uint64_t>(seed)));
    }
    fmt::print(stderr, "\rseed {}/{}", seed, seeds);
  }
  fmt::print(stderr, "\n");
  if (!class_outcomes.empty()) report(class_outcomes, "Class archetypes (10 Hz, 12 h)");
  if (!lab_outcomes.empty()) report(lab_outcomes, "Lab-2 variant runs");
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "scenario,seed,process,found_process,degree,c1,c1_se,c1_truth";
    for (const foglab::NoiseParameter& p : foglab::kNoiseParameters)
      csv << fmt::format(",{0}_truth,{0},{0}_lo,{0}_hi,{0}_status,{0}_octaves", p.name);
    csv << ",candidates\n";
    for (const auto* list : {&class_outcomes, &lab_outcomes}) {
      for (const Outcome& o : *list) {
        csv << fmt::format("{},{},{},{},{},{},{},{}", o.scenario, o.seed, o.process,
                           o.found_process, o.degree, o.c1, o.c1_se, o.c1_truth);
        for (int p = 0; p < kParamCount; ++p) {
          csv << fmt::format(",{},{},{},{},{},{:.2f}", o.truth[p], o.value[p], o.low[p], o.high[p],
                             foglab::model::to_string(o.status[p]), o.octaves[p]);
        }
        csv << "," << o.candidates << "\n";
      }
    }
  }
  return 0;
}
