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

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/model/analysis.h"
#include "foglab/report/report.h"
#include "foglab/stats/tau_grid.h"

namespace foglab::cli {
namespace {

struct AnalyzeCommand {
  InputOptions input;
  std::string temp_channel;
  std::string temp_degree = "auto";
  std::string taus = "octave";
  std::string json_path;
  std::string csv_path;
  std::string report_path;
  std::string kalibr_path;
};

/// How many candidate models the JSON lists (best first).
constexpr std::size_t kCandidatesListed = 8;

/// -1 for "auto", else 0..3.
int parse_temp_degree(const std::string& text) {
  if (text == "auto") return -1;
  if (text.size() == 1 && text[0] >= '0' && text[0] <= '3') return text[0] - '0';
  throw UsageError(
      fmt::format("--temp-degree '{}': expected auto, 0, 1, 2 or 3 (the degree of the "
                  "temperature polynomial)",
                  text));
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool is_time_name(const std::string& name) {
  const std::string l = lower(name);
  return l == "t" || l == "time" || l == "time_s";
}

/// The file's channel called `name`: exactly, else (with `ignore_case`)
/// without regard to case — but never a time column standing in for the
/// lab's temperature `T`.
std::optional<std::string> find_channel(const std::vector<std::string>& channels,
                                        const std::string& name, bool ignore_case) {
  for (const auto& c : channels) {
    if (c == name) return c;
  }
  if (!ignore_case) return std::nullopt;
  for (const auto& c : channels) {
    if (lower(c) == lower(name) && !is_time_name(c)) return c;
  }
  return std::nullopt;
}

/// The temperature channel names that pair with a rate channel (the lab's
/// Y1 -> T1, Y2 -> T2: a name ending in digits d pairs with "T" + d; a name
/// without digits, e.g. generate's CSV column "rate", with "T" or
/// "temperature"), in order of preference.
std::vector<std::string> paired_temperature_names(const std::string& channel) {
  std::size_t digits = channel.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(channel[digits - 1])) != 0) {
    --digits;
  }
  if (digits < channel.size() && digits > 0) return {"T" + channel.substr(digits)};
  if (digits == channel.size()) return {"T", "temperature"};
  return {};  // a bare column index such as "2": nothing to pair by name
}

/// --temp where no second channel can be read (checked before reading).
void check_temperature_option(const AnalyzeCommand& c) {
  if (c.temp_channel.empty()) return;
  if (c.input.path.empty()) {
    throw UsageError(fmt::format(
        "--temp {}: the built-in sample has no temperature channel (its only channel is Y1)",
        c.temp_channel));
  }
  if (c.input.path == "-") {
    throw UsageError(fmt::format(
        "--temp {}: standard input is read once, so a temperature cannot be read from it too; "
        "save the data to a file",
        c.temp_channel));
  }
}

struct Temperature {
  std::string channel;  ///< empty: none
  std::vector<double> values_c;
};

/// Reads the temperature that goes with `series` (or none, with a note).
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
  if (path == "-") {
    tell(
        "data from standard input: no temperature read, the systematic part is a constant "
        "(the record mean)");
    return {};
  }

  std::string name;
  if (!c.temp_channel.empty()) {
    const bool index = std::all_of(c.temp_channel.begin(), c.temp_channel.end(),
                                   [](unsigned char ch) { return std::isdigit(ch) != 0; });
    const auto found = find_channel(series.available_channels, c.temp_channel, true);
    if (!found && !index) {
      throw UsageError(fmt::format("--temp {}: '{}' has no channel '{}'; its channels are {}",
                                   c.temp_channel, path, c.temp_channel,
                                   fmt::join(series.available_channels, ", ")));
    }
    name = found ? *found : c.temp_channel;
  } else {
    const std::vector<std::string> wanted = paired_temperature_names(series.channel);
    for (const auto& w : wanted) {
      // The lab's T1, T2, T exactly; generate's "temperature" in any case.
      const auto found = find_channel(series.available_channels, w, w == "temperature");
      if (found && *found != series.channel) {
        name = *found;
        break;
      }
    }
    if (name.empty()) {
      tell(
          fmt::format("no temperature channel {} in '{}' (channels: {}): the systematic part is a "
                      "constant (the record mean); name one with --temp",
                      wanted.empty() ? std::string("paired with channel " + series.channel)
                                     : fmt::format("{}", fmt::join(wanted, " or ")),
                      path, fmt::join(series.available_channels, ", ")));
      return {};
    }
  }
  if (name == series.channel) {
    throw UsageError(
        fmt::format("--temp {}: the temperature cannot be the rate channel itself", name));
  }

