// foglab calibrate — the manual's output model (eq. 10) fitted to a rate-table run
// (model/calibration.h): scale factor, bias, their temperature polynomials, nonlinearity,
// asymmetry, with 95 % intervals, and the corrected-rate equation (eq. 11).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/reader.h"
#include "foglab/model/calibration.h"
#include "foglab/report/calibration.h"

namespace foglab::cli {
namespace {

struct CalibrateCommand {
  std::vector<std::string> paths;  // one run, or a triad's three mountings (x, y, z)
  std::string path;                // paths joined, for messages and the JSON
  bool triad = false;
  std::string rate_column = "rate_cmd_deg_s";
  std::string output_column = "output_lsb";
  std::vector<std::string> triad_columns = {"output_x_lsb", "output_y_lsb", "output_z_lsb"};
  std::string temperature_column = "temperature_c";
  std::optional<double> sample_rate_hz;
  model::CalibrationOptions options;
  std::string json_path;
  std::string csv_path;
  std::string report_path;
  std::string markdown_path;
  std::string language = "en";
};

report::ReportOptions report_options(const CalibrateCommand& c) {
  report::ReportOptions options;
  options.language = language_from_string(c.language);
  return options;
}

report::CalibrationReport make_report(const CalibrateCommand& c, const model::Calibration& r) {
  return report::make_calibration_report(r, c.path, report_options(c));
}

report::CalibrationReport make_report(const CalibrateCommand& c, const model::TriadCalibration& t) {
  return report::make_triad_report(t, c.path, c.paths, report_options(c));
}

io::Series read_column(const CalibrateCommand& c, const std::string& path,
                       const std::string& column) {
  io::ReadOptions options;
  options.channel = column;
  options.sample_rate_hz = c.sample_rate_hz;
  return io::read_series(path, options);
}

nlohmann::json value_json(const model::CalibratedValue& v) {
  return {{"value", number(v.value)},
          {"sd", number(v.sd)},
          {"ci95_low", number(v.ci95_low)},
          {"ci95_high", number(v.ci95_high)}};
}

nlohmann::json values_json(const std::vector<model::CalibratedValue>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& v : values) out.push_back(value_json(v));
  return out;
}

// One gyro's calibration (without the source and version).
nlohmann::json calibration_json(const model::Calibration& r) {
  nlohmann::json plateaus = nlohmann::json::array();
  for (const auto& p : r.plateaus) {
    plateaus.push_back({{"rate_deg_s", p.rate_deg_s},
                        {"first_sample", p.first_sample},
                        {"samples", p.samples},
                        {"output_mean_lsb", p.output_mean_lsb},
                        {"output_sd_lsb", p.output_sd_lsb},
                        {"temperature_c", p.temperature_c},
                        {"residual_lsb", p.residual_lsb}});
  }
  return {{"reference_c", r.reference_c},
          {"full_scale_deg_s", r.full_scale_deg_s},
          {"temperatures_c", r.temperatures_c},
          {"scale_factor_lsb_per_deg_s", value_json(r.scale_factor)},
          {"scale_factor_temp_coefs_per_degc_k", values_json(r.scale_factor_temp)},
          {"bias_lsb", value_json(r.bias)},
          {"bias_deg_h", value_json(r.bias_deg_h)},
          {"bias_temp_coefs_lsb_per_degc_k", values_json(r.bias_temp)},
          {"nonlinearity_coefs_per_deg_s_k", values_json(r.nonlinearity)},
          {"nonlinearity_degree", r.nonlinearity_degree},
          {"asymmetry", value_json(r.asymmetry)},
          {"nonlinearity_ieee_ppm_fs", number(r.nonlinearity_ieee_ppm_fs)},
          {"nonlinearity_lab1_percent", number(r.nonlinearity_lab1_percent)},
          {"white_noise_deg_h_rt_hz", number(r.white_noise_deg_h_rt_hz)},
          {"residual_rms_lsb", number(r.residual_rms_lsb)},
          {"dof", r.dof},
          {"weighting", r.noise_covariance ? "noise_covariance" : "alike"},
          {"residual_noise", noise_model_json(r.noise)},
          {"residual_noise_units", noise_units_json()},
          {"dispersion", number(r.dispersion)},
          {"error_budget_at_full_scale_deg_h",
           {{"bias", number(r.budget.bias_deg_h)},
            {"scale_factor", number(r.budget.scale_factor_deg_h)},
            {"nonlinearity", number(r.budget.nonlinearity_deg_h)},
            {"noise_1s", number(r.budget.noise_1s_deg_h)}}},
          {"corrected_rate_equation", report::corrected_rate_equation(r)},
          {"plateaus", plateaus},
          {"notes", english(r.notes)}};
}

nlohmann::json to_json(const CalibrateCommand& c, const model::Calibration& r) {
  nlohmann::json j = {{"source", {{"path", c.path}}}, {"settle_s", c.options.settle_s}};
  j.update(calibration_json(r));
  j["foglab_version"] = std::string(version());
  return j;
}

nlohmann::json to_json(const CalibrateCommand& c, const model::TriadCalibration& t) {
  nlohmann::json axes = nlohmann::json::array();
  nlohmann::json misalignment = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    axes.push_back(calibration_json(t.axes[i]));
    nlohmann::json row = nlohmann::json::array();
    for (int j = 0; j < 3; ++j) {
      model::CalibratedValue m = t.misalignment_rad[i][j];
      for (double* v : {&m.value, &m.sd, &m.ci95_low, &m.ci95_high}) *v *= 1e3;
      row.push_back(i == j ? nlohmann::json(nullptr) : value_json(m));
    }
    misalignment.push_back(row);
  }
  return {{"source", {{"paths", c.paths}, {"table_axes", model::kTriadAxes}}},
          {"settle_s", c.options.settle_s},
          {"axes", axes},
          {"misalignment_mrad", misalignment},
          {"misalignment_meaning",
           "[i][j]: gyro i's sensitivity to a rate about body axis j, M = I + m (small angles)"},
          {"foglab_version", std::string(version())}};
}

