// foglab rate-table — a generated rate-table run with known coefficients (sim/rate_table.h):
// the truth `foglab calibrate` is checked against, and variant data for a lab.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/writer.h"
#include "foglab/sim/optics.h"
#include "foglab/sim/rate_table.h"

namespace foglab::cli {
namespace {

struct RateTableCommand {
  std::string out_path;
  std::string truth_path;
  double full_scale_deg_s = 300.0;
  int rates_per_sign = 5;
  std::vector<double> temperatures_c = {-20.0, 25.0, 60.0};
  double plateau_s = 60.0;
  sim::RateTableOptions options;
  sim::RateTableGyro gyro;
  bool triad = false;
  int optics_variant = 0;  // > 0: the lab-1 optics of that Table 4 variant as the gyro
  bool full_scale_given = false, temperatures_given = false;
  /// [mrad] m_xy, m_xz, m_yx, m_yz, m_zx, m_zy (sim::RateTableTriad)
  std::vector<double> misalignment_mrad = {0.8, -0.5, 0.3, 1.2, -0.9, 0.4};
  /// With --triad: gyro k's S and u0 are S (1 + spread k) and u0 + 10 k LSB (k = 0, 1, 2), so
  /// that a swapped axis shows.
  double triad_spread = 0.01;
};

// The triad `foglab rate-table --triad` generates (the struct's comment above).
sim::RateTableTriad triad_of(const RateTableCommand& c) {
  sim::RateTableTriad t;
  for (int k = 0; k < 3; ++k) {
    t.gyros[k] = c.gyro;
    t.gyros[k].scale_factor_lsb_per_deg_s *= 1.0 + c.triad_spread * k;
    t.gyros[k].bias_lsb += 10.0 * k;
  }
  int next = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != j) t.misalignment_rad[i][j] = c.misalignment_mrad[next++] * 1e-3;
    }
  }
  return t;
}

// gyro.csv -> gyro-x.csv: the mounting about `axis`.
std::string mounting_path(const std::string& path, const char* axis) {
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "-" + axis + p.extension().string())).string();
}

nlohmann::json gyro_json(const sim::RateTableGyro& g) {
  return {{"model",
           "u = S (1 + sum s_k dT^k) [1 + sum a_k w^k + (A/2) sign(w)] w + u0 + "
           "sum b_k dT^k + S eta / 3600, dT = T - T_ref"},
          {"scale_factor_lsb_per_deg_s", g.scale_factor_lsb_per_deg_s},
          {"scale_factor_temp_coefs_per_degc_k", g.scale_factor_temp_coefs},
          {"nonlinearity_coefs_per_deg_s_k", g.nonlinearity_coefs},
          {"asymmetry", g.asymmetry},
          {"bias_lsb", g.bias_lsb},
          {"bias_temp_coefs_lsb_per_degc_k", g.bias_temp_coefs_lsb},
          {"reference_c", g.reference_c},
          {"noise",
           {{"N_deg_h_rt_hz", g.noise.N}, {"B_deg_h", g.noise.B}, {"K_deg_h_rt_s", g.noise.K}}}};
}

// The gyro `rate-table` generates: the options' eq. (10), or the lab-1 optics.
sim::RateTableGyro gyro_of(const RateTableCommand& c) {
  if (c.optics_variant == 0) return c.gyro;
  sim::RateTableGyro g = sim::optics_rate_table_gyro(sim::lab1_coil(c.optics_variant));
  g.noise = c.gyro.noise;
  g.reference_c = c.gyro.reference_c;
  return g;
}

nlohmann::json truth_json(const RateTableCommand& c) {
  nlohmann::json j;
  if (c.optics_variant > 0) {
    const sim::Coil coil = sim::lab1_coil(c.optics_variant);
    const sim::RateTableGyro g = gyro_of(c);
    sim::SweepOptions analytic;
    analytic.method = sim::SweepMethod::analytic;
    const double range_rad_s = c.full_scale_deg_s * std::numbers::pi / 180.0;
    j = gyro_json(g);
    j["model"] =
        "u = S r(w) + S eta / 3600, S r(w) the lab-1 open loop's steady state (square "
        "modulation at f_m) [a.u.]";
    j["optics"] = {{"variant", c.optics_variant},
                   {"omega_pi2_deg_s", sim::coil_numbers(coil).omega_pi2_deg_s},
                   {"sagnac_scale_factor_s", sim::coil_numbers(coil).scale_factor_s},
                   {"output_unit", "a.u. (the detector's arbitrary unit; the files' 'lsb')"},
                   {"lab1_sweep_nonlinearity_percent",
                    sim::sweep_open_loop(coil, range_rad_s, {}, analytic).nonlinearity_percent}};
  } else if (c.triad) {
    const sim::RateTableTriad t = triad_of(c);
    nlohmann::json gyros = nlohmann::json::array();
    nlohmann::json m = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
      gyros.push_back(gyro_json(t.gyros[i]));
      nlohmann::json row = nlohmann::json::array();
      for (int k = 0; k < 3; ++k) {
        row.push_back(i == k ? nlohmann::json(nullptr)
                             : nlohmann::json(t.misalignment_rad[i][k] * 1e3));
      }
      m.push_back(row);
    }
    j = {{"gyros", gyros},
         {"misalignment_mrad", m},
         {"misalignment_meaning",
          "[i][j]: gyro i's sensitivity to a rate about body axis j, M = I + m (small angles)"},
         {"files",
          {mounting_path(c.out_path, "x"), mounting_path(c.out_path, "y"),
           mounting_path(c.out_path, "z")}}};
  } else {
    j = gyro_json(c.gyro);
  }
  j["plan"] = {{"full_scale_deg_s", c.full_scale_deg_s},
               {"rates_per_sign", c.rates_per_sign},
               {"temperatures_c", c.temperatures_c},
               {"plateau_s", c.plateau_s},
               {"settle_s", c.options.settle_s},
               {"sample_rate_hz", c.options.sample_rate_hz},
               {"seed", c.options.seed}};
  j["foglab_version"] = std::string(version());
  return j;
}

