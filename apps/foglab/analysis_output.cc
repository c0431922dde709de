// foglab CLI — JSON and CSV of an analysis (analysis_output.h).
#include "analysis_output.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

#include "cli_common.h"
#include "foglab/core/version.h"
#include "foglab/report/imu.h"
#include "foglab/report/report.h"

namespace foglab::cli {
namespace {

/// How many candidate models the JSON lists (best first).
constexpr std::size_t kCandidatesListed = 8;

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

nlohmann::json optional_json(const std::optional<double>& v) {
  return v ? number(*v) : nlohmann::json(nullptr);
}

nlohmann::json systematic_json(const model::AnalysisResult& r, const AnalysisJsonInput& in) {
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
         {"criterion_degree",
          s.criterion_degree < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.criterion_degree)},
         {"residual_rms_deg_h", number(s.residual_rms_deg_h)},
         {"note", s.note.text()}};
  } else {
    j = {{"degree", 0},
         {"coefficients", nlohmann::json::array({number(in.record_mean_deg_h)})},
         {"standard_errors", nlohmann::json::array({nullptr})},
         {"t_ref_c", nullptr},
         {"bias_deg_h", number(in.record_mean_deg_h)},
         {"lab_constant_term_deg_h", nullptr},
         {"lab_polyfit", nullptr},
         {"lab_constant_meaningful", false},
         {"temperature_span_c", nullptr},
         {"temperature_min_c", nullptr},
         {"temperature_max_c", nullptr},
         {"constant_fallback", false},
         {"degree_chosen", false},
         {"criterion", nlohmann::json::array()},
         {"criterion_degree", nullptr},
         {"residual_rms_deg_h", nullptr},
         {"note",
          "no temperature: the systematic part is the record mean; t_ref_c, the lab's "
          "polyfit and the span are null"}};
  }
  j["temperature_channel"] = in.temperature_channel.empty()
                                 ? nlohmann::json(nullptr)
                                 : nlohmann::json(in.temperature_channel);
  j["degree_requested"] = in.temp_degree;
  return j;
}

std::vector<double> model_adev(const model::AnalysisResult& r) {
  std::vector<double> out;
  out.reserve(r.allan.tau_s.size());
  for (const double tau : r.allan.tau_s) {
    out.push_back(std::sqrt(model::fitted_allan_variance(r.noise, tau)));
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
          {"edf_reduction", numbers(a.edf_reduction)},
          {"gap_spanning_terms", a.gap_spanning_terms},
          {"model_adev_deg_h", numbers(model_adev(r))},
          {"psd_adev_deg_h", numbers(r.psd_allan.adev_deg_h)},
          {"of", "the residual after the systematic part"}};
}

/// The manual's eq. (17): the fitted PSD's Allan deviation against the measured one.
nlohmann::json psd_allan_json(const model::PsdAllanCheck& c) {
  return {{"compared", c.compared},
          {"inside_95", c.inside_95},
          {"worst_tau_s", number(c.worst_tau_s)},
          {"worst_ratio", number(c.worst_ratio)},
          {"worst_half_widths", number(c.worst_half_widths)}};
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
  return {{"terms", to_string(c.terms)},
          {"deviance", number(c.deviance)},
          {"criterion", number(c.criterion)},
          {"parameters", c.parameters},
          {"status", std::string(model::to_string(c.status))},
          {"iterations", c.iterations},
          {"model", noise_model_json(c.model)}};
}