  progress(fmt::format("reading temperature '{}' from '{}'", name, path));
  io::ReadOptions read;
  read.channel = name;
  read.sample_rate_hz = series.sample_rate_hz;  // the rate's, already checked
  read.format = io::input_format_from_string(c.input.format);
  read.unit = RateUnit::deg_per_hour;  // identity: degC stay degC
  read.time_channel = c.input.time_channel;
  io::Series t = io::read_series(path, read);
  if (t.values.size() != series.values.size()) {
    throw DataError(fmt::format(
        "'{}': the rate channel {} has {} samples but the temperature channel {} has {}; "
        "they must be sampled together",
        path, series.channel, series.values.size(), t.channel, t.values.size()));
  }
  return {t.channel, std::move(t.values)};
}

// ---- JSON ----------------------------------------------------------------

nlohmann::json parameter_json(const model::ParameterEstimate& p) {
  // Resolved: the two-sided interval; left out: the one-sided [0, bound].
  // An end the data do not close (infinite) is null: [lo, null].
  const bool interval = std::isfinite(p.ci95_low) && !std::isnan(p.ci95_high);
  return {{"value", number(p.value)},
          {"ci95", interval ? nlohmann::json::array({p.ci95_low, number(p.ci95_high)})
                            : nlohmann::json(nullptr)},
          {"status", std::string(model::to_string(p.status))},
          {"upper_95", number(p.upper_95)}};
}

nlohmann::json noise_model_values_json(const model::NoiseModel& m) {
  nlohmann::json j;
  for (const model::ReportedParameter& p : model::reported_parameters()) {
    j[std::string(p.name)] = m.*p.value;
  }
  return j;
}

nlohmann::json optional_json(const std::optional<double>& v) {
  return v ? number(*v) : nlohmann::json(nullptr);
}

nlohmann::json systematic_json(const model::AnalysisResult& r, const Temperature& temperature,
                               double record_mean_deg_h, const std::string& requested) {
  nlohmann::json j;
  if (r.systematic) {
    const model::SystematicFit& s = *r.systematic;
    j = {{"degree", s.degree},
         {"coefficients", numbers(s.coefficients)},
         {"standard_errors", numbers(s.standard_errors)},
         {"t_ref_c", number(s.t_ref_c)},
         {"bias_deg_h", number(s.bias_deg_h)},
         {"lab_constant_term_deg_h", number(s.lab_constant_term_deg_h)},
         {"lab_polyfit", numbers(s.lab_polyfit)},
         {"lab_constant_meaningful", s.lab_constant_meaningful},
         {"temperature_span_c", number(s.temperature_span_c)},
         {"temperature_min_c", number(s.temperature_min_c)},
         {"temperature_max_c", number(s.temperature_max_c)},
         {"constant_fallback", s.constant_fallback},
         {"degree_chosen", s.degree_chosen},
         {"criterion", numbers(s.criterion)},
         {"residual_rms_deg_h", number(s.residual_rms_deg_h)},
         {"note", s.note}};
  } else {
    j = {{"degree", 0},
         {"coefficients", nlohmann::json::array({number(record_mean_deg_h)})},
         {"standard_errors", nlohmann::json::array({nullptr})},
         {"t_ref_c", nullptr},
         {"bias_deg_h", number(record_mean_deg_h)},
         {"lab_constant_term_deg_h", nullptr},
         {"lab_polyfit", nullptr},
         {"lab_constant_meaningful", false},
         {"temperature_span_c", nullptr},
         {"temperature_min_c", nullptr},
         {"temperature_max_c", nullptr},
         {"constant_fallback", false},
         {"degree_chosen", false},
         {"criterion", nlohmann::json::array()},
         {"residual_rms_deg_h", nullptr},
         {"note",
          "no temperature: the systematic part is the record mean; t_ref_c, the lab's "
          "polyfit and the span are null"}};
  }
  j["temperature_channel"] =
      temperature.channel.empty() ? nlohmann::json(nullptr) : nlohmann::json(temperature.channel);
  j["degree_requested"] = requested;
  return j;
}

