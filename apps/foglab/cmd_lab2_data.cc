// foglab lab2-data — the lab-2 variant files FOG1_k.mat, FOG2_k.mat and the
// instructor's answer key (answers.json, answers.csv).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/writer.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/lab2_variants.h"

namespace foglab::cli {
namespace {

struct Lab2DataCommand {
  std::string out;
  std::uint64_t seed = sim::kLab2DefaultSeed;
  std::optional<double> hours;  // hidden: shorter runs for tests and quick looks
};

nlohmann::json optional_number(bool present, double value) {
  return present ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json lab2_units() {
  nlohmann::json units = model_units_json();
  units["polyfit_p"] = "MATLAB polyfit(T, Y, 2) order: deg/h/degC^2, deg/h/degC, deg/h";
  units["arw_deg_per_sqrt_h"] = "deg/sqrt(h)";
  units["bias_instability_deg_h"] = "deg/h (minimum of the model ADEV in usable_tau_s)";
  units["usable_tau_s"] = "s, [1/fs, duration/10]";
  units["random_bias_octaves"] =
      "octaves of usable_tau_s over which the random bias carries at least half the Allan "
      "variance (2 or more: the record shows it)";
  return units;
}

nlohmann::json gyro_truth(const sim::Lab2Gyro& g) { return model_json(g.model); }

nlohmann::json run_json(const sim::Lab2Variant& v, const sim::Lab2Gyro& g, const sim::Lab2Run& r) {
  const bool wiener = g.random_bias == RandomBiasProcess::wiener;
  const NoiseModel& n = g.model.noise;
  const auto samples =
      static_cast<std::int64_t>(std::llround(r.generator.duration_s * r.generator.sample_rate_hz));
  return {
      {"file", g.file_name},
      {"gyro", g.name},
      {"variant", v.variant},
      {"run", std::string(sim::to_string(r.temperature.kind))},
      {"rate_variable", r.rate_name},
      {"temperature_variable", r.temperature_name},
      {"temperature",
       {{"kind", std::string(sim::to_string(r.temperature.kind))},
        {"start_c", r.temperature.start_c},
        {"span_c", r.temperature.span_c},
        {"jitter_c", r.temperature.jitter_c},
        {"reference_c", r.t_ref_c}}},
      {"sample_rate_hz", r.generator.sample_rate_hz},
      {"duration_s", r.generator.duration_s},
      {"samples", samples},
      {"seed", r.generator.seed},
      {"stream", r.generator.stream},
      {"expected",
       {{"polyfit_p", {r.polyfit_p[0], r.polyfit_p[1], r.polyfit_p[2]}},
        {"lab_constant_term_deg_h", r.lab_constant_term_deg_h},
        {"constant_term_well_conditioned", r.constant_term_well_conditioned},
        {"bias_at_t_ref_deg_h", r.bias_at_t_ref_deg_h},
        {"N", n.N},
        {"arw_deg_per_sqrt_h", g.arw_deg_sqrt_h},
        {"random_bias_process", std::string(to_string(g.random_bias))},
        {"K", optional_number(wiener, n.K)},
        {"gm_sigma", optional_number(!wiener, n.gm_sigma)},
        {"gm_tc", optional_number(!wiener, n.gm_tc)},
        {"random_bias_octaves", r.random_bias_octaves},
        {"flicker_floor_deg_h", flicker_floor_deg_h(n.B)},
        {"bias_instability_deg_h", r.bias_instability.adev_deg_h},
        {"bias_instability_tau_s", r.bias_instability.tau_s},
        {"bias_instability_at_range_edge", r.bias_instability.at_range_edge},
        {"usable_tau_s", {r.usable_tau_min_s, r.usable_tau_max_s}},
        {"accuracy_class", std::string(sim::to_string(g.verdict.accuracy_class))},
        {"class_by_bias_instability", std::string(sim::to_string(g.verdict.by_bias_instability))},
        {"class_by_arw", std::string(sim::to_string(g.verdict.by_arw))},
        {"class_decided_by", std::string(to_string(g.verdict.decided_by))}}}};
}

std::string json_cell(const nlohmann::json& j) {
  if (j.is_null()) return "";
  if (j.is_string()) return j.get<std::string>();
  if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
  if (j.is_number_float()) return fmt::format("{}", j.get<double>());
  return j.dump();
}

std::string answers_csv(const nlohmann::json& rows) {
  const std::vector<std::string> top = {
      "file",           "gyro",       "variant", "run",  "rate_variable", "temperature_variable",
      "sample_rate_hz", "duration_s", "samples", "seed", "stream"};
  const std::vector<std::string> expected = {"lab_constant_term_deg_h",
                                             "constant_term_well_conditioned",
                                             "bias_at_t_ref_deg_h",
                                             "N",
                                             "arw_deg_per_sqrt_h",
                                             "random_bias_process",
                                             "K",
                                             "gm_sigma",
                                             "gm_tc",
                                             "random_bias_octaves",
                                             "flicker_floor_deg_h",
                                             "bias_instability_deg_h",
                                             "bias_instability_tau_s",
                                             "bias_instability_at_range_edge",
                                             "accuracy_class",
                                             "class_decided_by"};
  std::string out =
      "# foglab lab2-data answer key: N deg/h/sqrt(Hz), ARW deg/sqrt(h), K "
      "deg/h/sqrt(s), gm_sigma deg/h, gm_tc s, biases deg/h, temperatures degC; "
      "p1..p3 = polyfit(T, Y, 2) in MATLAB order\n";
  for (const std::string& k : top) {
    out += k;
    out += ',';
  }
  out += "t_ref_c,p1,p2,p3";
  for (const std::string& k : expected) {
    out += ',';
    out += k;
  }
  out += "\n";
  for (const nlohmann::json& row : rows) {
    for (const std::string& k : top) {
      out += json_cell(row[k]);
      out += ',';
    }
    const nlohmann::json& e = row["expected"];
    out += fmt::format("{},{},{},{}", row["temperature"]["reference_c"].get<double>(),
                       e["polyfit_p"][0].get<double>(), e["polyfit_p"][1].get<double>(),
                       e["polyfit_p"][2].get<double>());
    for (const std::string& k : expected) {
      out += ',';  // (not "," + json_cell(): GCC 12 -Wrestrict false positive, bug 105329)
      out += json_cell(e[k]);
    }
    out += "\n";
  }
  return out;
}

void run(const Lab2DataCommand& c) {
  const std::vector<sim::Lab2Variant> variants = sim::lab2_variants(lab2_options(c.seed, c.hours));
  OutputFolder folder("--out", c.out);

  nlohmann::json rows = nlohmann::json::array();
  nlohmann::json gyros = nlohmann::json::array();
  std::string table =
      fmt::format("{:<11} {:<12} {:<13} {:>9} {:>9} {:>10} {:>9} {:>9}\n", "file", "class",
                  "random bias", "N", "ARW", "BI [deg/h]", "p3 (Y2)", "fs x h");
  for (const sim::Lab2Variant& v : variants) {
    for (const sim::Lab2Gyro& g : v.gyros) {
      progress(fmt::format("generating {}", g.file_name));
      std::array<sim::Recording, 2> recs;
      for (std::size_t r = 0; r < 2; ++r) {
        recs[r] = sim::generate(g.model, g.runs[r].temperature, g.runs[r].generator);
      }
      const double f = recs[0].sample_rate_hz;
      const std::vector<io::NamedVector> vars = {{"f", {&f, 1}},
                                                 {"t", recs[0].time_s},
                                                 {"Y1", recs[0].rate_deg_h},
                                                 {"Y2", recs[1].rate_deg_h},
                                                 {"T1", recs[0].temperature_c},
                                                 {"T2", recs[1].temperature_c}};
      io::write_mat(folder.file(g.file_name), vars);
      for (const sim::Lab2Run& r : g.runs) rows.push_back(run_json(v, g, r));
      gyros.push_back({{"file", g.file_name},
                       {"gyro", g.name},
                       {"variant", v.variant},
                       {"design", g.design},
                       {"random_bias_process", std::string(to_string(g.random_bias))},
                       {"accuracy_class", std::string(sim::to_string(g.verdict.accuracy_class))},
                       {"model", gyro_truth(g)}});
      const sim::Lab2Run& ramp = g.runs[1];
      table += fmt::format("{:<11} {:<12} {:<13} {:>9.4g} {:>9.4g} {:>10.4g} {:>9.4g} {:>9}\n",
                           g.file_name, sim::to_string(g.verdict.accuracy_class),
                           to_string(g.random_bias), g.model.noise.N, g.arw_deg_sqrt_h,
                           ramp.bias_instability.adev_deg_h, ramp.lab_constant_term_deg_h,
                           fmt::format("{}x{:.3g}", ramp.generator.sample_rate_hz,
                                       ramp.generator.duration_s / 3600.0));
    }
  }
  const nlohmann::json answers = {
      {"generator", "foglab lab2-data"},
      {"foglab_version", std::string(version())},
      {"seed", c.seed},
      {"units", lab2_units()},
      {"notes",
       {"Values are computed from the model, not estimated from the data.",
        "The thermostat run's polyfit constant is ill-conditioned (the temperature moves only "
        "by sensor jitter): compare bias_at_t_ref_deg_h with mean(Y1) instead."}},
      {"gyros", gyros},
      {"runs", rows}};
  write_text_file(folder.file("answers.json"), json_text(answers));
  write_text_file(folder.file("answers.csv"), answers_csv(rows));
  folder.commit();
  std::cout << fmt::format("wrote 12 files, answers.json and answers.csv to '{}' (seed {})\n",
                           c.out, c.seed)
            << table;
}

}  // namespace

std::function<void()> register_lab2_data(CLI::App& app) {
  auto c = std::make_shared<Lab2DataCommand>();
  CLI::App* cmd = app.add_subcommand(
      "lab2-data",
      "the lab-2 variant data sets FOG1_1..6.mat, FOG2_1..6.mat (f, t, Y1, Y2, T1, T2) and "
      "the answer key answers.json/answers.csv");
  cmd->add_option("--out", c->out, "directory to write (created if needed)")->required();
  cmd->add_option("--seed", c->seed, "random seed of the variant design and the noise")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--hours", c->hours, "")->group("");  // hidden: shorter runs
  return [c] { run(*c); };
}

}  // namespace foglab::cli