nlohmann::json fit_json(const model::NoiseFitResult& f, const model::NoiseFitOptions& o) {
  nlohmann::json candidates = nlohmann::json::array();
  for (std::size_t k = 0; k < f.candidates.size() && k < kCandidatesListed; ++k) {
    candidates.push_back(candidate_json(f.candidates[k]));
  }
  return {{"status", std::string(model::to_string(f.status))},
          {"message", f.message},
          {"iterations", f.iterations},
          {"tolerance", o.tolerance},
          {"max_iterations", o.max_iterations},
          {"terms", to_string(f.terms)},
          {"deviance", number(f.deviance)},
          {"points", f.points},
          {"parameters", f.parameters},
          {"dispersion", number(f.dispersion)},
          {"penalty", o.penalty},
          {"model", noise_model_json(f.model)},
          {"candidates_total", f.candidates.size()},
          {"candidates", candidates},
          {"ramp_set_aside", f.ramp_set_aside.empty() ? nlohmann::json(nullptr)
                                                      : nlohmann::json(f.ramp_set_aside.text())},
          {"first_taus_left_out", f.first_taus_left_out},
          {"first_taus_left_out_why", f.first_taus_left_out_why.empty()
                                          ? nlohmann::json(nullptr)
                                          : nlohmann::json(f.first_taus_left_out_why.text())},
          {"shape_free_taus_left_out", f.shape_free_taus_left_out < 0
                                           ? nlohmann::json(nullptr)
                                           : nlohmann::json(f.shape_free_taus_left_out)},
          {"shape_free_N", number(f.shape_free_n)}};
}

nlohmann::json bandwidth_json(const model::BandwidthEstimate& b) {
  if (!b.resolved) {
    return {{"resolved", false},
            {"deviance_drop", number(b.deviance_drop)},
            {"correlated_deviance_drop", number(b.correlated_deviance_drop)},
            {"at_search_bound", b.at_search_bound}};
  }
  const bool ma = b.bandwidth.moving_average(), bw = b.bandwidth.butterworth(),
             memory = b.bandwidth.beyond_memory();
  return {{"resolved", true},
          {"kind", ma       ? "moving_average"
                   : bw     ? "butterworth_second_order"
                   : memory ? "beyond_memory"
                            : "first_order"},
          {"moving_average_samples", b.bandwidth.moving_average_samples},
          {"time_constant_s",
           ma || bw || memory ? nlohmann::json(nullptr) : number(b.bandwidth.time_constant_s)},
          {"memory_constant_samples",
           memory ? number(b.bandwidth.memory_constant_samples) : nlohmann::json(nullptr)},
          {"cutoff_hz", number(b.cutoff_hz)},
          {"filtered_fraction", number(b.bandwidth.filtered_fraction)},
          {"lag1_correlation", number(b.lag1_correlation)},
          {"first_tau_reduction", number(b.first_tau_reduction)},
          {"sample_interval_s", number(b.sample_interval_s)},
          {"deviance_drop", number(b.deviance_drop)},
          {"correlated_deviance_drop", number(b.correlated_deviance_drop)},
          {"at_search_bound", b.at_search_bound}};
}

nlohmann::json spikes_json(const model::AnalysisResult& r) {
  const model::Spikes& s = r.spikes;
  std::vector<double> times;
  for (std::int64_t k : s.indices) times.push_back(elapsed_s(k, r.gaps, r.sample_rate_hz));
  return {
      {"count", s.count},
      {"removed", s.removed},
      {"robust_sd_deg_h", number(s.robust_sd_deg_h)},
      {"threshold_deg_h", number(s.threshold_deg_h)},
      {"times_s", times},
      {"sizes_deg_h", numbers(s.sizes_deg_h)},
      {"shoulder_count", s.shoulder_count},
      {"shoulder_expected", number(s.shoulder_expected)},
      {"heavy_tailed", s.heavy_tailed},
      {"tail_index", s.heavy_tailed ? number(s.tail_index) : nlohmann::json(nullptr)},
      {"excess_kurtosis", s.heavy_tailed ? number(s.excess_kurtosis) : nlohmann::json(nullptr)}};
}

// Why the jumps were left in as the bias's process (null: they are steps).
nlohmann::json because(model::BiasSteps::AsNoise why) {
  using AsNoise = model::BiasSteps::AsNoise;
  switch (why) {
    case AsNoise::beyond_limit:
      return "more_than_the_limit";
    case AsNoise::wander:
      return "levelling_adds_wander";
    case AsNoise::two_levels:
      return "two_levels";
    case AsNoise::none:
      break;
  }
  return nullptr;
}