std::string to_table(const std::string& what, const model::Calibration& r) {
  std::string out = fmt::format(
      "rate-table calibration of {}: {} plateaus, {} temperature(s), full scale {:g} deg/s, "
      "T_ref {:g} degC ({} dof)\n",
      what, r.plateaus.size(), r.temperatures_c.size(), r.full_scale_deg_s, r.reference_c, r.dof);
  out +=
      fmt::format("  scale factor S       {} LSB/(deg/s)\n", report::interval_text(r.scale_factor));
  for (std::size_t k = 0; k < r.scale_factor_temp.size(); ++k) {
    out += fmt::format("  S temperature s_{}   {} ppm/degC^{}\n", k + 1,
                       report::interval_text(r.scale_factor_temp[k], 1e6), k + 1);
  }
  out += fmt::format("  bias u0              {} LSB = {} deg/h\n", report::interval_text(r.bias),
                     report::interval_text(r.bias_deg_h));
  for (std::size_t k = 0; k < r.bias_temp.size(); ++k) {
    out += fmt::format("  bias temperature b_{} {} LSB/degC^{}\n", k + 1,
                       report::interval_text(r.bias_temp[k]), k + 1);
  }
  for (std::size_t k = 0; k < r.nonlinearity.size(); ++k) {
    const double fs = std::pow(r.full_scale_deg_s, static_cast<double>(k + 1)) * 1e6;
    out += fmt::format("  nonlinearity a_{}     {} ppm of full scale\n", k + 1,
                       report::interval_text(r.nonlinearity[k], fs));
  }
  if (std::isfinite(r.asymmetry.value)) {
    out += fmt::format("  asymmetry A          {} ppm\n", report::interval_text(r.asymmetry, 1e6));
  }
  out += fmt::format(
      "  nonlinearity: {:.4g} ppm of full scale (IEEE Std 952), {:.4g} % (the lab manual's "
      "scale-factor spread)\n",
      r.nonlinearity_ieee_ppm_fs, r.nonlinearity_lab1_percent);
  out += fmt::format(
      "  white noise N {:.4g} deg/h/sqrt(Hz) (ARW {:.4g} deg/sqrt(h)); plateau "
      "residuals {:.4g} LSB rms\n",
      r.white_noise_deg_h_rt_hz, r.white_noise_deg_h_rt_hz / 60.0, r.residual_rms_lsb);
  if (r.noise_covariance) {
    out += fmt::format(
        "  plateaus weighted by the residual record's noise: N {:.4g} deg/h/sqrt(Hz), B {:.4g} "
        "deg/h, K {:.4g} deg/h/sqrt(s), Gauss-Markov {:.4g} deg/h over {:.4g} s; chi2/dof "
        "{:.3g}\n",
        r.noise.N, r.noise.B, r.noise.K, r.noise.gm_sigma, r.noise.gm_tc, r.dispersion);
  } else {
    out += "  plateaus weighted alike (ordinary least squares)\n";
  }
  out += fmt::format(
      "  error budget at full scale (eq. 13, 95 %): bias {:.4g}, scale factor {:.4g}, "
      "nonlinearity residual {:.4g}, noise over 1 s {:.4g} deg/h\n",
      r.budget.bias_deg_h, r.budget.scale_factor_deg_h, r.budget.nonlinearity_deg_h,
      r.budget.noise_1s_deg_h);
  out += "  corrected rate (eq. 11): " + report::corrected_rate_equation(r) + "\n";
  for (const Message& note : r.notes) out += "note: " + note.text() + "\n";
  return out;
}