std::vector<double> model_adev(const model::AnalysisResult& r) {
  std::vector<double> out;
  out.reserve(r.allan.tau_s.size());
  for (const double tau : r.allan.tau_s) {
    out.push_back(std::sqrt(model::allan_variance(r.noise.model, tau)));
  }
  return out;
}

nlohmann::json allan_json(const model::AnalysisResult& r) {
  const stats::AllanResult& a = r.allan;
  return {{"kind", std::string(stats::to_string(a.kind))},
          {"tau_s", a.tau_s},
          {"adev_deg_h", numbers(a.dev)},
          {"ci95_low", numbers(a.ci95_low)},
          {"ci95_high", numbers(a.ci95_high)},
          {"ci68_low", numbers(a.ci68_low)},
          {"ci68_high", numbers(a.ci68_high)},
          {"n", a.n},
          {"m", a.m},
          {"alpha", a.alpha},
          {"edf", numbers(a.edf)},
          {"model_adev_deg_h", numbers(model_adev(r))},
          {"of", "the residual after the systematic part"}};
}

nlohmann::json psd_json(const model::AnalysisResult& r, double bins_per_decade) {
  const stats::PsdResult& p = r.psd_smoothed;
  return {{"frequency_hz", numbers(p.frequency_hz)},
          {"sqrt_psd_deg_h_per_sqrt_hz", numbers(p.sqrt_psd)},
          {"psd_deg2_h2_per_hz", numbers(p.psd)},
          {"sided", "two"},
          {"smoothing_bins_per_decade", bins_per_decade},
          {"window", "hann"},
          {"segment_length", r.psd.segment_length},
          {"segments", r.psd.segments},
          {"resolution_hz", r.psd.resolution_hz},
          {"of", "the residual after the systematic part"}};
}

nlohmann::json candidate_json(const model::CandidateModel& c) {
  return {{"terms", c.terms},
          {"deviance", number(c.deviance)},
          {"criterion", number(c.criterion)},
          {"parameters", c.parameters},
          {"model", noise_model_values_json(c.model)}};
}

nlohmann::json fit_json(const model::NoiseFitResult& f, const model::NoiseFitOptions& o) {
  nlohmann::json candidates = nlohmann::json::array();
  for (std::size_t k = 0; k < f.candidates.size() && k < kCandidatesListed; ++k) {
    candidates.push_back(candidate_json(f.candidates[k]));
  }
  return {{"terms", f.terms},
          {"deviance", number(f.deviance)},
          {"points", f.points},
          {"parameters", f.parameters},
          {"dispersion", number(f.dispersion)},
          {"penalty", o.penalty},
          {"model", noise_model_values_json(f.model)},
          {"candidates_total", f.candidates.size()},
          {"candidates", candidates}};
}