nlohmann::json steps_json(const model::AnalysisResult& r) {
  const model::BiasSteps& s = r.steps;
  std::vector<double> times;
  for (std::int64_t k : s.indices) times.push_back(elapsed_s(k, r.gaps, r.sample_rate_hz));
  nlohmann::json across = nlohmann::json::array();
  for (const model::GapJump& j : s.across_gaps) {
    across.push_back({{"before_sample", j.before_sample},
                      {"time_s", elapsed_s(j.before_sample, r.gaps, r.sample_rate_hz)},
                      {"size_deg_h", number(j.size_deg_h)},
                      {"window_samples", j.window_samples},
                      {"significance", number(j.significance)},
                      {"significant", j.significant}});
  }
  return {{"count", s.indices.size()},
          {"removed", s.removed},
          {"left_as_noise", s.left_as_noise()},
          {"left_as_noise_because", because(s.left_as_noise_because)},
          {"at_temperature_turns", s.at_temperature_turns},
          {"times_s", times},
          {"sizes_deg_h", numbers(s.sizes_deg_h)},
          {"window_samples", s.window_samples},
          {"significance", numbers(s.significance)},
          {"across_gaps", across}};
}

nlohmann::json temperature_quantisation_json(const model::TemperatureQuantisation& t) {
  nlohmann::json j = {{"detected", t.detected}};
  if (!t.detected) return j;
  j["lsb_c"] = number(t.lsb_c);
  j["distinct_values"] = t.distinct_values;
  j["changes"] = t.changes;
  j["mean_hold_s"] = number(t.mean_hold_s);
  return j;
}

nlohmann::json quantisation_json(const model::AnalysisResult& r) {
  const model::OutputQuantisation& q = r.output_quantisation;
  nlohmann::json j = {{"detected", q.detected},
                      {"distinct_values", q.distinct_values},
                      {"samples_examined", q.samples_examined}};
  if (!q.detected) return j;
  const double n = r.noise.model.N;
  j["lsb_deg_h"] = number(q.lsb_deg_h);
  j["white_level_deg_h_sqrt_hz"] = number(q.white_level_deg_h_sqrt_hz);
  j["share_of_white_variance"] = number(n > 0 ? std::pow(q.white_level_deg_h_sqrt_hz / n, 2)
                                              : std::nan(""));  // of the sensor's
  j["sample_sd_deg_h"] = number(q.sample_sd_deg_h);
  j["step_sd_deg_h"] = number(q.step_sd_deg_h);
  j["noise_like"] = q.noise_like;
  j["white_variance_departure"] = number(q.white_variance_departure);
  j["taken_out_of_N"] = r.noise.known_white_deg_h_sqrt_hz > 0.0;
  return j;
}

// A periodic disturbance's harmonics above the first, taken out with it.
nlohmann::json harmonics_json(const SpectralLine& line) {
  nlohmann::json harmonics = nlohmann::json::array();
  for (const LineHarmonic& h : line.harmonics) {
    harmonics.push_back({{"number", h.number},
                         {"frequency_hz", number(h.number * line.frequency_hz)},
                         {"amplitude_deg_h", number(h.amplitude_deg_h)},
                         {"phase_rad", number(h.phase_rad)}});
  }
  return harmonics;
}

nlohmann::json lines_json(const model::NoiseFitResult& f) {
  nlohmann::json lines = nlohmann::json::array();
  for (const SpectralLine& line : f.lines) {
    lines.push_back(
        {{"frequency_hz", number(line.frequency_hz)},
         {"width_hz", number(line.width_hz)},
         {"rms_deg_h", number(std::sqrt(line.variance))},
         {"peak_ratio", number(line.peak_ratio)},
         {"variance_scale", number(line.takes_variance_scale ? f.line_variance_scale : 1.0)},
         {"removed_from_record", line.removed_from_record},
         {"amplitude_deg_h",
          line.removed_from_record ? number(line.amplitude_deg_h) : nlohmann::json(nullptr)},
         {"phase_rad", line.removed_from_record ? number(line.phase_rad) : nlohmann::json(nullptr)},
         {"harmonics", harmonics_json(line)},
         {"adev_at_quarter_period_deg_h",
          number(std::sqrt(line_allan_variance(line, 0.371 / line.frequency_hz,
                                               f.bandwidth.sample_interval_s)))}});
  }
  return lines;
}