std::string to_table(const CalibrateCommand& c, const model::Calibration& r) {
  return to_table(fmt::format("'{}'", c.path), r);
}

std::string to_table(const CalibrateCommand& c, const model::TriadCalibration& t) {
  constexpr const auto& kAxis = model::kTriadAxes;
  std::string out;
  for (int i = 0; i < 3; ++i) {
    out += to_table(fmt::format("gyro {} ('{}')", kAxis[i], c.paths[i]), t.axes[i]);
  }
  out += "misalignment m_ij [mrad] (gyro i's sensitivity to a rate about axis j), 95 %:\n";
  for (int i = 0; i < 3; ++i) {
    out += fmt::format("  {}", kAxis[i]);
    for (int j = 0; j < 3; ++j) {
      out += i == j ? fmt::format("  {:>34}", "1 (scale factor)")
                    : fmt::format("  {:>34}", report::interval_text(t.misalignment_rad[i][j], 1e3));
    }
    out += "\n";
  }
  return out;
}

constexpr const char* kPlateauCsvHeader =
    "rate_deg_s,first_sample,samples,output_mean_lsb,output_sd_lsb,temperature_c,residual_lsb";

std::string plateau_rows(const model::Calibration& r, const std::string& prefix) {
  std::string out;
  for (const auto& p : r.plateaus) {
    out += prefix + fmt::format("{:.10g},{},{},{:.12g},{:.6g},{:.6g},{:.6g}\n", p.rate_deg_s,
                                p.first_sample, p.samples, p.output_mean_lsb, p.output_sd_lsb,
                                p.temperature_c, p.residual_lsb);
  }
  return out;
}

std::string to_csv(const model::Calibration& r) {
  return std::string(kPlateauCsvHeader) + "\n" + plateau_rows(r, "");
}

// A triad's plateaus: each gyro on its own mounting, then on the others (the cross-axis fits).
std::string to_csv(const model::TriadCalibration& t) {
  constexpr const auto& kAxis = model::kTriadAxes;
  std::string out = std::string("gyro,table_axis,") + kPlateauCsvHeader + "\n";
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      out += plateau_rows(i == j ? t.axes[i] : t.cross[i][j],
                          fmt::format("{},{},", kAxis[i], kAxis[j]));
    }
  }
  return out;
}

// Renders everything first, then writes: a failure never leaves half the outputs.
template <class Result>
void write_outputs(const CalibrateCommand& c, const Result& result) {
  const std::string json = c.json_path.empty() ? "" : json_text(to_json(c, result));
  const std::string csv = c.csv_path.empty() ? "" : to_csv(result);
  report::CalibrationReport rep;
  if (!c.report_path.empty() || !c.markdown_path.empty()) {
    progress("drawing the report's plots");
    rep = make_report(c, result);
    if (rep.plots_skipped && !c.report_path.empty()) note(rep.plots_note);
  }
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (!c.report_path.empty()) write_text_file(c.report_path, rep.html);
  if (!c.markdown_path.empty()) write_text_file(c.markdown_path, rep.markdown);
  if (c.json_path != "-" && c.csv_path != "-" && c.markdown_path != "-") {
    std::cout << to_table(c, result);
  }
}

