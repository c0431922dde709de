// foglab fit — the noise model fitted to an Allan deviation table.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "analysis_output.h"
#include "cli_common.h"
#include "commands.h"
#include "foglab/core/noise_model.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/allan_table.h"
#include "foglab/model/table_fit.h"

namespace foglab::cli {
namespace {

struct FitCommand {
  std::string path;
  double penalty = model::NoiseFitOptions{}.penalty;
  std::string json_path;
};

nlohmann::json to_json(const FitCommand& c, const io::AllanTable& table, const model::TableFit& r,
                       const model::NoiseFitOptions& options) {
  nlohmann::json parameters = nlohmann::json::object();
  for (const NoiseParameter& p : kNoiseParameters) {
    nlohmann::json one = parameter_estimate_json(r.fit.estimate(p));
    one["unit"] = std::string(p.unit);
    parameters[std::string(p.name)] = one;
  }
  return {{"source", {{"path", c.path}, {"layout", table.layout}, {"points", table.tau_s.size()}}},
          {"tau_s", table.tau_s},
          {"dev_deg_h", table.dev},
          {"edf", numbers(r.edf)},
          {"edf_source", std::string(model::to_string(r.edf_source))},
          {"noise_model", parameters},
          {"random_bias_process", std::string(to_string(r.fit.random_bias_process))},
          {"fit", noise_fit_json(r.fit, options)},
          {"bias_instability_deg_h", number(r.bias_instability_deg_h)},
          {"bias_instability_tau_s", number(r.bias_instability_tau_s)},
          {"arw_deg_sqrt_h", number(r.arw_deg_sqrt_h)},
          {"accuracy_class", std::string(to_string(r.verdict.accuracy_class))},
          {"accuracy_class_decided_by", std::string(to_string(r.verdict.decided_by))},
          {"notes", english(r.notes)},
          {"foglab_version", std::string(version())}};
}

std::string to_table(const FitCommand& c, const io::AllanTable& table, const model::TableFit& r) {
  std::string out = fmt::format(
      "noise model of the Allan table '{}' ({} taus, {} layout; edf "
      "from {})\n",
      c.path, table.tau_s.size(), table.layout, model::to_string(r.edf_source));
  out += fmt::format("{:>9} {:>14} {:>30} {:>13} {}\n", "parameter", "value", "95 % interval",
                     "status", "unit");
  for (const NoiseParameter& p : kNoiseParameters) {
    const model::ParameterEstimate& e = r.fit.estimate(p);
    const std::string interval =
        std::isfinite(e.ci95_low) && !std::isnan(e.ci95_high)
            ? fmt::format("[{:.4g}, {:.4g}]", e.ci95_low, e.ci95_high)
            : (std::isfinite(e.upper_95) ? fmt::format("< {:.4g}", e.upper_95) : "-");
    const std::string value = std::isfinite(e.value) ? fmt::format("{:.6g}", e.value) : "-";
    out += fmt::format("{:>9} {:>14} {:>30} {:>13} {}\n", p.name, value, interval,
                       model::to_string(e.status), p.unit);
  }
  out += fmt::format(
      "bias instability (table minimum) {:.4g} deg/h at {:.4g} s; ARW {:.4g} "
      "deg/sqrt(h); accuracy class {} (decided by {})\n",
      r.bias_instability_deg_h, r.bias_instability_tau_s, r.arw_deg_sqrt_h,
      to_string(r.verdict.accuracy_class), to_string(r.verdict.decided_by));
  for (const Message& note : r.notes) out += "note: " + note.text() + "\n";
  return out;
}

void run(const FitCommand& c) {
  const RunPath inputs[] = {{"TABLE", c.path}};
  const RunPath outputs[] = {{"--json", c.json_path}};
  check_outputs(inputs, outputs);
  const io::AllanTable table = io::read_allan_table(c.path);
  progress(fmt::format("fitting the noise model to {} taus", table.tau_s.size()));
  model::NoiseFitOptions options;
  options.penalty = c.penalty;
  const model::TableColumns columns{table.tau_s, table.dev,      table.n,        table.m,
                                    table.edf,   table.ci68_low, table.ci68_high};
  const model::TableFit fit = model::fit_allan_table(columns, options);
  // Render everything first, then write: a failure never leaves half the outputs.
  const std::string json = c.json_path.empty() ? "" : json_text(to_json(c, table, fit, options));
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (c.json_path != "-") std::cout << to_table(c, table, fit);
}

}  // namespace

std::function<void()> register_fit(CLI::App& app) {
  auto c = std::make_shared<FitCommand>();
  CLI::App* cmd = app.add_subcommand(
      "fit",
      "Fit the noise model (N, B, K, R, Q, Gauss-Markov) to an Allan deviation table: "
      "Stable32's output, a vendor's report, another tool's CSV or `foglab allan --csv`");
  cmd->add_option("TABLE", c->path,
                  "the table: a header naming tau and the deviation (and optionally n, m, "
                  "alpha, edf, 68 % bounds), or Stable32's seven columns")
      ->required();
  cmd->add_option("--penalty", c->penalty,
                  "cost of one parameter in the model selection (criterion D + penalty * p)")
      ->capture_default_str();
  cmd->add_option("--json", c->json_path, "write JSON ('-' for stdout)");
  return [c] { run(*c); };
}

}  // namespace foglab::cli