nlohmann::json drift_json(const stats::AllanDrift& d) {
  nlohmann::json block_adev = nlohmann::json::array();
  for (const std::vector<double>& per_block : d.block_adev)
    block_adev.push_back(numbers(per_block));
  return {{"blocks", d.blocks},
          {"z_threshold", number(d.z_threshold)},
          {"tau_s", numbers(d.tau_s)},
          {"trend_z", numbers(d.trend_z)},
          {"last_to_first_ratio", numbers(d.last_to_first)},
          {"drifting", d.drifting},
          {"blocks_used", d.blocks_used},
          {"block_time_s", numbers(d.block_time_s)},
          {"block_adev_deg_h", std::move(block_adev)}};
}

nlohmann::json evidence_json(const model::RandomBiasEvidence& e, const model::NoiseFitResult& fit) {
  return {{"deviance_none", number(e.deviance_none)},
          {"deviance_wiener", number(e.deviance_wiener)},
          {"deviance_gauss_markov", number(e.deviance_gauss_markov)},
          {"criterion_none", number(e.criterion_none)},
          {"criterion_wiener", number(e.criterion_wiener)},
          {"criterion_gauss_markov", number(e.criterion_gauss_markov)},
          {"adev_end_slope", number(e.adev_end_slope)},
          {"psd_low_frequency_slope", number(e.psd_low_frequency_slope)},
          {"gauss_markov_set_aside", fit.gauss_markov_set_aside.empty()
                                         ? nlohmann::json(nullptr)
                                         : nlohmann::json(fit.gauss_markov_set_aside.text())},
          {"summary", e.summary.text()}};
}

