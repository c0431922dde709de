// foglab allan — one statistic of the Allan family with confidence intervals.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/time_error.h"

namespace foglab::cli {
namespace {

std::vector<std::string> alpha_methods(const stats::AllanResult& r) {
  std::vector<std::string> out;
  for (const stats::AlphaMethod& m : r.alpha_method) out.push_back(stats::to_string(m));
  return out;
}

struct AllanCommand {
  InputOptions input;
  std::string kind = "oadev";
  std::string taus = "octave";
  std::int64_t min_clusters = 10;
  std::string input_kind = "rate";
  bool no_ci = false;
  bool no_bias_correction = false;
  std::string noise_id = "foglab";
  std::string csv_path;
  std::string json_path;
};

/// The deviation's unit: the rate's (TDEV, TTOTDEV: times s); m/s^2 for an
/// accelerometer read in an acceleration unit.
std::string dev_unit(stats::AllanKind kind, Sensor sensor) {
  return in_sensor_units(stats::is_time_deviation(kind) ? "deg/h*s" : "deg/h", sensor);
}

Sensor sensor_of_input(const AllanCommand& c) {
  return sensor_of(parse_units_option(c.input.units, c.input.path));
}

nlohmann::json to_json(const stats::AllanResult& r, const io::Series& series,
                       const AllanCommand& c) {
  return {{"kind", std::string(stats::to_string(r.kind))},
          {"input", std::string(to_string(r.input))},
          {"unit", dev_unit(r.kind, sensor_of_input(c))},
          {"tau_s", r.tau_s},
          {"dev", numbers(r.dev)},
          {"n", r.n},
          {"m", r.m},
          {"alpha", r.alpha},
          {"alpha_method", alpha_methods(r)},
          {"edf", numbers(r.edf)},
          {"ci68_low", numbers(r.ci68_low)},
          {"ci68_high", numbers(r.ci68_high)},
          {"ci95_low", numbers(r.ci95_low)},
          {"ci95_high", numbers(r.ci95_high)},
          {"taus", c.taus},
          {"min_clusters", c.min_clusters},
          {"noise_id", c.noise_id},
          {"bias_correction", r.kind == stats::AllanKind::htotdev && !c.no_bias_correction},
          {"source", input_json(series)},
          {"foglab_version", std::string(version())}};
}

std::string to_csv(const stats::AllanResult& r, Sensor sensor) {
  const std::string base = sensor == Sensor::gyroscope ? "deg_h" : "m_s2";
  const std::string u = stats::is_time_deviation(r.kind) ? base + "_s" : base;
  std::string out = fmt::format(
      "tau_s,m,n,dev_{0},alpha,edf,ci68_low_{0},ci68_high_{0},ci95_low_{0},ci95_high_{0}\n", u);
  for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
    out += fmt::format("{:.10g},{},{},{},{},{},{},{},{},{}\n", r.tau_s[k], r.m[k], r.n[k],
                       csv_number(r.dev[k]), r.alpha[k], csv_number(r.edf[k]),
                       csv_number(r.ci68_low[k]), csv_number(r.ci68_high[k]),
                       csv_number(r.ci95_low[k]), csv_number(r.ci95_high[k]));
  }
  return out;
}

std::string to_table(const stats::AllanResult& r, const io::Series& series, Sensor sensor) {
  const std::string unit = dev_unit(r.kind, sensor);
  std::string out = fmt::format("{} of '{}' channel {} ({} samples at {} Hz, {})\n",
                                stats::to_string(r.kind), series.path, series.channel,
                                series.values.size(), series.sample_rate_hz, to_string(r.input));
  out += fmt::format("{:>12} {:>10} {:>14} {:>6} {:>14} {:>14}\n", "tau [s]", "n",
                     fmt::format("dev [{}]", unit), "alpha", "95% low", "95% high");
  for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
    out += fmt::format("{:>12.6g} {:>10} {:>14.6g} {:>6} {:>14.6g} {:>14.6g}\n", r.tau_s[k], r.n[k],
                       r.dev[k], r.alpha[k], r.ci95_low[k], r.ci95_high[k]);
  }
  return out;
}

// The command's tau grid and its record, checked to vary: what both the
// Allan family and the time error start from.
stats::TauGrid tau_grid_of(const AllanCommand& c) {
  stats::TauGrid grid = parse_taus_option(c.taus, c.input.path);
  grid.min_clusters = c.min_clusters;
  return grid;
}

io::Series load_varying_record(const AllanCommand& c, InputKind input) {
  io::Series series = load_input(c.input);
  naming_the_input(series, [&] {
    require_varying(series.values, input == InputKind::rate ? "deg/h" : "(deg/h)*s (phase)");
    return 0;
  });
  return series;
}

