// foglab coil | simulate | sweep | lab1 — lab 1's optical signal chain
// (sim/optics.h, sim/lab1.h, report/lab1.h). The commands choose the coil
// and the options, call the library and write what it returns.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/language.h"
#include "foglab/core/output.h"
#include "foglab/core/units.h"
#include "foglab/core/version.h"
#include "foglab/io/channels.h"
#include "foglab/io/reader.h"
#include "foglab/report/lab1.h"
#include "foglab/sim/lab1.h"
#include "foglab/sim/optics.h"

namespace foglab::cli {
namespace {

/// --variant N or --length/--radius/--wavelength (with --group-index).
struct CoilOptions {
  std::optional<int> variant;
  std::optional<double> length_m, radius_m, wavelength_m;
  double group_index = 1.0;
};

void add_coil_options(CLI::App& cmd, CoilOptions& c, bool variant_default) {
  auto* v =
      cmd.add_option("--variant", c.variant,
                     variant_default ? "Table 4 variant 1-6 (default 1)" : "Table 4 variant 1-6");
  auto* l = cmd.add_option("--length", c.length_m, "fibre length L [m]");
  auto* r = cmd.add_option("--radius", c.radius_m, "coil radius R [m]");
  auto* w = cmd.add_option("--wavelength", c.wavelength_m, "source wavelength [m], e.g. 1550e-9");
  v->excludes(l)->excludes(r)->excludes(w);
  cmd.add_option("--group-index", c.group_index,
                 "group index n_g of the transit time tau0 = n_g L / c (the manual: 1)")
      ->capture_default_str();
}

std::string coil_name(const CoilOptions& c) {
  return c.variant ? fmt::format("Table 4 variant {}", *c.variant) : "the given coil";
}

sim::Coil resolve_coil(const CoilOptions& c, bool variant_default) {
  const bool any = c.length_m || c.radius_m || c.wavelength_m;
  if (!c.variant && !any && !variant_default) {
    throw UsageError("give --variant N (Table 4) or --length, --radius and --wavelength");
  }
  sim::Coil coil;
  if (c.variant || !any) {
    coil = sim::lab1_coil(c.variant.value_or(1));
  } else {
    if (!c.length_m || !c.radius_m || !c.wavelength_m) {
      throw UsageError("a coil needs all of --length, --radius and --wavelength (or --variant)");
    }
    coil.length_m = *c.length_m;
    coil.radius_m = *c.radius_m;
    coil.wavelength_m = *c.wavelength_m;
  }
  coil.group_index = c.group_index;
  sim::coil_numbers(coil);  // validates
  return coil;
}

nlohmann::json coil_json(const sim::Coil& coil, const sim::CoilNumbers& n) {
  return {{"scale_factor_s", n.scale_factor_s},
          {"omega_pi2_rad_s", n.omega_pi2_rad_s},
          {"omega_pi2_deg_s", n.omega_pi2_deg_s},
          {"transit_time_s", n.transit_time_s},
          {"modulation_frequency_hz", n.modulation_frequency_hz},
          {"coil",
           {{"length_m", coil.length_m},
            {"radius_m", coil.radius_m},
            {"wavelength_m", coil.wavelength_m},
            {"group_index", coil.group_index}}},
          {"units",
           {{"scale_factor_s", "s (Sagnac phase rad per rad/s)"},
            {"omega_pi2_rad_s", "rad/s"},
            {"omega_pi2_deg_s", "deg/s"},
            {"transit_time_s", "s"},
            {"modulation_frequency_hz", "Hz"}}},
          {"foglab_version", std::string(version())}};
}

/// A sweep in the CLI's units: rates [deg/s]; outputs S [a.u.] (open loop),
/// the output rate [deg/s] (closed loop) or the feedback phase [rad] (the
/// closed loop in the manual's form); scale factors output/rate, the phase
/// form's per rad/s [s] (-K_s).
struct SweepInDegrees {
  std::vector<double> rates_deg_s, outputs, scale_factors;
};

SweepInDegrees in_degrees(const sim::SweepResult& s) {
  SweepInDegrees d;
  for (std::size_t i = 0; i < s.rates_rad_s.size(); ++i) {
    d.rates_deg_s.push_back(s.rates_rad_s[i] * kDegPerRad);
    if (s.phase_form) {
      d.outputs.push_back(s.outputs[i]);
      d.scale_factors.push_back(s.scale_factors[i]);
      continue;
    }
    d.outputs.push_back(s.closed_loop ? s.outputs[i] * kDegPerRad : s.outputs[i]);
    d.scale_factors.push_back(d.outputs.back() / d.rates_deg_s.back());
  }
  return d;
}

/// docs/json.md's sweep fields (rates, outputs, scale factors, nonlinearity).
nlohmann::json sweep_json(const sim::SweepResult& s) {
  const SweepInDegrees d = in_degrees(s);
  return {{"rates_deg_s", d.rates_deg_s},
          {"outputs", d.outputs},
          {"scale_factors", d.scale_factors},
          {"nonlinearity_percent", s.nonlinearity_percent}};
}

// ---- coil ------------------------------------------------------------------------------

struct CoilCommand {
  CoilOptions coil;
  std::string json_path;
};

void run_coil(const CoilCommand& c) {
  const sim::Coil coil = resolve_coil(c.coil, false);
  const sim::CoilNumbers n = sim::coil_numbers(coil);
  if (!c.json_path.empty()) write_text_file(c.json_path, json_text(coil_json(coil, n)));
  if (c.json_path == "-") return;
  std::cout << fmt::format(
      "coil: {} (L = {:.6g} m, R = {:.6g} m, lambda = {:.6g} nm, n_g = {:.6g})\n"
      "  Sagnac scale factor K_s   {:>12.6g} s (rad per rad/s)\n"
      "  range Omega_pi/2          {:>12.6g} rad/s = {:.6g} deg/s\n"
      "  transit time tau0         {:>12.6g} us\n"
      "  modulation frequency f_m  {:>12.6g} kHz\n",
      coil_name(c.coil), coil.length_m, coil.radius_m, coil.wavelength_m * 1e9, coil.group_index,
      n.scale_factor_s, n.omega_pi2_rad_s, n.omega_pi2_deg_s, n.transit_time_s * 1e6,
      n.modulation_frequency_hz * 1e-3);
}

// ---- simulate --------------------------------------------------------------------------

struct SimulateCommand {
  std::string scheme;  // open-loop | closed-loop
  CoilOptions coil;
  std::string modulation = "square";
  std::optional<double> rate_deg_s;
  std::string ramp;  // A:B:SECONDS
  std::string rate_file;
  std::optional<double> duration_s;
  std::optional<double> frequency_hz;
  int samples_per_transit = 8;
  double loop_gain = 0.5;
  std::string csv_path, json_path;
};

/// "A:B:SECONDS" -> a ramp from A to B deg/s over SECONDS.
sim::RateInput parse_ramp(const std::string& text) {
  double a = 0, b = 0, s = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf:%lf%c", &a, &b, &s, &tail) != 3) {
    throw UsageError(fmt::format(
        "--ramp '{}': expected START:END:SECONDS (rates in deg/s), e.g. -100:100:0.01", text));
  }
  return sim::RateInput::ramp(a / kDegPerRad, b / kDegPerRad, s);
}

sim::RateInput rate_input(const SimulateCommand& c, double default_rate_rad_s) {
  const int given =
      (c.rate_deg_s ? 1 : 0) + (c.ramp.empty() ? 0 : 1) + (c.rate_file.empty() ? 0 : 1);
  if (given > 1) throw UsageError("give one of --rate, --ramp and --rate-file");
  if (c.rate_deg_s) {
    if (!(std::fabs(*c.rate_deg_s) <= sim::kMaxInputRateRadS * kDegPerRad)) {
      throw UsageError(
          fmt::format("--rate must be finite and at most {:g} deg/s in magnitude, "
                      "got {}",
                      sim::kMaxInputRateRadS * kDegPerRad, *c.rate_deg_s));
    }
    return sim::RateInput::constant(*c.rate_deg_s / kDegPerRad);
  }
  if (!c.ramp.empty()) return parse_ramp(c.ramp);
  if (!c.rate_file.empty()) {
    // A text or MAT file with a time column (t) and a rate column [deg/s].
    // The profile's own t column sets the times (they need not be uniform),
    // so the reader is given a nominal sample rate and no time column.
    io::ReadOptions read;
    read.unit = RateUnit::deg_per_hour;  // identity: the values stay deg/s
    read.sample_rate_hz = 1.0;
    read.channel = "rate";
    if (io::is_stream(c.rate_file)) {
      throw UsageError(
          fmt::format("--rate-file '{}' is read once (standard input, a FIFO or a "
                      "device), and its t and rate columns are read in turn: save "
                      "it to a file",
                      c.rate_file));
    }
    const std::vector<std::string> channels = io::list_channels(c.rate_file);
    if (std::find(channels.begin(), channels.end(), "rate") == channels.end() ||
        std::find(channels.begin(), channels.end(), "t") == channels.end()) {
      throw DataError(fmt::format(
          "--rate-file '{}': needs columns (or variables) t [s] and rate [deg/s]; it has {}",
          c.rate_file, io::list_names(channels)));
    }
    io::Series rate = io::read_series(c.rate_file, read);
    read.channel = "t";
    io::Series t = io::read_series(c.rate_file, read);
    for (double& v : rate.values) v /= kDegPerRad;
    if (t.values.size() < 2) {
      throw DataError(
          fmt::format("--rate-file '{}': one row only; a rate profile needs at least "
                      "two (the simulated time is the span of its t column)",
                      c.rate_file));
    }
    try {
      return sim::RateInput::profile(std::move(t.values), std::move(rate.values));
    } catch (const UsageError& e) {
      throw DataError(fmt::format("--rate-file '{}': {}", c.rate_file, e.what()));
    }
  }
  return sim::RateInput::constant(default_rate_rad_s);
}

void run_simulate(const SimulateCommand& c) {
  const RunPath inputs[] = {{"--rate-file", c.rate_file}};
  const RunPath outputs[] = {{"--json", c.json_path}, {"--csv", c.csv_path}};
  check_outputs(inputs, outputs);
  const sim::Coil coil = resolve_coil(c.coil, true);
  const sim::CoilNumbers n = sim::coil_numbers(coil);
  const bool closed = c.scheme == "closed-loop";
  sim::OpticsOptions o;
  o.modulation = sim::modulation_from_string(c.modulation);
  if (closed && o.modulation != sim::Modulation::square) {
    throw UsageError("--modulation: the closed loop uses square bias modulation");
  }
  o.samples_per_transit = c.samples_per_transit;
  if (c.frequency_hz) o.modulation_frequency_hz = *c.frequency_hz;
  const sim::RateInput rate = rate_input(c, 0.5 * n.omega_pi2_rad_s);
  const double period_s = 1.0 / n.modulation_frequency_hz;
  double duration_s = c.duration_s.value_or(2000.0 * period_s);
  if (!c.duration_s && rate.kind == sim::RateInput::Kind::ramp) duration_s = rate.ramp_duration_s;
  if (!c.duration_s && rate.kind == sim::RateInput::Kind::profile) duration_s = rate.time_s.back();
  const double samples = duration_s / (n.transit_time_s / o.samples_per_transit);
  if (samples > 4e9) {
    throw UsageError(
        fmt::format("--duration {} s is {:.3g} samples at the physics rate; at most "
                    "4e9 (a few minutes' work) are allowed",
                    duration_s, samples));
  }
  progress(fmt::format("simulating {:.3g} s ({:.3g} samples)", duration_s, samples));
  sim::ClosedLoopOptions loop;
  loop.loop_gain = c.loop_gain;
  const sim::OpticsResult r = closed ? sim::simulate_closed_loop(coil, rate, duration_s, o, loop)
                                     : sim::simulate_open_loop(coil, rate, duration_s, o);
  const sim::PeriodSeries& p = r.periods;
  std::string csv;
  if (!c.csv_path.empty()) {
    csv = closed ? "# foglab simulate closed-loop: per modulation period; error = sin(phi_s + u); "
                   "ramp_phase_rad: the feedback phase psi at the period's end, stepping by the "
                   "feedback step every transit time, reset by 2 pi (the manual's Fig. 11)\n"
                   "time_s,rate_deg_s,error,feedback_step_rad,ramp_phase_rad,output_deg_s\n"
                 : "# foglab simulate open-loop: per modulation period; S in a.u. (detector "
                   "gain x intensity)\ntime_s,rate_deg_s,demodulated,output_lowpass\n";
    for (std::size_t i = 0; i < p.time_s.size(); ++i) {
      csv += closed ? fmt::format("{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n", p.time_s[i],
                                  p.rate_rad_s[i] * kDegPerRad, p.demodulated[i],
                                  p.feedback_step_rad[i], p.ramp_phase_rad[i],
                                  p.output[i] * kDegPerRad)
                    : fmt::format("{:.10g},{:.10g},{:.10g},{:.10g}\n", p.time_s[i],
                                  p.rate_rad_s[i] * kDegPerRad, p.demodulated[i], p.output[i]);
    }
  }
  const double last_rate = p.rate_rad_s.empty() ? NAN : p.rate_rad_s.back();
  const double last_output = p.output.empty() ? NAN : p.output.back();
  nlohmann::json j = coil_json(coil, n);
  j["scheme"] = c.scheme;
  j["modulation"] = closed ? "square" : c.modulation;
  j["simulated_modulation_frequency_hz"] = r.modulation_frequency_hz;
  j["sample_interval_s"] = r.sample_interval_s;
  j["samples"] = r.samples;
  j["duration_s"] = duration_s;
  j["periods"] = p.time_s.size();
  j["final_rate_deg_s"] = number(last_rate * kDegPerRad);
  if (closed) {
    j["final_output_deg_s"] = number(last_output * kDegPerRad);
    j["final_feedback_step_rad"] =
        number(p.feedback_step_rad.empty() ? NAN : p.feedback_step_rad.back());
  } else {
    j["final_output"] = number(last_output);
    j["steady_state_output"] = number(sim::steady_state_output(coil, last_rate, o));
  }
  if (!c.json_path.empty()) write_text_file(c.json_path, json_text(j));
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (c.json_path == "-" || c.csv_path == "-") return;
  std::cout << fmt::format(
      "{} ({}), {}: {:.6g} s simulated, {} samples at dt = {:.4g} ns, {} modulation periods at "
      "{:.6g} kHz\n",
      c.scheme, closed ? "square bias modulation and phase ramp" : c.modulation + " modulation",
      coil_name(c.coil), duration_s, r.samples, r.sample_interval_s * 1e9, p.time_s.size(),
      r.modulation_frequency_hz * 1e-3);
  if (closed) {
    std::cout << fmt::format(
        "final rate {:.6g} deg/s, output {:.6g} deg/s (the manual's output, the feedback phase "
        "step: {:.6g} rad = -K_s x rate)\n",
        last_rate * kDegPerRad, last_output * kDegPerRad,
        p.feedback_step_rad.empty() ? NAN : p.feedback_step_rad.back());
  } else {
    std::cout << fmt::format(
        "final rate {:.6g} deg/s, output (low-passed) {:.6g} a.u., analytic steady state "
        "{:.6g} a.u.\n",
        last_rate * kDegPerRad, last_output, sim::steady_state_output(coil, last_rate, o));
  }
}

// ---- sweep -----------------------------------------------------------------------------

struct SweepCommand {
  std::string scheme;
  CoilOptions coil;
  std::string modulation = "square";
  std::optional<double> range_deg_s;
  std::string method = "time";
  std::string output = "rate";
  std::string json_path, csv_path;
};

/// The closed loop's --output: "rate" (foglab's, deg/s) or "phase" (the
/// manual's feedback phase, rad); the open loop has only its signal S.
bool phase_output(const std::string& output, bool closed) {
  if (output == "rate") return false;
  if (output != "phase") {
    throw UsageError(fmt::format("--output '{}': expected rate or phase", output));
  }
  if (!closed) {
    throw UsageError(
        "--output phase: the feedback phase is the closed loop's output; the open loop's is the "
        "demodulated signal S");
  }
  return true;
}

void run_sweep(const SweepCommand& c) {
  const RunPath written[] = {{"--json", c.json_path}, {"--csv", c.csv_path}};
  check_outputs({}, written);
  const sim::Coil coil = resolve_coil(c.coil, false);
  const sim::CoilNumbers n = sim::coil_numbers(coil);
  const bool closed = c.scheme == "closed-loop";
  sim::OpticsOptions o;
  o.modulation = sim::modulation_from_string(c.modulation);
  if (o.modulation == sim::Modulation::none) {
    throw UsageError(
        "--modulation none: without modulation there is no demodulated output to "
        "sweep");
  }
  if (closed && o.modulation != sim::Modulation::square) {
    throw UsageError("--modulation: the closed loop uses square bias modulation");
  }
  sim::SweepOptions so;
  if (c.method == "analytic") {
    so.method = sim::SweepMethod::analytic;
  } else if (c.method != "time") {
    throw UsageError(fmt::format("--method '{}': expected time or analytic", c.method));
  }
  const double range = c.range_deg_s ? *c.range_deg_s / kDegPerRad : n.omega_pi2_rad_s;
  if (!(range > 0.0 && range <= sim::kMaxInputRateRadS)) {
    throw UsageError(fmt::format("--range must be in (0, {:g}] deg/s, got {}",
                                 sim::kMaxInputRateRadS * kDegPerRad, *c.range_deg_s));
  }
  const bool phase = phase_output(c.output, closed);
  const sim::SweepResult rate_form = closed ? sim::sweep_closed_loop(coil, range, o, {}, so)
                                            : sim::sweep_open_loop(coil, range, o, so);
  const sim::SweepResult s = phase ? sim::feedback_phase_form(rate_form) : rate_form;
  std::optional<double> range30;
  if (!closed) range30 = sim::range_for_nonlinearity(coil, 30.0, o, so);

  const SweepInDegrees d = in_degrees(s);
  const std::vector<double>& rates_deg = d.rates_deg_s;
  const std::vector<double>& outputs = d.outputs;
  const std::vector<double>& sfs = d.scale_factors;
  nlohmann::json j = sweep_json(s);
  j.update({{"scheme", c.scheme},
            {"modulation", closed ? "square" : c.modulation},
            {"method", c.method},
            {"output", closed ? c.output : "signal"},
            {"range_for_30_percent_deg_s",
             range30 ? nlohmann::json(*range30 * kDegPerRad) : nlohmann::json(nullptr)},
            {"omega_pi2_deg_s", n.omega_pi2_deg_s},
            {"units",
             {{"rates_deg_s", "deg/s"},
              {"outputs", phase    ? "rad (the feedback phase step u, the manual's output)"
                          : closed ? "deg/s (the feedback converted to rate)"
                                   : "a.u. (demodulated signal S, detector gain x intensity)"},
              {"scale_factors", phase    ? "s (u / rate in rad/s: -K_s)"
                                : closed ? "1 (output / rate)"
                                         : "a.u. per deg/s"},
              {"nonlinearity_percent", "% ((max - min) / mean scale factor)"},
              {"range_for_30_percent_deg_s", "deg/s (open loop only)"}}},
            {"foglab_version", std::string(version())}});
  std::string csv;
  if (!c.csv_path.empty()) {
    csv = fmt::format(
        "# foglab sweep {}: output {}, scale factor {}\nrate_deg_s,output,scale_factor\n", c.scheme,
        phase    ? "rad (feedback phase)"
        : closed ? "deg/s"
                 : "a.u.",
        phase    ? "s (per rad/s)"
        : closed ? "1"
                 : "a.u. per deg/s");
    for (std::size_t i = 0; i < rates_deg.size(); ++i) {
      csv += fmt::format("{:.10g},{:.10g},{:.10g}\n", rates_deg[i], outputs[i], sfs[i]);
    }
  }
  if (!c.json_path.empty()) write_text_file(c.json_path, json_text(j));
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (c.json_path == "-" || c.csv_path == "-") return;
  std::cout << fmt::format(
      "{} sweep, {}, {} ({} method), range +-{:.6g} deg/s (Omega_pi/2 = "
      "{:.6g} deg/s)\n",
      c.scheme, closed ? "square bias modulation" : c.modulation + " modulation", coil_name(c.coil),
      c.method, range * kDegPerRad, n.omega_pi2_deg_s);
  std::cout << fmt::format("  {:>12}  {:>16}  {:>16}\n", "rate [deg/s]",
                           phase    ? "phase u [rad]"
                           : closed ? "output [deg/s]"
                                    : "output [a.u.]",
                           phase    ? "SF [s]"
                           : closed ? "SF [1]"
                                    : "SF [a.u./(deg/s)]");
  for (std::size_t i = 0; i < rates_deg.size(); ++i) {
    std::cout << fmt::format("  {:>12.6g}  {:>16.9g}  {:>16.9g}\n", rates_deg[i], outputs[i],
                             sfs[i]);
  }
  std::cout << fmt::format(
      "nonlinearity {:.6g} %{}\n", s.nonlinearity_percent,
      closed ? fmt::format(" ({:.3g} ppm)", s.nonlinearity_percent * 1e4) : "");
  if (closed) {
    // The manual's output is the feedback phase (scale factor -K_s); foglab's the rate (1).
    std::cout << fmt::format(
        "the manual's form (--output phase): scale factor -K_s = {:.6g} s; foglab's (--output "
        "rate): 1; the nonlinearity is the same number in both\n",
        -n.scale_factor_s);
  }
  if (!closed) {
    std::cout << (range30 ? fmt::format("range with 30 % nonlinearity: +-{:.6g} deg/s\n",
                                        *range30 * kDegPerRad)
                          : std::string("the nonlinearity stays below 30 % up to Omega_pi/2\n"));
  }
}

// ---- lab1 ------------------------------------------------------------------------------

struct Lab1Command {
  int variant = 1;
  std::string out = "lab1-report";
  bool no_plots = false;
  std::string language = "en";
  std::string output = "rate";
  TitleOptions title;
};

void run_lab1(const Lab1Command& c) {
  const Language language = language_from_string(c.language);
  const sim::Coil coil = sim::lab1_coil(c.variant);
  const bool phase = phase_output(c.output, true);
  OutputFolder folder("--out", c.out);  // a bad --out is said before the work
  progress(fmt::format("running lab 1 on Table 4 variant {}", c.variant));
  sim::Lab1Options options;
  const sim::Lab1Result result = sim::run_lab1(coil, options);
  progress("drawing the plots");
  report::ReportOptions ro;
  ro.plots = !c.no_plots;
  ro.language = language;
  ro.title_block = title_block(c.title, 1, c.variant);
  ro.loop_output_phase = phase;
  const std::string title = Message(Text::lab1_title, c.variant).text(language);
  const report::Lab1Report rep = report::make_lab1_report(result, title, options.loop, ro);
  if (rep.plots_skipped) note(rep.plots_note);
  const sim::CoilNumbers& n = result.numbers;
  const nlohmann::json coil_j = coil_json(coil, n);
  nlohmann::json sweeps = nlohmann::json::object();
  sweeps["open_loop_square"] = sweep_json(result.sweep_square);
  sweeps["open_loop_square"]["range_for_30_percent_deg_s"] =
      result.range_30_rad_s ? nlohmann::json(*result.range_30_rad_s * kDegPerRad)
                            : nlohmann::json();
  sweeps["open_loop_square_analytic"] = sweep_json(result.sweep_square_analytic);
  sweeps["open_loop_square_analytic"]["range_for_30_percent_deg_s"] =
      result.range_30_analytic_rad_s ? nlohmann::json(*result.range_30_analytic_rad_s * kDegPerRad)
                                     : nlohmann::json();
  sweeps["open_loop_sine"] = sweep_json(result.sweep_sine);
  sweeps["closed_loop"] = sweep_json(result.sweep_closed);
  // The manual's form whatever --output: the feedback phase and -K_s.
  sweeps["closed_loop_phase"] = sweep_json(sim::feedback_phase_form(result.sweep_closed));
  const nlohmann::json j = {
      {"variant", c.variant},
      {"coil", coil_j},
      {"sweeps", sweeps},
      {"checks",
       {{"square_worst_deviation_of_full_scale", result.open_loop[1].worst_deviation_of_full_scale},
        {"sine_worst_deviation_of_full_scale", result.open_loop[2].worst_deviation_of_full_scale},
        {"off_frequency_ratio",
         result.off_frequency.modulation_frequency_hz / n.modulation_frequency_hz},
        {"off_frequency_signal_ratio", result.off_frequency_signal_ratio},
        {"off_frequency_theory_ratio", result.off_frequency_theory_ratio},
        {"off_frequency_spike_fraction", result.off_frequency_spike_fraction}}},
      {"units",
       {{"sweeps.*.rates_deg_s", "deg/s"},
        {"sweeps.open_loop_*.outputs", "a.u."},
        {"sweeps.open_loop_*.scale_factors", "a.u. per deg/s"},
        {"sweeps.closed_loop.outputs", "deg/s"},
        {"sweeps.closed_loop.scale_factors", "1"},
        {"sweeps.closed_loop_phase.outputs", "rad (the feedback phase step u)"},
        {"sweeps.closed_loop_phase.scale_factors", "s (u / rate in rad/s: -K_s)"},
        {"sweeps.*.nonlinearity_percent", "%"},
        {"checks.*", "1 (fractions)"}}},
      {"foglab_version", std::string(version())}};

  write_text_file(folder.file("report.html"), rep.html);
  write_text_file(folder.file("report.md"), rep.markdown);
  write_text_file(folder.file("sweeps.csv"), rep.sweep_csv);
  write_text_file(folder.file("lab1.json"), json_text(j));
  folder.commit();
  std::cout << rep.markdown;
  std::cout << fmt::format("Report: {}\n(also in '{}': report.md, sweeps.csv, lab1.json)\n",
                           folder.final_file("report.html"), c.out);
}

}  // namespace