nlohmann::json units_json() {
  nlohmann::json units = {
      {"input.sample_rate_hz", "Hz"},
      {"steps.times_s", "s"},
      {"steps.sizes_deg_h", "deg/h"},
      {"steps.window_samples", "samples"},
      {"steps.significance", "1 (robust spreads)"},
      {"steps.across_gaps[].time_s", "s"},
      {"steps.across_gaps[].size_deg_h", "deg/h"},
      {"steps.across_gaps[].window_samples", "samples"},
      {"steps.across_gaps[].significance", "1 (robust spreads)"},
      {"spikes.robust_sd_deg_h", "deg/h"},
      {"spikes.threshold_deg_h", "deg/h"},
      {"spikes.times_s", "s"},
      {"spikes.sizes_deg_h", "deg/h"},
      {"spikes.shoulder_count", "samples"},
      {"spikes.shoulder_expected", "samples"},
      {"spikes.tail_index", "1 (exponent of the tail's power law)"},
      {"spikes.excess_kurtosis", "1"},
      {"output_quantisation.lsb_deg_h", "deg/h"},
      {"output_quantisation.white_level_deg_h_sqrt_hz", "deg/h/sqrt(Hz)"},
      {"output_quantisation.share_of_white_variance", "1 (of N^2)"},
      {"output_quantisation.sample_sd_deg_h", "deg/h"},
      {"output_quantisation.step_sd_deg_h", "deg/h"},
      {"output_quantisation.white_variance_departure", "1 (of the sensor's white variance)"},
      {"temperature_quantisation.lsb_c", "degC"},
      {"temperature_quantisation.mean_hold_s", "s"},
      {"spectral_lines[].frequency_hz", "Hz"},
      {"spectral_lines[].width_hz", "Hz"},
      {"spectral_lines[].rms_deg_h", "deg/h"},
      {"spectral_lines[].peak_ratio", "1 (PSD over the noise floor)"},
      {"spectral_lines[].amplitude_deg_h", "deg/h"},
      {"spectral_lines[].phase_rad", "rad"},
      {"spectral_lines[].harmonics[].frequency_hz", "Hz"},
      {"spectral_lines[].harmonics[].amplitude_deg_h", "deg/h"},
      {"spectral_lines[].harmonics[].phase_rad", "rad"},
      {"spectral_lines[].adev_at_quarter_period_deg_h", "deg/h"},
      {"sensor_bandwidth.time_constant_s", "s"},
      {"sensor_bandwidth.memory_constant_samples", "samples"},
      {"sensor_bandwidth.cutoff_hz", "Hz"},
      {"sensor_bandwidth.sample_interval_s", "s"},
      {"sensor_bandwidth.filtered_fraction", "1 (fraction of N^2)"},
      {"sensor_bandwidth.lag1_correlation", "1"},
      {"sensor_bandwidth.first_tau_reduction", "1 (fraction of the first tau's Allan variance)"},
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
      {"allan.psd_adev_deg_h", "deg/h (eq. 17 on the fitted PSD)"},
      {"psd_allan_check.worst_tau_s", "s"},
      {"psd_allan_check.worst_ratio", "eq. 17 / measured ADEV (dimensionless)"},
      {"psd_allan_check.worst_half_widths",
       "log distance over the 95 % half-width (dimensionless)"},
      {"psd.frequency_hz", "Hz"},
      {"psd.sqrt_psd_deg_h_per_sqrt_hz", "deg/h/sqrt(Hz)"},
      {"psd.psd_deg2_h2_per_hz", "(deg/h)^2/Hz"},
      {"psd.resolution_hz", "Hz"},
      {"arw_deg_per_sqrt_h", "deg/sqrt(h)"},
      {"bias_instability_deg_h", "deg/h"},
      {"bias_instability_tau_s", "s"},
      {"bias_instability_from_tau_s", "s"},
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
      {"fit.tolerance", "relative change of the fitted Allan variances (dimensionless)"},
      {"fit.shape_free_N", "deg/h/sqrt(Hz)"},
      {"fit.model", "N, B, K, R, Q, gm_sigma, gm_tc in the units above"},
      {"random_bias_evidence.adev_end_slope", "log-log slope (dimensionless)"},
      {"allan_drift.tau_s", "s"},
      {"allan_drift.trend_z", "Mann-Kendall z of the blocks' Allan variances (dimensionless)"},
      {"allan_drift.last_to_first_ratio", "ratio of Allan variances (dimensionless)"},
      {"allan_drift.block_time_s", "s"},
      {"allan_drift.block_adev_deg_h", "deg/h"},
      {"random_bias_evidence.psd_low_frequency_slope", "log-log slope (dimensionless)"}};
  for (const NoiseParameter& p : kNoiseParameters) units[std::string(p.name)] = p.unit;
  return units;
}

}  // namespace

