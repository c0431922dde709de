// foglab psd — Welch power spectral density of a rate record.
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/stats/psd.h"

namespace foglab::cli {
namespace {

struct PsdCommand {
  InputOptions input;
  std::size_t segment = 0;
  double overlap = 0.5;
  double smooth_per_decade = 20.0;
  std::string csv_path;
  std::string json_path;
};

nlohmann::json spectrum_json(const stats::PsdResult& p) {
  return {{"frequency_hz", numbers(p.frequency_hz)},
          {"psd", numbers(p.psd)},
          {"sqrt_psd", numbers(p.sqrt_psd)}};
}

void run(const PsdCommand& c) {
  const RunPath inputs[] = {{"FILE", c.input.path}};
  const RunPath outputs[] = {{"--json", c.json_path}, {"--csv", c.csv_path}};
  check_outputs(inputs, outputs);
  const io::Series series = load_input(c.input);
  naming_the_input(series, [&] {
    require_varying(series.values);
    return 0;
  });
  progress(fmt::format("Welch PSD of {} samples", series.values.size()));
  stats::WelchOptions options;
  options.segment_length = c.segment;
  options.overlap = c.overlap;
  // A record (or its longest stretch) under welch_psd()'s 16 samples is a
  // DataError from it, named by naming_the_input().
  const stats::PsdResult psd = naming_the_input(series, [&] {
    return stats::welch_psd(series.values, series.sample_rate_hz, options, series.gaps);
  });
  const stats::PsdResult smooth =
      naming_the_input(series, [&] { return stats::log_smooth(psd, c.smooth_per_decade); });

  // An accelerometer read in an acceleration unit is in m/s^2.
  const Sensor sensor = sensor_of(parse_units_option(c.input.units, c.input.path));
  std::string json;
  if (!c.json_path.empty()) {
    nlohmann::json j = spectrum_json(psd);
    j["sided"] = "two";
    j["unit"] = in_sensor_units("(deg/h)^2/Hz", sensor);
    j["sqrt_unit"] = in_sensor_units("deg/h/sqrt(Hz)", sensor);
    j["window"] = "hann";
    j["segment_length"] = psd.segment_length;
    j["segments"] = psd.segments;
    j["overlap"] = c.overlap;
    j["resolution_hz"] = psd.resolution_hz;
    j[sensor == Sensor::gyroscope ? "mean_removed_deg_h" : "mean_removed_m_s2"] =
        compensated_mean(series.values);
    j["smoothed"] = spectrum_json(smooth);
    j["smoothed"]["bins_per_decade"] = c.smooth_per_decade;
    j["source"] = input_json(series);
    j["foglab_version"] = std::string(version());
    json = json_text(j);
  }
  std::string csv;
  if (!c.csv_path.empty()) {
    csv = sensor == Sensor::gyroscope
              ? "frequency_hz,psd_deg2_h2_per_hz,sqrt_psd_deg_h_per_sqrt_hz\n"
              : "frequency_hz,psd_m2_s4_per_hz,sqrt_psd_m_s2_per_sqrt_hz\n";
    for (std::size_t k = 0; k < psd.frequency_hz.size(); ++k) {
      csv += fmt::format("{:.10g},{:.10g},{:.10g}\n", psd.frequency_hz[k], psd.psd[k],
                         psd.sqrt_psd[k]);
    }
  }
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (c.json_path != "-" && c.csv_path != "-") {
    std::cout << fmt::format(
        "Two-sided PSD of '{}' channel {} (Welch, Hann, {} segments of {} samples, "
        "resolution {:.4g} Hz); log-smoothed, {} bins per decade:\n",
        series.path, series.channel, psd.segments, psd.segment_length, psd.resolution_hz,
        c.smooth_per_decade);
    std::cout << fmt::format("{:>14} {:>18} {:>22}\n", "f [Hz]",
                             in_sensor_units("PSD [(deg/h)^2/Hz]", sensor),
                             in_sensor_units("sqrt [deg/h/sqrt(Hz)]", sensor));
    for (std::size_t k = 0; k < smooth.frequency_hz.size(); ++k) {
      std::cout << fmt::format("{:>14.6g} {:>18.6g} {:>22.6g}\n", smooth.frequency_hz[k],
                               smooth.psd[k], smooth.sqrt_psd[k]);
    }
  }
}

}  // namespace

std::function<void()> register_psd(CLI::App& app) {
  auto c = std::make_shared<PsdCommand>();
  CLI::App* cmd = app.add_subcommand(
      "psd", "two-sided power spectral density of the rate by Welch's method (Hann window)");
  add_input_options(*cmd, c->input, /*file_optional=*/true);
  cmd->add_option("--segment", c->segment,
                  "segment length in samples (default: largest power of two <= N/4)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--overlap", c->overlap, "segment overlap fraction in [0, 1)")
      ->capture_default_str();
  cmd->add_option("--smooth", c->smooth_per_decade,
                  "log-frequency bins per decade of the smoothed spectrum")
      ->capture_default_str();
  cmd->add_option("--csv", c->csv_path, "write the Welch estimate as CSV ('-' for stdout)");
  cmd->add_option("--json", c->json_path, "write JSON ('-' for stdout)");
  return [c] { run(*c); };
}

}  // namespace foglab::cli