std::function<void()> register_coil(CLI::App& app) {
  auto c = std::make_shared<CoilCommand>();
  CLI::App* cmd = app.add_subcommand(
      "coil",
      "a fibre coil's Sagnac scale factor, Omega_pi/2, transit time and modulation "
      "frequency (lab 1, item 1.1)");
  add_coil_options(*cmd, c->coil, false);
  cmd->add_option("--json", c->json_path, "write the numbers as JSON ('-' for stdout)");
  return [c] { run_coil(*c); };
}

std::function<void()> register_simulate(CLI::App& app) {
  auto c = std::make_shared<SimulateCommand>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "simulate the open- or closed-loop FOG in time at the physics rate (per modulation period "
      "output as CSV)");
  cmd->add_option("SCHEME", c->scheme, "open-loop or closed-loop")
      ->required()
      ->check(CLI::IsMember({"open-loop", "closed-loop"}));
  add_coil_options(*cmd, c->coil, true);
  cmd->add_option("--modulation", c->modulation, "none, square or sine (open loop)")
      ->capture_default_str();
  cmd->add_option("--rate", c->rate_deg_s, "constant input rate [deg/s] (default 0.5 Omega_pi/2)");
  cmd->add_option("--ramp", c->ramp, "rate ramp START:END:SECONDS [deg/s, deg/s, s]");
  cmd->add_option("--rate-file", c->rate_file,
                  "rate profile: CSV or MAT with t [s] and rate [deg/s], linear between points");
  cmd->add_option(
      "--duration", c->duration_s,
      "simulated time [s] (default: the ramp or profile, else 2000 modulation periods)");
  cmd->add_option("--frequency", c->frequency_hz,
                  "modulation frequency [Hz] (default: the proper 1/(2 tau0))");
  cmd->add_option("--samples-per-transit", c->samples_per_transit,
                  "samples per transit time (2 x per modulation period)")
      ->capture_default_str();
  cmd->add_option("--loop-gain", c->loop_gain, "closed loop: integrator gain per period")
      ->capture_default_str();
  cmd->add_option("--csv", c->csv_path, "per-period series as CSV ('-' for stdout)");
  cmd->add_option("--json", c->json_path, "summary as JSON ('-' for stdout)");
  return [c] { run_simulate(*c); };
}