nlohmann::json analysis_json(const model::AnalysisResult& r, const AnalysisJsonInput& in,
                             const model::AnalysisOptions& options) {
  nlohmann::json input = in.input;
  input["samples"] = r.samples;
  input["duration_s"] = r.duration_s;
  input["units"] = in.units;
  input["temperature_channel"] = in.temperature_channel.empty()
                                     ? nlohmann::json(nullptr)
                                     : nlohmann::json(in.temperature_channel);
  if (!r.allan.gap_spanning_terms.empty() && input.contains("gaps")) {
    input["gaps"]["treatment"] = fmt::format(
        "contiguous stretches: Welch segments spanning a gap are left out, and Allan terms "
        "too unless each of their two clusters misses at most {:g} % of its samples (each "
        "cluster's mean over the samples it has; allan.gap_spanning_terms counts them); "
        "nothing is interpolated",
        100.0 * options.max_missing_share);
  }

  nlohmann::json noise;
  for (const NoiseParameter& p : kNoiseParameters) {
    noise[std::string(p.name)] = parameter_json(r.noise.estimate(p));
  }

  nlohmann::json readings = {
      {"adev",
       {{"N", optional_json(r.adev_readings.N)},
        {"K", optional_json(r.adev_readings.K)},
        {"B", number(r.adev_readings.bias_instability_deg_h)},
        {"tau_s", number(r.adev_readings.bias_instability_tau_s)},
        {"minimum_at_edge", r.adev_readings.minimum_at_edge}}},
      {"psd", {{"N", optional_json(r.psd_readings.N)}, {"K", optional_json(r.psd_readings.K)}}}};

  std::vector<std::string> notes = in.notes;
  for (const Message& n : r.notes) notes.push_back(n.text());

  return {{"input", input},
          {"systematic", systematic_json(r, in)},
          {"allan", allan_json(r)},
          {"allan_drift", drift_json(r.allan_drift)},
          {"psd", psd_json(r, options.psd_bins_per_decade)},
          {"noise_model", noise},
          {"sensor_bandwidth", bandwidth_json(r.noise.bandwidth)},
          {"spectral_lines", lines_json(r.noise)},
          {"psd_allan_check", psd_allan_json(r.psd_allan)},
          {"output_quantisation", quantisation_json(r)},
          {"temperature_quantisation", temperature_quantisation_json(r.temperature_quantisation)},
          {"spikes", spikes_json(r)},
          {"steps", steps_json(r)},
          {"arw_deg_per_sqrt_h", number(r.arw_deg_sqrt_h)},
          {"bias_instability_deg_h", number(r.bias_instability_deg_h)},
          {"bias_instability_tau_s", number(r.bias_instability_tau_s)},
          {"bias_instability_at_edge", r.bias_instability_at_edge},
          {"bias_instability_from_tau_s", number(r.bias_instability_from_tau_s)},
          {"random_bias_process", std::string(to_string(r.noise.random_bias_process))},
          {"random_bias_evidence", evidence_json(r.evidence, r.noise)},
          {"readings", readings},
          {"accuracy_class", std::string(to_string(r.verdict.accuracy_class))},
          {"accuracy_class_decided_by", std::string(to_string(r.verdict.decided_by))},
          {"class_by_bias_instability", std::string(to_string(r.verdict.by_bias_instability))},
          {"class_by_arw", std::string(to_string(r.verdict.by_arw))},
          {"fit", fit_json(r.noise, options.noise_fit)},
          {"notes", notes},
          {"options",
           {{"taus", in.taus},
            {"temp_degree", in.temp_degree},
            {"max_missing_percent", 100.0 * options.max_missing_share}}},
          {"units", units_json()},
          {"foglab_version", std::string(version())}};
}

namespace {

/// `key` with its rate unit in the accelerometer's: deg_h -> m_s2,
/// deg2_h2 -> m2_s4.
std::string accelerometer_key(std::string key) {
  for (const auto& [from, to] :
       {std::pair<std::string_view, std::string_view>{"deg2_h2", "m2_s4"}, {"deg_h", "m_s2"}}) {
    for (std::size_t at = key.find(from); at != std::string::npos;
         at = key.find(from, at + to.size())) {
      key.replace(at, from.size(), to);
    }
  }
  return key;
}

nlohmann::json in_accelerometer_terms(const nlohmann::json& j) {
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : j.items()) {
      out[accelerometer_key(key)] = in_accelerometer_terms(value);
    }
    return out;
  }
  if (j.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& value : j) out.push_back(in_accelerometer_terms(value));
    return out;
  }
  if (j.is_string()) return in_sensor_units(j.get<std::string>(), Sensor::accelerometer);
  return j;
}

}  // namespace