nlohmann::json evidence_json(const model::RandomBiasEvidence& e) {
  return {{"deviance_none", number(e.deviance_none)},
          {"deviance_wiener", number(e.deviance_wiener)},
          {"deviance_gauss_markov", number(e.deviance_gauss_markov)},
          {"criterion_none", number(e.criterion_none)},
          {"criterion_wiener", number(e.criterion_wiener)},
          {"criterion_gauss_markov", number(e.criterion_gauss_markov)},
          {"adev_end_slope", number(e.adev_end_slope)},
          {"psd_low_frequency_slope", number(e.psd_low_frequency_slope)},
          {"summary", e.summary}};
}

nlohmann::json units_json() {
  nlohmann::json units = {
      {"input.sample_rate_hz", "Hz"},
      {"input.duration_s", "s"},
      {"input.rate", "deg/h (converted on reading from input.units)"},
      {"input.temperature", "degC"},
      {"systematic.coefficients", "deg/h/degC^j, j = 0, 1, ... in powers of (T - t_ref_c)"},
      {"systematic.standard_errors", "deg/h/degC^j, as coefficients"},
      {"systematic.t_ref_c", "degC"},
      {"systematic.bias_deg_h", "deg/h"},
      {"systematic.lab_constant_term_deg_h", "deg/h"},
      {"systematic.lab_polyfit", "[deg/h/degC^2, deg/h/degC, deg/h] (MATLAB order, raw degC)"},
      {"systematic.temperature_span_c", "degC"},
      {"systematic.temperature_min_c", "degC"},
      {"systematic.temperature_max_c", "degC"},
      {"systematic.residual_rms_deg_h", "deg/h"},
      {"allan.tau_s", "s"},
      {"allan.adev_deg_h", "deg/h"},
      {"allan.ci95_low", "deg/h"},
      {"allan.ci95_high", "deg/h"},
      {"allan.ci68_low", "deg/h"},
      {"allan.ci68_high", "deg/h"},
      {"allan.model_adev_deg_h", "deg/h"},
      {"psd.frequency_hz", "Hz"},
      {"psd.sqrt_psd_deg_h_per_sqrt_hz", "deg/h/sqrt(Hz)"},
      {"psd.psd_deg2_h2_per_hz", "(deg/h)^2/Hz"},
      {"psd.resolution_hz", "Hz"},
      {"arw_deg_per_sqrt_h", "deg/sqrt(h)"},
      {"bias_instability_deg_h", "deg/h"},
      {"bias_instability_tau_s", "s"},
      {"readings.adev.N", "deg/h/sqrt(Hz)"},
      {"readings.adev.K", "deg/h/sqrt(s)"},
      {"readings.adev.B", "deg/h (the ADEV minimum)"},
      {"readings.adev.tau_s", "s"},
      {"readings.psd.N", "deg/h/sqrt(Hz)"},
      {"readings.psd.K", "deg/h/sqrt(s)"},
      {"random_bias_evidence.deviance_*", "gamma deviance (dimensionless)"},
      {"random_bias_evidence.criterion_*", "-2 ln L + penalty x parameters (dimensionless)"},
      {"systematic.criterion", "Wald statistic + penalty x degree (dimensionless)"},
      {"fit.deviance", "gamma deviance (dimensionless)"},
      {"fit.model", "N, B, K, R, Q, gm_sigma, gm_tc in the units above"},
      {"random_bias_evidence.adev_end_slope", "log-log slope (dimensionless)"},
      {"random_bias_evidence.psd_low_frequency_slope", "log-log slope (dimensionless)"}};
  for (const model::ReportedParameter& p : model::reported_parameters()) {
    units[std::string(p.name)] = p.unit;
  }
  return units;
}

