// foglab analyze — the whole identification of a static recording (lab 2):
// temperature polynomial, Allan deviation and PSD of the residual, the
// noise-model fit with intervals, the lab's graphical readings, the random
// bias question and the accuracy class. The work is model::analyze(); this
// file reads the rate and its temperature, and writes what comes back.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis_output.h"
#include "analyze_command.h"
#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/language.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/channels.h"
#include "foglab/model/analysis.h"
#include "foglab/report/report.h"
#include "foglab/stats/tau_grid.h"

namespace foglab::cli {

int parse_temp_degree(const std::string& text) {
  if (text == "auto") return -1;
  if (text.size() == 1 && text[0] >= '0' && text[0] <= '3') return text[0] - '0';
  throw UsageError(
      fmt::format("--temp-degree '{}': expected auto, 0, 1, 2 or 3 (the degree of the "
                  "temperature polynomial)",
                  text));
}

/// --temp where no second channel can be read (checked before reading).
void check_temperature_option(const AnalyzeCommand& c) {
  if (c.temp_channel.empty()) return;
  if (c.input.path.empty()) {
    throw UsageError(fmt::format(
        "--temp {}: the built-in sample has no temperature channel (its only channel is Y1)",
        c.temp_channel));
  }
  if (io::is_stream(c.input.path)) {
    throw UsageError(fmt::format(
        "--temp {}: {} is read once (standard input, a FIFO or a device), so a temperature "
        "cannot be read from it too; save the data to a file",
        c.temp_channel, c.input.path == "-" ? "standard input" : "'" + c.input.path + "'"));
  }
}

Temperature load_temperature(const AnalyzeCommand& c, const io::Series& series,
                             std::vector<std::string>& notes) {
  const std::string& path = c.input.path;
  auto tell = [&](const std::string& text) {
    note(text);
    notes.push_back(text);
  };
  if (path.empty()) {
    tell(
        "the built-in sample has no temperature: the systematic part is a constant (the "
        "record mean)");
    return {};
  }
  if (io::is_stream(path)) {
    tell(
        fmt::format("data from {} (read once): no temperature read, the systematic part is a "
                    "constant (the record mean)",
                    path == "-" ? "standard input" : "the stream '" + path + "'"));
    return {};
  }

  // A variable the file holds that is no channel (a char or complex T1):
  // reading it gives the reader's message saying why it cannot be used.
  auto unusable = [&](const std::string& wanted) {
    return wanted != series.channel && std::find(series.variables.begin(), series.variables.end(),
                                                 wanted) != series.variables.end();
  };
  std::string name;
  if (!c.temp_channel.empty()) {
    const bool index = std::all_of(c.temp_channel.begin(), c.temp_channel.end(),
                                   [](unsigned char ch) { return std::isdigit(ch) != 0; });
    const auto found =
        io::find_channel(series.available_channels, c.temp_channel, io::NameMatch::ignore_case);
    if (!found && !index && unusable(c.temp_channel)) {
      name = c.temp_channel;
    } else if (!found && !index) {
      throw UsageError(fmt::format("--temp {}: '{}' has no channel '{}'; its channels are {}",
                                   c.temp_channel, path, c.temp_channel,
                                   io::list_names(series.available_channels)));
    }
    if (name.empty()) name = found ? *found : c.temp_channel;
  } else {
    const std::vector<std::string> wanted = io::paired_temperature_names(series.channel);
    for (const auto& w : wanted) {
      // The lab's T1, T2, T exactly; generate's "temperature" in any case.
      const auto found =
          io::find_channel(series.available_channels, w,
                           w == "temperature" ? io::NameMatch::ignore_case : io::NameMatch::exact);
      if (found && *found != series.channel) {
        name = *found;
        break;
      }
    }
    for (const auto& w : wanted) {
      if (name.empty() && unusable(w)) name = w;
    }
    if (name.empty()) {
      tell(
          fmt::format("no temperature channel {} in '{}' (channels: {}): the systematic part is a "
                      "constant (the record mean); name one with --temp",
                      wanted.empty() ? std::string("paired with channel " + series.channel)
                                     : fmt::format("{}", fmt::join(wanted, " or ")),
                      path, io::list_names(series.available_channels)));
      return {};
    }
  }
  if (name == series.channel) {
    throw UsageError(
        fmt::format("--temp {}: the temperature cannot be the rate channel itself", name));
  }

  progress(fmt::format("reading temperature '{}' from '{}'", name, path));
  InputOptions input = c.input;
  input.units = "deg/h";  // the rate's unit (an IMU's list of them) is not the temperature's
  io::ReadOptions read = read_options(input);
  read.channel = name;
  read.sample_rate_hz = series.sample_rate_hz;  // the rate's, already checked
  read.unit = RateUnit::deg_per_hour;           // identity: degC stay degC
  read.nan_is_missing = true;                   // a NaN temperature leaves its row out
  io::Series t = io::read_series(path, read);
  for (const Message& m : t.notes) note(m.text());
  if (t.values.size() != series.values.size()) {
    throw DataError(fmt::format(
        "'{}': the rate channel {} has {} samples but the temperature channel {} has {}; "
        "they must be sampled together",
        path, series.channel, series.values.size(), t.channel, t.values.size()));
  }
  return {t.channel, std::move(t.values)};
}

double max_missing_share_of(double percent, std::string_view option) {
  if (!(percent >= 0.0 && percent <= 10.0)) {
    throw UsageError(fmt::format(
        "{} must lie in [0, 10] (the share of an Allan cluster's samples that may be missing "
        "across a gap, %; 0: only the stretches between gaps), got {}",
        option, percent));
  }
  return percent / 100.0;
}

model::AnalysisOptions checked_analysis_options(const AnalyzeCommand& c) {
  const RunPath inputs[] = {{"FILE", c.input.path}};
  const RunPath outputs[] = {{"--json", c.json_path},
                             {"--csv", c.csv_path},
                             {"--report", c.report_path},
                             {"--kalibr", c.kalibr_path}};
  check_outputs(inputs, outputs);
  model::AnalysisOptions options;
  options.systematic.degree = parse_temp_degree(c.temp_degree);
  options.grid = parse_taus_option(c.taus, c.input.path);
  options.max_missing_share = max_missing_share_of(c.max_missing_percent, "--max-missing-percent");
  check_temperature_option(c);
  return options;
}

ChannelAnalysis analyse_series(const AnalyzeCommand& c, io::Series series,
                               const model::AnalysisOptions& options, bool preview,
                               bool read_temperature) {
  ChannelAnalysis a;
  std::vector<std::string> notes;
  Temperature temperature;
  if (read_temperature) {
    // A row is missing when its rate or its temperature is NaN (load_input
    // left the NaN rows in for this).
    temperature = load_temperature(c, series, notes);
    leave_missing_samples(series, temperature.channel.empty() ? nullptr : &temperature.values_c);
  }
  if (temperature.channel.empty() && c.temp_degree != "auto") {
    const std::string text =
        fmt::format("--temp-degree {} ignored: there is no temperature", c.temp_degree);
    note(text);
    notes.push_back(text);
  }
  const std::size_t samples = series.values.size();
  const double record_mean_deg_h =
      temperature.channel.empty() ? compensated_mean(series.values) : NAN;

  // The report's time plots need the record, which the analysis consumes.
  report::ReportInput& report_input = a.report_input;
  report_input.file_name = series.path;
  report_input.channel = series.channel;
  report_input.temperature_channel = temperature.channel;
  report_input.input_unit = c.input.units;
  for (const std::string& text : notes) report_input.notes.push_back(Message::verbatim(text));
  if (temperature.channel.empty()) report_input.record_mean_deg_h = record_mean_deg_h;
  if (preview) {
    report_input.preview = report::preview_record(series.values, temperature.values_c,
                                                  series.sample_rate_hz, 2000, series.gaps);
  }

  progress(fmt::format("analysing {} samples", samples));
  a.result = naming_the_input(series, [&] {
    return model::analyze(series.values, temperature.values_c, series.sample_rate_hz, options,
                          series.gaps);
  });
  series.values.clear();
  series.values.shrink_to_fit();

  AnalysisJsonInput& json_input = a.json_input;
  json_input.input = input_json(series);
  json_input.temperature_channel = temperature.channel;
  json_input.record_mean_deg_h = record_mean_deg_h;
  json_input.units = c.input.units;
  json_input.temp_degree = c.temp_degree;
  json_input.taus = c.taus;
  json_input.notes = std::move(notes);
  return a;
}

namespace {

void run(const AnalyzeCommand& c) {
  const Language language = language_from_string(c.language);
  if (const auto channels = imu_channels(c)) {
    if (language != Language::en) {
      throw UsageError(fmt::format(
          "--lang {}: the IMU form of analyze (several channels, an accelerometer, a ROS bag) "
          "writes English only; name one gyroscope channel with --channel",
          c.language));
    }
    run_imu_analysis(c, *channels);
    return;
  }
  const model::AnalysisOptions options = checked_analysis_options(c);
  const ChannelAnalysis a =
      analyse_series(c, load_input(c.input, true), options, !c.report_path.empty(), true);
  const model::AnalysisResult& result = a.result;
  const report::ReportInput& report_input = a.report_input;

  // Render everything first, then write: a failure never leaves half the outputs.
  const std::string json =
      c.json_path.empty() ? "" : json_text(analysis_json(result, a.json_input, options));
  const std::string csv = c.csv_path.empty() ? "" : analysis_csv(result);
  std::string html, yaml;
  if (!c.report_path.empty()) {
    progress("drawing the report's plots");
    report::ReportOptions report_options;
    report_options.language = language;
    const report::Report rep = report::make_report(result, report_input, report_options);
    if (rep.plots_skipped) note(rep.plots_note);
    html = report::html_document(rep);
  }
  if (!c.kalibr_path.empty()) yaml = report::kalibr_imu_yaml(result, report_input);
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (!c.report_path.empty()) write_text_file(c.report_path, html);
  if (!c.kalibr_path.empty()) write_text_file(c.kalibr_path, yaml);
  if (c.json_path != "-" && c.csv_path != "-") {
    std::cout << report::markdown_summary(result, report_input, language);
  }
}

}  // namespace

std::function<void()> register_analyze(CLI::App& app) {
  auto c = std::make_shared<AnalyzeCommand>();
  CLI::App* cmd = app.add_subcommand(
      "analyze",
      "identify a static recording: temperature polynomial, OADEV and PSD of the residual, "
      "noise model (N, B, K, R, Q, Gauss-Markov) with 95 % intervals, random bias, class");
  add_input_options(*cmd, c->input, /*file_optional=*/true);
  cmd->add_option("--channels", c->channels,
                  "several channels in one run, in parallel: names or 1-based indexes "
                  "(gx,gy,gz,ax,ay,az), or 'all'; default with no --channel: every channel whose "
                  "name says gyro or accel (gyro_x, ax, ...) when there are two or more");
  cmd->add_option("--topic", c->topic,
                  "ROS bag: the sensor_msgs/Imu topic (default: the only one)");
  cmd->add_option("--temp", c->temp_channel,
                  "temperature channel [degC]; default: the one paired with the rate channel "
                  "(Y1 -> T1, Y2 -> T2; 'rate' -> T or temperature)");
  cmd->add_option("--temp-degree", c->temp_degree,
                  "degree of the temperature polynomial: auto (information criterion), 0, 1, 2 "
                  "(the lab's polyfit) or 3")
      ->capture_default_str();
  cmd->add_option("--taus", c->taus,
                  "reported Allan tau grid: octave, decade, all, N-per-decade, or averaging "
                  "times in s (1,10,100); the noise fit always uses the octave grid")
      ->capture_default_str();
  cmd->add_option("--max-missing-percent", c->max_missing_percent,
                  "Allan terms across a gap: the most of a cluster's samples that may be missing "
                  "[%] (each cluster's mean over the samples it has), 0 to 10; 0: only the "
                  "contiguous stretches (Stable32's rule)")
      ->capture_default_str();
  cmd->add_option("--json", c->json_path, "write the results as JSON ('-' for stdout)");
  cmd->add_option("--csv", c->csv_path,
                  "write the Allan table of the residual with the fitted model as CSV ('-' for "
                  "stdout)");
  cmd->add_option("--report", c->report_path,
                  "write a self-contained HTML report (gnuplot SVG plots: record, bias against "
                  "temperature, PSD, Allan deviation with the fitted model)");
  cmd->add_option("--kalibr", c->kalibr_path,
                  "write Kalibr's imu.yaml for the gyroscope (noise density rad/s/sqrt(Hz), "
                  "random walk rad/s^2/sqrt(Hz))");
  cmd->add_option("--lang", c->language,
                  "the report's and the terminal summary's language: en, or ru (the lab manual's "
                  "terms and units); one gyroscope channel only")
      ->capture_default_str();
  return [c] { run(*c); };
}

}  // namespace foglab::cli
