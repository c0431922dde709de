// foglab lab2 — the whole of lab 2 in one command: for each gyro the
// constant-temperature run (Y1, T1) and the ramp run (Y2, T2), analysed,
// drawn and tabulated as the lab manual asks (report/lab2.h). With no FILE it
// generates a variant (sim/lab2_variants.h) and shows its answer key.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis_output.h"
#include "analyze_command.h"
#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/io/channels.h"
#include "foglab/io/writer.h"
#include "foglab/model/analysis.h"
#include "foglab/report/lab2.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/lab2_variants.h"

namespace foglab::cli {
namespace {

struct Lab2Command {
  std::vector<std::string> files;
  int variant = 1;
  std::uint64_t seed = sim::kLab2DefaultSeed;
  std::string out = "lab2-report";
  std::string temp_degree = "2";  // the manual's step 2.3: polyfit(T, Y, 2)
  bool no_answers = false;
  bool no_plots = false;
  std::string lang = "en";
  Language language = Language::en;  // from lang, before the run
  std::optional<double> hours;  // hidden: shorter generated runs (tests)
  TitleOptions title;
};

/// One run to analyse: the record and what the report needs besides.
struct PendingRun {
  report::Lab2Run run;
  std::vector<double> rate_deg_h;
  std::vector<double> temperature_c;
  std::vector<Gap> gaps;  ///< of the rate's time axis
  double sample_rate_hz = 0.0;
  AnalysisJsonInput json;
  std::string stem;  ///< output file names: "<stem>.json", "<stem>_allan.csv"
};

/// A file written at the end (every output is rendered before any is written).
struct Output {
  std::string name;
  std::string text;
};

constexpr std::array<const char*, 2> kRateNames = {"Y1", "Y2"};  // their temperatures: io/channels.h
constexpr std::array<report::Lab2Condition, 2> kConditions = {report::Lab2Condition::constant,
                                                              report::Lab2Condition::ramp};

/// "FOG1" from "…/FOG1_3.mat"; the stem when it has no '_'.
std::string gyro_name(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  const std::size_t underscore = stem.find('_');
  return underscore == std::string::npos || underscore == 0 ? stem : stem.substr(0, underscore);
}

/// A generated gyro's two recordings, for its MAT file in the lab's layout.
struct GeneratedFile {
  std::string name;  ///< "FOG1_1.mat"
  std::array<sim::Recording, 2> runs;
};

/// Generates the variant's four runs (and keeps the data for the MAT files).
std::vector<PendingRun> generated_runs(const Lab2Command& c, std::vector<GeneratedFile>& files) {
  const sim::Lab2Variant v = sim::lab2_variant(c.variant, lab2_options(c.seed, c.hours));
  std::vector<PendingRun> runs;
  for (const sim::Lab2Gyro& g : v.gyros) {
    files.push_back({g.file_name, {}});
    for (std::size_t k = 0; k < 2; ++k) {
      const sim::Lab2Run& r = g.runs[k];
      progress(fmt::format("generating {} {} ({:.3g} h at {} Hz)", g.file_name, r.rate_name,
                           r.generator.duration_s / 3600.0, r.generator.sample_rate_hz));
      files.back().runs[k] = sim::generate(g.model, r.temperature, r.generator);
      const sim::Recording& rec = files.back().runs[k];
      PendingRun p;
      p.run.gyro = g.name;
      p.run.condition = kConditions[k];
      p.run.input.title =
          report::lab2_run_title(g.name, kConditions[k], g.file_name, r.rate_name, c.language);
      p.run.input.file_name = g.file_name;
      p.run.input.channel = r.rate_name;
      p.run.input.temperature_channel = r.temperature_name;
      if (!c.no_answers) p.run.truth = report::lab2_truth(g, r);
      p.rate_deg_h = rec.rate_deg_h;
      p.temperature_c = rec.temperature_c;
      p.sample_rate_hz = rec.sample_rate_hz;
      p.json.input = {{"path", g.file_name},
                      {"channel", r.rate_name},
                      {"sample_rate_hz", rec.sample_rate_hz},
                      {"sample_rate_source", "generated (foglab lab2 --variant)"},
                      {"variant", c.variant},
                      {"seed", c.seed}};
      p.json.temperature_channel = r.temperature_name;
      p.stem =
          fmt::format("{}_{}", std::filesystem::path(g.file_name).stem().string(), r.rate_name);
      runs.push_back(std::move(p));
    }
  }
  return runs;
}

/// Reads the lab's files: Y1/T1 (constant temperature) and Y2/T2 (ramp) of
/// each, whichever are present (at least one).
std::vector<PendingRun> file_runs(const Lab2Command& c) {
  std::vector<PendingRun> runs;
  for (const std::string& path : c.files) {
    if (io::is_stream(path)) {
      throw UsageError(
          fmt::format("'{}' is read once (standard input, a FIFO or a device), "
                      "and lab2 reads each file's runs and temperatures in turn: "
                      "save it to a file",
                      path));
    }
    // Every variable of the file, usable or not (a char or complex Y1 is
    // not a channel, but the reader says why when it is asked for it).
    const std::vector<std::string> variables = io::list_variables(path);
    auto present = [&](std::string_view name) {
      return std::find(variables.begin(), variables.end(), name) != variables.end();
    };
    io::ReadOptions read;
    read.max_magnitude = io::kMaxSampleMagnitude;  // 1e308 would overflow the statistics
    read.max_samples = default_max_samples();
    auto read_channel = [&](const char* name, std::optional<double> sample_rate_hz) {
      read.channel = name;
      read.sample_rate_hz = sample_rate_hz;
      io::Series s = io::read_series(path, read);  // a wrong class: the reader's DataError
      for (const Message& m : s.notes) note(m.text());
      return s;
    };
    if (!present(kRateNames[0]) && !present(kRateNames[1])) {
      throw DataError(fmt::format(
          "'{}': no Y1 or Y2 variable (the lab's layout is f, t, Y1, Y2, T1, T2); it has {}", path,
          variables.empty() ? std::string("none") : io::list_names(variables)));
    }
    for (std::size_t k = 0; k < 2; ++k) {
      if (!present(kRateNames[k])) {
        note(fmt::format("'{}' has no {}: its {} run is left out", path, kRateNames[k],
                         report::to_string(kConditions[k])));
        continue;
      }
      progress(fmt::format("reading '{}' {}", path, kRateNames[k]));
      io::Series rate = read_channel(kRateNames[k], std::nullopt);
      PendingRun p;
      p.run.gyro = gyro_name(path);
      p.run.condition = kConditions[k];
      p.run.input.title = report::lab2_run_title(p.run.gyro, kConditions[k],
                                                 std::filesystem::path(path).filename().string(),
                                                 rate.channel, c.language);
      p.run.input.file_name = path;
      p.run.input.channel = rate.channel;
      p.json.input = input_json(rate);
      const std::string temperature = io::paired_temperature_names(kRateNames[k]).front();
      if (present(temperature)) {
        io::Series t = read_channel(temperature.c_str(), rate.sample_rate_hz);
        if (t.values.size() != rate.values.size()) {
          throw DataError(
              fmt::format("'{}': {} has {} samples but {} has {}; they must be sampled together",
                          path, rate.channel, rate.values.size(), t.channel, t.values.size()));
        }
        p.temperature_c = std::move(t.values);
        p.run.input.temperature_channel = temperature;
        p.json.temperature_channel = temperature;
      } else {
        const std::string text =
            fmt::format("'{}' has no {}: the systematic part of {} is a constant (the record mean)",
                        path, temperature, rate.channel);
        note(text);
        p.run.input.notes.push_back(Message::verbatim(text));
        p.json.notes.push_back(text);
      }
      p.sample_rate_hz = rate.sample_rate_hz;
      p.rate_deg_h = std::move(rate.values);
      p.gaps = std::move(rate.gaps);
      p.stem = fmt::format("{}_{}", std::filesystem::path(path).stem().string(), rate.channel);
      runs.push_back(std::move(p));
    }
  }
  return runs;
}

std::string intro_text(const Lab2Command& c, const std::vector<report::Lab2Run>& runs) {
  std::string files;
  for (const report::Lab2Run& r : runs) {
    if (files.find(r.input.file_name) == std::string::npos) {
      files += (files.empty() ? "" : ", ") + r.input.file_name;
    }
  }
  const Message intro =
      c.files.empty() ? Message(Text::lab2_intro_generated, c.variant, c.seed, files,
                                c.no_answers ? Message() : Message(Text::lab2_intro_answer_key))
                      : Message(Text::lab2_intro_files, files);
  return intro.text(c.language) + Message(Text::lab2_intro_method).text(c.language);
}

void run(const Lab2Command& c) {
  if (c.variant < 1 || c.variant > sim::kLab2Variants) {
    throw UsageError(
        fmt::format("--variant {}: the lab has variants 1 to {}", c.variant, sim::kLab2Variants));
  }
  model::AnalysisOptions options;
  options.systematic.degree = parse_temp_degree(c.temp_degree);
  // Made first, so a bad --out is said before the work; filled at the end.
  OutputFolder folder("--out", c.out);

  std::vector<Output> outputs;
  std::vector<GeneratedFile> generated;
  std::vector<PendingRun> pending = c.files.empty() ? generated_runs(c, generated) : file_runs(c);

  std::vector<report::Lab2Run> runs;
  for (std::size_t k = 0; k < pending.size(); ++k) {
    PendingRun& p = pending[k];
    const double fs = p.sample_rate_hz;
    progress(fmt::format("[{}/{}] analysing {}", k + 1, pending.size(), p.run.input.title));
    p.run.input.preview = report::preview_record(p.rate_deg_h, p.temperature_c, fs, 2000, p.gaps);
    if (p.temperature_c.empty()) p.run.input.record_mean_deg_h = compensated_mean(p.rate_deg_h);
    p.json.record_mean_deg_h = p.run.input.record_mean_deg_h.value_or(0.0);
    try {
      p.run.result = model::analyze(p.rate_deg_h, p.temperature_c, fs, options, p.gaps);
    } catch (const DataError& e) {
      throw DataError(
          fmt::format("'{}' {}: {}", p.run.input.file_name, p.run.input.channel, e.what()));
    } catch (const UsageError& e) {
      throw UsageError(
          fmt::format("'{}' {}: {}", p.run.input.file_name, p.run.input.channel, e.what()));
    }
    p.rate_deg_h = {};
    p.temperature_c = {};
    p.json.temp_degree = c.temp_degree;
    outputs.push_back({p.stem + ".json", json_text(analysis_json(p.run.result, p.json, options))});
    outputs.push_back({p.stem + "_allan.csv", analysis_csv(p.run.result)});
    runs.push_back(std::move(p.run));
  }

  progress(fmt::format("drawing the plots of {} runs", runs.size()));
  report::ReportOptions report_options;
  report_options.plots = !c.no_plots;
  report_options.language = c.language;
  report_options.title_block =
      title_block(c.title, 2, c.files.empty() ? std::optional<int>(c.variant) : std::nullopt);
  const std::string title = c.files.empty() ? Message(Text::lab2_title, c.variant).text(c.language)
                                            : Message(Text::lab2_title_files).text(c.language);
  const report::Lab2Report rep =
      report::make_lab2_report(runs, title, intro_text(c, runs), report_options);
  if (rep.plots_skipped) note(rep.plots_note);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    outputs.push_back({pending[k].stem + "_imu.yaml", rep.runs[k].kalibr_yaml});
  }
  outputs.push_back({"report.html", rep.html});
  outputs.push_back({"report.md", rep.markdown});
  outputs.push_back({"lab2_table.csv", rep.csv});