nlohmann::json to_json(const model::AnalysisResult& r, const io::Series& series,
                       std::size_t samples, const Temperature& temperature,
                       double record_mean_deg_h, const AnalyzeCommand& c,
                       const model::AnalysisOptions& options,
                       const std::vector<std::string>& cli_notes) {
  nlohmann::json input = input_json(series);
  input["samples"] = samples;
  input["duration_s"] = r.duration_s;
  input["units"] = c.input.units;
  input["temperature_channel"] =
      temperature.channel.empty() ? nlohmann::json(nullptr) : nlohmann::json(temperature.channel);

  nlohmann::json noise;
  for (const model::ReportedParameter& p : model::reported_parameters()) {
    noise[std::string(p.name)] = parameter_json(r.noise.*p.estimate);
  }

  nlohmann::json readings = {
      {"adev",
       {{"N", optional_json(r.adev_readings.N)},
        {"K", optional_json(r.adev_readings.K)},
        {"B", number(r.adev_readings.bias_instability_deg_h)},
        {"tau_s", number(r.adev_readings.bias_instability_tau_s)},
        {"minimum_at_edge", r.adev_readings.minimum_at_edge}}},
      {"psd", {{"N", optional_json(r.psd_readings.N)}, {"K", optional_json(r.psd_readings.K)}}}};

  std::vector<std::string> notes = cli_notes;
  notes.insert(notes.end(), r.notes.begin(), r.notes.end());

  return {{"input", input},
          {"systematic", systematic_json(r, temperature, record_mean_deg_h, c.temp_degree)},
          {"allan", allan_json(r)},
          {"psd", psd_json(r, options.psd_bins_per_decade)},
          {"noise_model", noise},
          {"arw_deg_per_sqrt_h", number(r.arw_deg_sqrt_h)},
          {"bias_instability_deg_h", number(r.bias_instability_deg_h)},
          {"bias_instability_tau_s", number(r.bias_instability_tau_s)},
          {"bias_instability_at_edge", r.bias_instability_at_edge},
          {"random_bias_process", std::string(model::to_string(r.noise.random_bias_process))},
          {"random_bias_evidence", evidence_json(r.evidence)},
          {"readings", readings},
          {"accuracy_class", std::string(to_string(r.verdict.accuracy_class))},
          {"accuracy_class_decided_by", r.verdict.decided_by},
          {"class_by_bias_instability", std::string(to_string(r.verdict.by_bias_instability))},
          {"class_by_arw", std::string(to_string(r.verdict.by_arw))},
          {"fit", fit_json(r.noise, options.noise_fit)},
          {"notes", notes},
          {"options", {{"taus", c.taus}, {"temp_degree", c.temp_degree}}},
          {"units", units_json()},
          {"foglab_version", std::string(version())}};
}

// ---- CSV: the Allan table of the residual with the fitted model ----------

std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : ""; }

std::string to_csv(const model::AnalysisResult& r) {
  using model::NoiseTerm;
  constexpr NoiseTerm kTerms[] = {NoiseTerm::N, NoiseTerm::B, NoiseTerm::K,
                                  NoiseTerm::R, NoiseTerm::Q, NoiseTerm::gm};
  // The model's deviation, then each term's part of it (sqrt of its variance).
  std::string out =
      "tau_s,m,n,adev_deg_h,edf,ci95_low_deg_h,ci95_high_deg_h,model_adev_deg_h,"
      "model_N_deg_h,model_B_deg_h,model_K_deg_h,model_R_deg_h,model_Q_deg_h,model_gm_deg_h\n";
  const stats::AllanResult& a = r.allan;
  const std::vector<double> fitted = model_adev(r);
  for (std::size_t k = 0; k < a.tau_s.size(); ++k) {
    out += fmt::format("{:.10g},{},{},{},{},{},{},{}", a.tau_s[k], a.m[k], a.n[k], cell(a.dev[k]),
                       cell(a.edf[k]), cell(a.ci95_low[k]), cell(a.ci95_high[k]), cell(fitted[k]));
    for (const NoiseTerm t : kTerms) {
      out += ',';
      out += cell(std::sqrt(model::allan_variance(r.noise.model, t, a.tau_s[k])));
    }
    out += "\n";
  }
  return out;
}

// ---- the human-readable summary -------------------------------------------

std::string g(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return std::isfinite(v) ? fmt::format("{:.4g}", v) : "-";
}