std::string extension_of(const std::string& path) {
  return std::filesystem::path(path).extension().string();
}

// Writes one file of columns as CSV or MAT (by its extension).
void write_columns(const std::string& path, std::span<const io::NamedVector> columns,
                   const std::string& comment) {
  if (extension_of(path) == ".mat") {
    io::write_mat(path, columns);
  } else {
    const std::string comments[] = {comment};
    io::write_csv(path, columns, comments);
  }
}

void run(RateTableCommand& c) {
  if (c.optics_variant > 0) {
    if (c.triad) throw UsageError("--optics and --triad: one gyro of optics only");
    // The lab's sweep: +-Omega_pi/2 in steps of a fifth, at one temperature.
    if (!c.full_scale_given) {
      c.full_scale_deg_s = sim::coil_numbers(sim::lab1_coil(c.optics_variant)).omega_pi2_deg_s;
    }
    if (!c.temperatures_given) c.temperatures_c = {c.gyro.reference_c};
  }
  const std::string ext = extension_of(c.out_path);
  if (ext != ".csv" && ext != ".mat") {
    throw UsageError(
        fmt::format("--out '{}': write a .csv or .mat file, not '{}'", c.out_path, ext));
  }
  std::vector<RunPath> outputs = {{"--truth", c.truth_path}};
  static constexpr const char* kAxis[] = {"x", "y", "z"};
  if (c.triad) {
    if (c.misalignment_mrad.size() != 6) {
      throw UsageError(
          fmt::format("--misalignment: six angles m_xy,m_xz,m_yx,m_yz,m_zx,m_zy [mrad], got {}",
                      c.misalignment_mrad.size()));
    }
    for (const char* axis : kAxis) outputs.push_back({"--out", mounting_path(c.out_path, axis)});
  } else {
    outputs.push_back({"--out", c.out_path});
  }
  check_outputs({}, outputs);
  const std::vector<sim::RatePlateau> plan = sim::standard_rate_table_plan(
      c.full_scale_deg_s, c.rates_per_sign, c.temperatures_c, c.plateau_s);
  progress(fmt::format("generating a rate-table run{}: {} plateaus of {} s",
                       c.triad ? " of a triad on three mountings" : "", plan.size(), c.plateau_s));
  const std::string truth = c.truth_path.empty() ? "" : json_text(truth_json(c));
  const std::string comment = fmt::format("foglab {} rate-table run: {} plateaus, seed {}",
                                          version(), plan.size(), c.options.seed);
  std::size_t samples = 0;
  double sample_rate_hz = 0.0;
  std::string written;
  if (c.triad) {
    const auto runs = sim::generate_rate_table_triad(triad_of(c), plan, c.options);
    for (const sim::TriadRecording& r : runs) {
      const io::NamedVector columns[] = {{"time_s", r.motion.time_s},
                                         {"rate_cmd_deg_s", r.motion.rate_command_deg_s},
                                         {"table_rate_deg_s", r.motion.table_rate_deg_s},
                                         {"output_x_lsb", r.output_lsb[0]},
                                         {"output_y_lsb", r.output_lsb[1]},
                                         {"output_z_lsb", r.output_lsb[2]},
                                         {"temperature_c", r.motion.temperature_c}};
      const std::string path = mounting_path(c.out_path, kAxis[r.table_axis]);
      write_columns(
          path, columns,
          fmt::format("{}; the table about the triad's {} axis", comment, kAxis[r.table_axis]));
      written += (written.empty() ? "" : ", ") + path;
    }
    samples = runs[0].motion.time_s.size();
    sample_rate_hz = runs[0].motion.sample_rate_hz;
  } else {
    const sim::RateTableRecording run = sim::generate_rate_table(gyro_of(c), plan, c.options);
    const io::NamedVector columns[] = {{"time_s", run.time_s},
                                       {"rate_cmd_deg_s", run.rate_command_deg_s},
                                       {"table_rate_deg_s", run.table_rate_deg_s},
                                       {"output_lsb", run.output_lsb},
                                       {"temperature_c", run.temperature_c}};
    write_columns(c.out_path, columns, comment);
    written = c.out_path;
    samples = run.time_s.size();
    sample_rate_hz = run.sample_rate_hz;
  }
  if (!c.truth_path.empty()) write_text_file(c.truth_path, truth);
  std::cout << fmt::format("wrote {} ({} samples at {} Hz, {} plateaus{}){}\n", written, samples,
                           sample_rate_hz, plan.size(), c.triad ? " each" : "",
                           c.truth_path.empty() ? "" : " and the truth to " + c.truth_path);
}

}  // namespace