  // Everything is rendered: now write (each file atomically).
  for (const GeneratedFile& f : generated) {
    const sim::Recording& constant = f.runs[0];
    const sim::Recording& ramp = f.runs[1];
    const double fs = constant.sample_rate_hz;
    const std::vector<io::NamedVector> vars = {
        {"f", {&fs, 1}},         {"t", constant.time_s},         {"Y1", constant.rate_deg_h},
        {"Y2", ramp.rate_deg_h}, {"T1", constant.temperature_c}, {"T2", ramp.temperature_c}};
    io::write_mat(folder.file(f.name), vars);
  }
  for (const Output& o : outputs) write_text_file(folder.file(o.name), o.text);
  folder.commit();

  std::cout << rep.markdown_summary;
  std::cout << fmt::format(
      "Report: {}\n(also in '{}': report.md, lab2_table.csv, and for each run its analysis "
      "<file>_<channel>.json, Allan table _allan.csv and Kalibr _imu.yaml{})\n",
      folder.final_file("report.html"), c.out,
      generated.empty() ? "" : "; the generated data in the lab's layout");
}

}  // namespace

std::function<void()> register_lab2(CLI::App& app) {
  auto c = std::make_shared<Lab2Command>();
  CLI::App* cmd = app.add_subcommand(
      "lab2",
      "the whole of lab 2: each gyro's constant-temperature (Y1, T1) and ramp (Y2, T2) runs "
      "analysed, the lab's table, classes and an HTML report with plots; no FILE: variant 1 "
      "generated on the fly");
  auto* files = cmd->add_option("FILE", c->files,
                                "the lab's MAT files (FOG1_k.mat, FOG2_k.mat: f, t, Y1, Y2, T1, "
                                "T2); none: generate --variant");
  auto* variant = cmd->add_option("--variant", c->variant,
                                  "variant 1-6 of the generated lab data (foglab lab2-data)")
                      ->capture_default_str();
  variant->excludes(files);
  cmd->add_option("--seed", c->seed, "seed of the generated data (as foglab lab2-data)")
      ->capture_default_str()
      ->excludes(files)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", c->out,
                  "directory for report.html, report.md, lab2_table.csv and each run's JSON, "
                  "CSV and imu.yaml (created if needed)")
      ->capture_default_str();
  cmd->add_option("--temp-degree", c->temp_degree,
                  "degree of the temperature polynomial removed: 2 (the manual's polyfit(T, Y, "
                  "2), with the criterion's verdict beside it), 0, 1, 3, or auto (the "
                  "criterion's degree, as analyze does)")
      ->capture_default_str();
  cmd->add_flag("--no-answers", c->no_answers,
                "generated data: leave the answer key out of the report");
  cmd->add_flag("--no-plots", c->no_plots, "write the report without plots (no gnuplot)");
  cmd->add_option("--lang", c->lang,
                  "the report's language: en, or ru (the lab manual's terms and units; the "
                  "CSV and JSON stay English)")
      ->capture_default_str();
  add_title_options(cmd, c->title);
  cmd->add_option("--hours", c->hours, "")->group("");  // hidden: shorter generated runs
  return [c] {
    c->language = language_from_string(c->lang);
    run(*c);
  };
}

}  // namespace foglab::cli