std::string summary(const model::AnalysisResult& r, const io::Series& series, std::size_t samples,
                    const Temperature& temperature, double record_mean_deg_h,
                    const std::vector<std::string>& cli_notes) {
  std::string out = fmt::format(
      "foglab analyze: '{}' channel {}{} ({} samples at {} Hz, {:.4g} h)\n\n", series.path,
      series.channel,
      temperature.channel.empty() ? ", no temperature"
                                  : fmt::format(", temperature {}", temperature.channel),
      samples, series.sample_rate_hz, r.duration_s / 3600.0);

  out += "Systematic part\n";
  if (r.systematic) {
    const model::SystematicFit& s = *r.systematic;
    out += fmt::format("  polynomial of degree {} in (T - {:.4g} degC){}{}\n", s.degree, s.t_ref_c,
                       s.degree_chosen ? ", degree chosen by the criterion" : "",
                       s.constant_fallback ? ", constant fallback" : "");
    for (std::size_t j = 0; j < s.coefficients.size(); ++j) {
      const double se = j < s.standard_errors.size() ? s.standard_errors[j] : NAN;
      const std::string unit = j == 0   ? "deg/h"
                               : j == 1 ? "deg/h/degC"
                                        : fmt::format("deg/h/degC^{}", j);
      out += fmt::format("  c{} = {:>12.6g} +- {:<10} {}\n", j, s.coefficients[j], g(se), unit);
    }
    out += fmt::format("  bias at {:.4g} degC: {:.6g} deg/h; temperature span {:.4g} degC\n",
                       s.t_ref_c, s.bias_deg_h, s.temperature_span_c);
    out += fmt::format("  lab's polyfit(T, Y, 2) constant term: {:.6g} deg/h{}\n",
                       s.lab_constant_term_deg_h,
                       s.lab_constant_meaningful ? "" : " (not meaningful: the span is too small)");
    if (!s.note.empty()) out += "  " + s.note + "\n";
  } else {
    out += fmt::format("  no temperature: constant bias (record mean) {:.6g} deg/h\n",
                       record_mean_deg_h);
  }

  out += fmt::format(
      "\nNoise model (fit to the OADEV of the residual: terms {}, {} points, "
      "dispersion {:.3g})\n",
      r.noise.terms.empty() ? "none" : r.noise.terms, r.noise.points, r.noise.dispersion);
  out += fmt::format("  {:<9} {:>11}  {:<15} {:<12} {}\n", "parameter", "value", "unit", "status",
                     "95% interval");
  for (const model::ReportedParameter& row : model::reported_parameters()) {
    const model::ParameterEstimate& p = r.noise.*row.estimate;
    std::string value = g(p.value);
    std::string interval;
    if (p.status == model::TermStatus::resolved) {
      interval = fmt::format("[{}, {}]", g(p.ci95_low), g(p.ci95_high));
    } else if (p.status == model::TermStatus::upper_bound) {
      value = "< " + g(std::isfinite(p.upper_95) ? p.upper_95 : p.value);
      if (std::isfinite(p.ci95_high)) interval = fmt::format("[0, {}]", g(p.ci95_high));
    } else {
      value = "-";
      if (std::isfinite(p.upper_95)) interval = fmt::format("(< {})", g(p.upper_95));
    }
    out += fmt::format("  {:<9} {:>11}  {:<15} {:<12} {}\n", row.name, value, row.unit,
                       model::to_string(p.status), interval);
  }
  out += fmt::format("  ARW {} deg/sqrt(h); bias instability (ADEV minimum) {} deg/h at {} s{}\n",
                     g(r.arw_deg_sqrt_h), g(r.bias_instability_deg_h), g(r.bias_instability_tau_s),
                     r.bias_instability_at_edge ? " (at the end of the tau range)" : "");
  auto opt = [](const std::optional<double>& v) { return v ? g(*v) : std::string("not visible"); };
  out += fmt::format("  graphical readings: ADEV N {}, K {}, minimum {} deg/h; PSD N {}, K {}\n",
                     opt(r.adev_readings.N), opt(r.adev_readings.K),
                     g(r.adev_readings.bias_instability_deg_h), opt(r.psd_readings.N),
                     opt(r.psd_readings.K));

  out += fmt::format("\nRandom bias: {}\n", model::to_string(r.noise.random_bias_process));
  if (!r.evidence.summary.empty()) out += "  " + r.evidence.summary + "\n";
  out += fmt::format("\nAccuracy class: {} (decided by {}; by bias instability: {}, by ARW: {})\n",
                     to_string(r.verdict.accuracy_class), r.verdict.decided_by,
                     to_string(r.verdict.by_bias_instability), to_string(r.verdict.by_arw));
  std::vector<std::string> notes = cli_notes;
  for (const auto& n : r.notes) {
    if (!r.systematic || n != r.systematic->note) notes.push_back(n);  // that one is shown above
  }
  if (!notes.empty()) {
    out += "\nNotes\n";
    for (const auto& n : notes) out += "  - " + n + "\n";
  }
  return out;
}