std::function<void()> register_sweep(CLI::App& app) {
  auto c = std::make_shared<SweepCommand>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "the lab's ten-rate sweep: scale factors, nonlinearity and (open loop) the range "
      "with 30 % nonlinearity");
  cmd->add_option("SCHEME", c->scheme, "open-loop or closed-loop")
      ->required()
      ->check(CLI::IsMember({"open-loop", "closed-loop"}));
  add_coil_options(*cmd, c->coil, false);
  cmd->add_option("--modulation", c->modulation, "square or sine (open loop)")
      ->capture_default_str();
  cmd->add_option("--range", c->range_deg_s, "sweep +-RANGE [deg/s] (default Omega_pi/2)");
  cmd->add_option("--method", c->method, "time (simulation) or analytic (steady state)")
      ->capture_default_str();
  cmd->add_option("--output", c->output,
                  "closed loop: rate (foglab's output in deg/s, scale factor 1) or phase (the "
                  "manual's feedback phase in rad, scale factor -K_s in s)")
      ->capture_default_str();
  cmd->add_option("--json", c->json_path, "write the sweep as JSON ('-' for stdout)");
  cmd->add_option("--csv", c->csv_path, "write the sweep as CSV ('-' for stdout)");
  return [c] { run_sweep(*c); };
}

std::function<void()> register_lab1(CLI::App& app) {
  auto c = std::make_shared<Lab1Command>();
  CLI::App* cmd = app.add_subcommand(
      "lab1",
      "the whole of lab 1 on a Table 4 coil: coil numbers, open loop with each "
      "modulation, sweeps, nonlinearity, the 30 % range, the closed loop; HTML report");
  cmd->add_option("--variant", c->variant, "Table 4 variant 1-6")->capture_default_str();
  cmd->add_option("--out", c->out, "directory for report.html, report.md, sweeps.csv, lab1.json")
      ->capture_default_str();
  cmd->add_flag("--no-plots", c->no_plots, "write the report without plots (no gnuplot)");
  cmd->add_option("--lang", c->language,
                  "the report's language: en, or ru (the lab manual's terms and units)")
      ->capture_default_str();
  cmd->add_option("--output", c->output,
                  "the closed loop's table: rate (foglab's output in deg/s, scale factor 1) or "
                  "phase (the manual's feedback phase in rad, scale factor -K_s in s)")
      ->capture_default_str();
  add_title_options(cmd, c->title);
  return [c] { run_lab1(*c); };
}

}  // namespace foglab::cli