std::function<void()> register_rate_table(CLI::App& app) {
  auto c = std::make_shared<RateTableCommand>();
  c->gyro.scale_factor_temp_coefs = {-8.0e-5, 3.0e-7};
  c->gyro.nonlinearity_coefs = {4.0e-8, 1.5e-10};
  c->gyro.asymmetry = 2.0e-5;
  c->gyro.bias_lsb = 30.0;
  c->gyro.bias_temp_coefs_lsb = {0.4, 0.004};
  c->gyro.noise.N = 0.5;
  c->gyro.noise.B = 0.05;
  CLI::App* cmd = app.add_subcommand(
      "rate-table",
      "Generate a rate-table calibration run with known coefficients (the manual's eq. 10): "
      "plateaus up and down +-FS at each temperature, columns time_s, rate_cmd_deg_s, "
      "table_rate_deg_s, output_lsb, temperature_c");
  cmd->add_option("--out", c->out_path, "the run: .csv or .mat")->required();
  cmd->add_option("--truth", c->truth_path, "write the coefficients as JSON");
  cmd->add_option("--full-scale", c->full_scale_deg_s,
                  "largest rate [deg/s] (with --optics: Omega_pi/2)")
      ->capture_default_str()
      ->each([c](const std::string&) { c->full_scale_given = true; });
  cmd->add_option("--rates", c->rates_per_sign, "rates of each sign, FS k / RATES")
      ->capture_default_str();
  cmd->add_option("--temps", c->temperatures_c,
                  "chamber temperatures [degC] (with --optics: the reference temperature)")
      ->delimiter(',')
      ->capture_default_str()
      ->each([c](const std::string&) { c->temperatures_given = true; });
  cmd->add_option("--plateau", c->plateau_s, "each plateau's length [s]")->capture_default_str();
  cmd->add_option("--settle", c->options.settle_s,
                  "[s] the table's and the chamber's transition at each plateau's start")
      ->capture_default_str();
  cmd->add_option("--fs", c->options.sample_rate_hz, "sample rate [Hz]")->capture_default_str();
  cmd->add_option("--seed", c->options.seed, "random seed")->capture_default_str();
  cmd->add_option("--sf", c->gyro.scale_factor_lsb_per_deg_s, "scale factor S [LSB/(deg/s)]")
      ->capture_default_str();
  cmd->add_option("--sf-temp", c->gyro.scale_factor_temp_coefs,
                  "s_1,s_2,...: S(T) = S (1 + sum s_k dT^k) [1/degC^k]")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--nonlinearity", c->gyro.nonlinearity_coefs,
                  "a_1,a_2,...: f(w) = sum a_k w^k [1/(deg/s)^k]")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--asymmetry", c->gyro.asymmetry, "A = (S+ - S-) / S")->capture_default_str();
  cmd->add_option("--bias", c->gyro.bias_lsb, "u0 at the reference temperature [LSB]")
      ->capture_default_str();
  cmd->add_option("--bias-temp", c->gyro.bias_temp_coefs_lsb,
                  "b_1,b_2,...: u0(T) = u0 + sum b_k dT^k [LSB/degC^k]")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--reference-c", c->gyro.reference_c, "T_ref [degC]")->capture_default_str();
  cmd->add_flag("--triad", c->triad,
                "a triad of three gyros (x, y, z), on three mountings: writes OUT-x, OUT-y, "
                "OUT-z (the table about x, y, z) with columns output_x_lsb, output_y_lsb, "
                "output_z_lsb; gyro k's S is S (1 + 0.01 k) and u0 is u0 + 10 k LSB");
  cmd->add_option("--optics", c->optics_variant,
                  "the lab-1 optics of Table 4 variant 1-6 as the gyro (open loop, square "
                  "modulation): output in the detector's a.u., rates +-Omega_pi/2 k/RATES at "
                  "one temperature; the eq. (10) coefficients are not used")
      ->check(CLI::Range(1, 6));
  cmd->add_option("--misalignment", c->misalignment_mrad,
                  "with --triad: m_xy,m_xz,m_yx,m_yz,m_zx,m_zy [mrad], m_ij gyro i's "
                  "sensitivity to a rate about axis j")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--N", c->gyro.noise.N, "white rate noise [deg/h/sqrt(Hz)]")
      ->capture_default_str();
  cmd->add_option("--B", c->gyro.noise.B, "flicker (bias instability) [deg/h]")
      ->capture_default_str();
  cmd->add_option("--K", c->gyro.noise.K, "rate random walk [deg/h/sqrt(s)]")
      ->capture_default_str();
  return [c] { run(*c); };
}

}  // namespace foglab::cli