nlohmann::json accelerometer_json(nlohmann::json gyro_form) {
  // The class and the angle random walk are a gyroscope's; the velocity
  // random walk (sensor_terms_json()) takes the latter's place.
  gyro_form.erase("arw_deg_per_sqrt_h");
  if (gyro_form.contains("units")) gyro_form["units"].erase("arw_deg_per_sqrt_h");
  for (const char* key : {"accuracy_class", "accuracy_class_decided_by",
                          "class_by_bias_instability", "class_by_arw"}) {
    gyro_form[key] = nullptr;
  }
  nlohmann::json out = in_accelerometer_terms(gyro_form);
  out["accuracy_class_note"] = std::string(report::kNoAccelerometerClass);
  return out;
}

nlohmann::json sensor_terms_json(const model::AnalysisResult& r, Sensor sensor) {
  const report::FilterNoise f = report::filter_noise(r, sensor);
  const double factor = report::kalibr_factor(sensor);
  const double fs = r.sample_rate_hz;
  const bool gyro = sensor == Sensor::gyroscope;
  const std::string density =
      gyro ? "noise_density_rad_s_per_sqrt_hz" : "noise_density_m_s2_per_sqrt_hz";
  const std::string walk = gyro ? "random_walk_rad_s2_per_sqrt_hz" : "random_walk_m_s3_per_sqrt_hz";
  const std::string per_sample = gyro ? "_rad_s" : "_m_s2";
  nlohmann::json j = {
      {density, number(f.white * factor)},
      {density + "_resolved", f.white_resolved},
      {density + "_from", f.white_source},
      {walk, number(f.random_walk * factor)},
      {walk + "_resolved", f.random_walk_resolved},
      {walk + "_from", f.random_walk_source},
      {"white_noise_per_sample" + per_sample, number(f.white * factor * std::sqrt(fs))},
      {"random_walk_per_sample" + per_sample, number(f.random_walk * factor / std::sqrt(fs))},
      {"sample_rate_hz", fs},
      {"of",
       "continuous-time densities in Kalibr's units; per sample: the standard deviation at the "
       "sample rate (white: density x sqrt(rate); random walk: K / sqrt(rate))"}};
  if (gyro) {
    j["arw_deg_per_sqrt_h"] = number(r.arw_deg_sqrt_h);
    j["bias_instability_deg_h"] = number(r.bias_instability_deg_h);
  } else {
    j["velocity_random_walk_m_s_per_sqrt_h"] =
        number(report::velocity_random_walk_m_s_sqrt_h(f.white));
    j["bias_instability_m_s2"] = number(r.bias_instability_deg_h);
    j["bias_instability_mg"] = number(r.bias_instability_deg_h / kStandardGravity * 1000.0);
  }
  return j;
}

// ---- CSV: the Allan table of the residual with the fitted model ----------

std::string analysis_csv(const model::AnalysisResult& r) {
  // The model's deviation, then each term's part of it (sqrt of its variance).
  std::string out =
      "tau_s,m,n,adev_deg_h,edf,ci95_low_deg_h,ci95_high_deg_h,model_adev_deg_h,"
      "model_N_deg_h,model_B_deg_h,model_K_deg_h,model_R_deg_h,model_Q_deg_h,model_gm_deg_h\n";
  const stats::AllanResult& a = r.allan;
  const std::vector<double> fitted = model_adev(r);
  for (std::size_t k = 0; k < a.tau_s.size(); ++k) {
    out += fmt::format("{:.10g},{},{},{},{},{},{},{}", a.tau_s[k], a.m[k], a.n[k],
                       csv_number(a.dev[k]), csv_number(a.edf[k]), csv_number(a.ci95_low[k]),
                       csv_number(a.ci95_high[k]), csv_number(fitted[k]));
    for (const NoiseTerm t : kNoiseTerms) {
      out += ',';
      out += csv_number(std::sqrt(model::fitted_allan_variance(r.noise, t, a.tau_s[k])));
    }
    out += "\n";
  }
  return out;
}

nlohmann::json parameter_estimate_json(const model::ParameterEstimate& p) {
  return parameter_json(p);
}

nlohmann::json noise_fit_json(const model::NoiseFitResult& f, const model::NoiseFitOptions& o) {
  return fit_json(f, o);
}

}  // namespace foglab::cli