// MTIE and TIE rms: the same input, grid and outputs, a value per tau in the
// angle's unit and no intervals.
void run_time_error(const AllanCommand& c) {
  const stats::TimeErrorKind kind = stats::time_error_kind_from_string(c.kind);
  const stats::TauGrid grid = tau_grid_of(c);
  const InputKind input = input_kind_from_string(c.input_kind);
  io::Series series = load_varying_record(c, input);
  if (!series.gaps.empty()) {
    naming_the_input(series, [&]() -> int {
      throw DataError(
          fmt::format("{} gap(s) (in the time column, or NaN samples left out): {} across a gap "
                      "would take the missing time for none; "
                      "analyse each stretch on its own",
                      series.gaps.size(), stats::to_string(kind)));
    });
  }
  progress(fmt::format("{} of {} samples", stats::to_string(kind), series.values.size()));
  const stats::TimeErrorResult r = naming_the_input(series, [&] {
    return stats::time_error(series.values, series.sample_rate_hz, input, kind, grid);
  });
  const Sensor sensor = sensor_of_input(c);
  const std::string unit = in_sensor_units("deg/h*s", sensor);
  const std::string name(stats::to_string(kind));
  const nlohmann::json document = {{"kind", name},
                                   {"input", std::string(to_string(input))},
                                   {"unit", unit},
                                   {"tau_s", r.tau_s},
                                   {"value", numbers(r.value)},
                                   {"n", r.n},
                                   {"m", r.m},
                                   {"taus", c.taus},
                                   {"min_clusters", c.min_clusters},
                                   {"source", input_json(series)},
                                   {"foglab_version", std::string(version())}};
  const std::string json = c.json_path.empty() ? "" : json_text(document);
  const std::string column =
      fmt::format("{}_{}_s", name, sensor == Sensor::gyroscope ? "deg_h" : "m_s2");
  std::string csv = fmt::format("tau_s,m,n,{}\n", column);
  std::string table =
      fmt::format("{} of '{}' channel {} ({} samples at {} Hz, {})\n{:>12} {:>10} {:>16}\n", name,
                  series.path, series.channel, series.values.size(), series.sample_rate_hz,
                  to_string(input), "tau [s]", "n", fmt::format("{} [{}]", name, unit));
  for (std::size_t k = 0; k < r.tau_s.size(); ++k) {
    csv += fmt::format("{:.10g},{},{},{}\n", r.tau_s[k], r.m[k], r.n[k], csv_number(r.value[k]));
    table += fmt::format("{:>12.6g} {:>10} {:>16.6g}\n", r.tau_s[k], r.n[k], r.value[k]);
  }
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (c.json_path != "-" && c.csv_path != "-") std::cout << table;
}

void run(const AllanCommand& c) {
  const RunPath inputs[] = {{"FILE", c.input.path}};
  const RunPath outputs[] = {{"--json", c.json_path}, {"--csv", c.csv_path}};
  check_outputs(inputs, outputs);
  if (stats::is_time_error_kind(c.kind)) {
    run_time_error(c);
    return;
  }
  stats::AllanOptions options;
  try {
    options.kind = stats::allan_kind_from_string(c.kind);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("unknown statistic '{}': expected adev, oadev, mdev, hdev, ohdev, tdev, "
                    "totdev, mtotdev, ttotdev, htotdev, theo1, mtie or tierms",
                    c.kind));
  }
  options.grid = tau_grid_of(c);
  options.confidence = !c.no_ci;
  options.bias_correction = !c.no_bias_correction;
  options.noise_rules = stats::noise_rules_from_string(c.noise_id);
  const InputKind input = input_kind_from_string(c.input_kind);
  io::Series series = load_varying_record(c, input);
  const std::size_t samples = series.values.size();
  progress(fmt::format("{} of {} samples{}", stats::to_string(options.kind), samples,
                       options.confidence ? " with noise identification and intervals" : ""));
  // In place: the record becomes the angle record, so memory holds one copy.
  const stats::AllanResult result = naming_the_input(series, [&] {
    return stats::allan_deviation_in_place(series.values, series.sample_rate_hz, input, options,
                                           series.gaps);
  });
  series.values.resize(samples);  // only the count is used below
  // Render everything first, then write: a failure never leaves half the outputs.
  const std::string json = c.json_path.empty() ? "" : json_text(to_json(result, series, c));
  const std::string csv = c.csv_path.empty() ? "" : to_csv(result, sensor_of_input(c));
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (c.json_path != "-" && c.csv_path != "-")
    std::cout << to_table(result, series, sensor_of_input(c));
}

}  // namespace

std::function<void()> register_allan(CLI::App& app) {
  auto c = std::make_shared<AllanCommand>();
  CLI::App* cmd = app.add_subcommand(
      "allan",
      "Allan-family deviation (ADEV, OADEV, MDEV, HDEV, OHDEV, TDEV, TOTDEV, MTOTDEV, "
      "TTOTDEV, HTOTDEV, Theo1) with 68 % and 95 % confidence intervals");
  add_input_options(*cmd, c->input, /*file_optional=*/true);
  cmd->add_option("--kind", c->kind,
                  "oadev, adev, mdev, hdev, ohdev, tdev, totdev, mtotdev, ttotdev, htotdev or "
                  "theo1 (tau = 0.75 m tau0); or mtie or tierms (the angle's largest excursion "
                  "and rms change over tau, no intervals)")
      ->capture_default_str();
  cmd->add_option("--taus", c->taus,
                  "octave, decade, all, N-per-decade, or averaging times in s (1,10,100)")
      ->capture_default_str();
  cmd->add_option("--min-clusters", c->min_clusters,
                  "generated grids keep floor(samples/m) >= this (the lab's L_m >= 10)")
      ->capture_default_str();
  cmd->add_option("--input", c->input_kind, "rate (default) or phase (angle samples)")
      ->capture_default_str();
  cmd->add_flag("--no-ci", c->no_ci, "skip noise identification and confidence intervals");
  cmd->add_flag("--no-bias-correction", c->no_bias_correction,
                "htotdev: print the raw value, not divided by Riley's bias factor");
  cmd->add_option("--noise-id", c->noise_id,
                  "foglab (default: Stable32's rules, and no phase noise beyond the first "
                  "frequency-noise tau) or stable32 (its alpha, tau for tau)")
      ->capture_default_str();
  cmd->add_option("--csv", c->csv_path, "write the table as CSV ('-' for stdout)");
  cmd->add_option("--json", c->json_path, "write JSON ('-' for stdout)");
  return [c] { run(*c); };
}

}  // namespace foglab::cli