void run(CalibrateCommand& c) {
  if (c.paths.size() != (c.triad ? 3u : 1u)) {
    throw UsageError(c.triad
                         ? fmt::format("--triad needs the three mountings' files (the table "
                                       "about x, y, z), got {}",
                                       c.paths.size())
                         : fmt::format("one FILE (three with --triad), got {}", c.paths.size()));
  }
  c.path = fmt::format("{}", fmt::join(c.paths, "', '"));
  std::vector<RunPath> inputs;
  for (const std::string& path : c.paths) inputs.push_back({"FILE", path});
  const RunPath outputs[] = {{"--json", c.json_path},
                             {"--csv", c.csv_path},
                             {"--report", c.report_path},
                             {"--markdown", c.markdown_path}};
  check_outputs(inputs, outputs);
  for (const std::string& path : c.paths) {
    if (io::is_stream(path)) {
      throw UsageError(fmt::format(
          "{} is read once (standard input, a FIFO or a device), and calibrate reads several "
          "columns from it; save the run to a file",
          path == "-" ? "standard input" : "'" + path + "'"));
    }
  }
  if (!c.triad) {
    const io::Series rate = read_column(c, c.paths[0], c.rate_column);
    const io::Series output = read_column(c, c.paths[0], c.output_column);
    const io::Series temperature = c.temperature_column.empty()
                                       ? io::Series{}
                                       : read_column(c, c.paths[0], c.temperature_column);
    progress(fmt::format("calibrating on {} samples at {} Hz", output.values.size(),
                         output.sample_rate_hz));
    write_outputs(
        c, model::calibrate({output.sample_rate_hz, rate.values, output.values, temperature.values},
                            c.options));
    return;
  }
  // Each mounting's columns; the series own the samples the records view.
  std::vector<io::Series> columns;
  columns.reserve(15);
  std::array<model::TriadRecord, 3> mountings;
  for (int j = 0; j < 3; ++j) {
    const std::string& path = c.paths[j];
    const io::Series& rate = columns.emplace_back(read_column(c, path, c.rate_column));
    mountings[j].sample_rate_hz = rate.sample_rate_hz;
    mountings[j].rate_command_deg_s = rate.values;
    for (int i = 0; i < 3; ++i) {
      mountings[j].output_lsb[i] =
          columns.emplace_back(read_column(c, path, c.triad_columns[i])).values;
    }
    if (!c.temperature_column.empty()) {
      mountings[j].temperature_c =
          columns.emplace_back(read_column(c, path, c.temperature_column)).values;
    }
  }
  progress("calibrating the triad: three gyros on three mountings");
  write_outputs(c, model::calibrate_triad(mountings, c.options));
}

}  // namespace

std::function<void()> register_calibrate(CLI::App& app) {
  auto c = std::make_shared<CalibrateCommand>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit the manual's output model (eq. 10) to a rate-table run: scale factor, bias, their "
      "temperature polynomials, nonlinearity and asymmetry with 95 % intervals, and the "
      "corrected-rate equation (eq. 11)");
  cmd->add_option("FILE", c->paths,
                  "the run: CSV or MAT with a time column or f; with --triad the three "
                  "mountings, the table about x, y and z")
      ->required()
      ->expected(1, 3);
  cmd->add_flag("--triad", c->triad,
                "calibrate a triad: three files, three gyros each; adds the misalignment");
  cmd->add_option("--triad-columns", c->triad_columns, "with --triad: the gyros' outputs [LSB]")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  cmd->add_option("--rate-column", c->rate_column, "the commanded rate [deg/s]")
      ->capture_default_str();
  cmd->add_option("--output-column", c->output_column, "the gyro's output [LSB]")
      ->capture_default_str();
  cmd->add_option("--temperature-column", c->temperature_column,
                  "the temperature [degC] ('' for none)")
      ->capture_default_str();
  cmd->add_option("--fs", c->sample_rate_hz, "sample rate [Hz] (else from the file)");
  cmd->add_option("--settle", c->options.settle_s, "left out at each plateau's start [s]")
      ->capture_default_str();
  cmd->add_option("--plateaus", c->options.plateaus,
                  "where the plateaus are found: 'command' (runs of one value of the rate "
                  "column) or 'output' (where the output stays level; each plateau's rate the "
                  "rate column's mean over it: for a measured table rate)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, model::PlateauSource>{
              {"command", model::PlateauSource::commanded_rate},
              {"output", model::PlateauSource::output}},
          CLI::ignore_case))
      ->default_str("command");
  cmd->add_option("--reference-c", c->options.reference_c,
                  "T_ref of the temperature polynomials [degC]")
      ->capture_default_str();
  cmd->add_option("--nonlinearity-degree", c->options.nonlinearity_degree,
                  "terms a_1 .. a_d of the nonlinearity f(w); -1: the highest term kept only "
                  "while the plateaus show it (t above its 99.5 % point), up to 5")
      ->capture_default_str();
  cmd->add_flag("!--no-asymmetry", c->options.asymmetry, "do not fit the asymmetry");
  cmd->add_flag("!--weigh-alike", c->options.noise_covariance,
                "weigh every plateau alike (ordinary least squares) instead of by the plateau "
                "means' covariance from the residual record's noise model");
  cmd->add_option("--json", c->json_path, "write JSON ('-' for stdout)");
  cmd->add_option("--csv", c->csv_path, "write the plateaus as CSV ('-' for stdout)");
  cmd->add_option("--report", c->report_path,
                  "write a self-contained HTML report (gnuplot SVG plots: output, scale factor "
                  "and residuals against rate, residuals against temperature)");
  cmd->add_option("--markdown", c->markdown_path,
                  "write the report's numbers and tables as Markdown ('-' for stdout)");
  cmd->add_option("--lang", c->language,
                  "the report's language: en, or ru (the lab manual's terms and units)")
      ->check(CLI::IsMember({"en", "ru"}, CLI::ignore_case))
      ->capture_default_str();
  return [c] { run(*c); };
}

}  // namespace foglab::cli