// ---- the command ---------------------------------------------------------

void run(const AnalyzeCommand& c) {
  model::AnalysisOptions options;
  options.systematic.degree = parse_temp_degree(c.temp_degree);
  options.grid = stats::parse_tau_grid(c.taus);
  check_temperature_option(c);

  io::Series series = load_input(c.input);
  std::vector<std::string> notes;
  Temperature temperature = load_temperature(c, series, notes);
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
  const bool reporting = !c.report_path.empty() || !c.kalibr_path.empty();
  report::ReportInput report_input;
  if (reporting) {
    report_input.file_name = series.path;
    report_input.channel = series.channel;
    report_input.temperature_channel = temperature.channel;
    report_input.input_unit = c.input.units;
    report_input.notes = notes;
    if (!c.report_path.empty()) {
      report_input.preview =
          report::preview_record(series.values, temperature.values_c, series.sample_rate_hz);
    }
  }

  progress(fmt::format("analysing {} samples", samples));
  model::AnalysisResult result;
  try {
    result = model::analyze(series.values, temperature.values_c, series.sample_rate_hz, options);
  } catch (const DataError& e) {
    throw DataError(fmt::format("'{}' channel {}: {}", series.path, series.channel, e.what()));
  } catch (const UsageError& e) {
    throw UsageError(fmt::format("'{}' channel {}: {}", series.path, series.channel, e.what()));
  }
  series.values.clear();
  series.values.shrink_to_fit();

  // Render everything first, then write: a failure never leaves half the outputs.
  const std::string json = c.json_path.empty() ? ""
                                               : to_json(result, series, samples, temperature,
                                                         record_mean_deg_h, c, options, notes)
                                                         .dump(2) +
                                                     "\n";
  const std::string csv = c.csv_path.empty() ? "" : to_csv(result);
  std::string html, yaml;
  if (!c.report_path.empty()) {
    progress("drawing the report's plots");
    const report::ReportOptions report_options;
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
    std::cout << summary(result, series, samples, temperature, record_mean_deg_h, notes);
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
  cmd->add_option("--temp", c->temp_channel,
                  "temperature channel [degC]; default: the one paired with the rate channel "
                  "(Y1 -> T1, Y2 -> T2; 'rate' -> T or temperature)");
  cmd->add_option("--temp-degree", c->temp_degree,
                  "degree of the temperature polynomial: auto (information criterion), 0, 1, 2 "
                  "(the lab's polyfit) or 3")
      ->capture_default_str();
  cmd->add_option("--taus", c->taus,
                  "Allan tau grid: octave, decade, N-per-decade, or averaging times in s "
                  "(1,10,100)")
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
  return [c] { run(*c); };
}

}  // namespace foglab::cli
