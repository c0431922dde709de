// foglab — the report of one analysed recording (report.h).
#include "foglab/report/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <limits>
#include <numbers>
#include <utility>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/units.h"
#include "foglab/core/version.h"
#include "foglab/report/imu.h"
#include "report_internal.h"

namespace foglab::report {

namespace detail {

// ---- shared with lab2.cc (report_internal.h) ----------------------------------

std::string g(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "-"; }
std::string g(const std::optional<double>& v, Language language) {
  return v ? g(*v) : say(language, Text::an_not_visible);
}

ParameterText parameter_text(const model::ParameterEstimate& p, Language language) {
  ParameterText t;
  if (p.status == model::TermStatus::resolved) {
    t.value = g(p.value);
    t.interval = fmt::format("[{}, {}]", g(p.ci95_low), g(p.ci95_high));
  } else if (p.status == model::TermStatus::upper_bound) {
    const double bound = std::isfinite(p.upper_95) ? p.upper_95 : p.value;
    t.value = std::isfinite(bound) ? "< " + g(bound) : "-";
    t.interval = std::isfinite(p.ci95_high) ? fmt::format("[0, {}]", g(p.ci95_high))
                                            : say(language, Text::an_no_bound);
  } else {
    t.value = "-";
    if (std::isfinite(p.upper_95)) t.interval = fmt::format("(< {})", g(p.upper_95));
  }
  // A Gauss-Markov Tc left out may still have the interval of the close
  // Gauss-Markov candidates (noise_fit.h), not one-sided from 0.
  if (p.status != model::TermStatus::resolved && p.ci95_low > 0.0) {
    t.interval = fmt::format("[{}, {}]", g(p.ci95_low), g(p.ci95_high));
  }
  return t;
}

/// The eq. (17) check in a sentence: how many taus it meets within the
/// measured 95 % intervals and its largest disagreement.
std::string eq17_sentence(const model::PsdAllanCheck& c, Language language) {
  if (c.compared == 0) return say(language, Text::an_eq17_none);
  return say(language, Text::an_eq17_value, c.inside_95, c.compared, 100.0 * (c.worst_ratio - 1.0),
             g(c.worst_tau_s), c.worst_half_widths);
}

/// The manual's way of reading K and writing the quantisation term beside
/// foglab's, with both numbers (docs/manual_notes.md): a sentence each,
/// where the record shows them.
std::vector<std::string> manual_conventions(const model::AnalysisResult& r, Language language) {
  std::vector<std::string> out;
  if (r.adev_readings.K || r.psd_readings.K) {
    out.push_back(say(language, Text::an_manual_k,
                      r.adev_readings.K ? g(*r.adev_readings.K / std::sqrt(3.0)) : "-",
                      r.psd_readings.K ? g(*r.psd_readings.K / (2.0 * std::numbers::pi)) : "-"));
  }
  if (r.noise.Q.status == model::TermStatus::resolved) {
    out.push_back(
        say(language, Text::an_manual_q, g(std::sqrt(3.0) * r.noise.Q.value), g(r.noise.Q.value)));
  }
  return out;
}

std::string random_bias_answer(const model::AnalysisResult& r, Language language) {
  switch (r.noise.random_bias_process) {
    case RandomBiasProcess::wiener:
      return say(language, Text::an_random_bias_wiener, parameter_text(r.noise.K, language).value);
    case RandomBiasProcess::gauss_markov:
      return say(language, Text::an_random_bias_gauss_markov,
                 parameter_text(r.noise.gm_sigma, language).value,
                 parameter_text(r.noise.gm_tc, language).value);
    case RandomBiasProcess::none:
      break;
  }
  return say(language, Text::an_random_bias_none);
}

std::string bandwidth_sentence(const model::NoiseFitResult& fit, Language language) {
  const model::BandwidthEstimate& b = fit.bandwidth;
  if (!b.resolved) return say(language, Text::an_bandwidth_none);
  const std::string percent = g(100.0 * b.bandwidth.filtered_fraction);
  const std::string lag1 = g(b.lag1_correlation);
  const std::string lowered = g(100.0 * b.first_tau_reduction);
  if (b.bandwidth.beyond_memory()) {
    return say(language, Text::an_bandwidth_beyond_memory, g(b.bandwidth.memory_constant_samples),
               g(b.cutoff_hz), lowered);
  }
  std::string kind =
      b.bandwidth.moving_average()
          ? say(language, Text::an_bandwidth_moving_average, b.bandwidth.moving_average_samples,
                g(b.cutoff_hz), percent, lag1, lowered)
      : b.bandwidth.butterworth()
          ? say(language, Text::an_bandwidth_butterworth, g(b.cutoff_hz), percent, lag1, lowered)
          : say(language, Text::an_bandwidth_first_order, g(b.bandwidth.time_constant_s),
                g(b.cutoff_hz), percent, lag1, lowered);
  if (fit.shape_free_taus_left_out == 0) {
    kind += say(language, Text::an_bandwidth_shape_free_all);
  } else if (fit.shape_free_taus_left_out > 0) {
    kind += say(language, Text::an_bandwidth_shape_free, fit.shape_free_taus_left_out);
  }
  if (std::isfinite(fit.shape_free_n)) {  // set only where that fit was made
    kind += say(language, Text::an_bandwidth_shape_free_n, g(fit.shape_free_n));
    // Past what the two differ by where the kind is right (within 0.3 % at
    // 100 Hz, 3.9 % at 1 Hz; docs/validation.md): say that the shape decides.
    constexpr double kDecides = 0.05;
    if (const double n = fit.model.N; n > 0.0 && std::fabs(fit.shape_free_n / n - 1.0) > kDecides) {
      kind += say(language, Text::an_bandwidth_shape_decides,
                  fmt::format("{:+.0f}", 100.0 * (fit.shape_free_n / n - 1.0)));
    }
  }
  return kind;
}

std::string lines_sentence(const model::NoiseFitResult& fit, Language language) {
  if (fit.lines.empty()) return say(language, Text::an_lines_none);
  std::string text;
  bool kept = false;  // a line whose Allan variance the fit took
  for (const SpectralLine& line : fit.lines) {
    if (!text.empty()) text += "; ";
    kept = kept || !line.removed_from_record;
    if (!line.harmonics.empty()) {
      text += say(language, Text::an_line_removed_periodic, g(line.frequency_hz),
                  g(1.0 / line.frequency_hz), g(std::sqrt(line.variance)), g(line.amplitude_deg_h),
                  line.harmonics.size(), line.harmonics.back().number, g(line.peak_ratio));
    } else if (line.removed_from_record) {
      text += say(language, Text::an_line_removed, g(line.frequency_hz), g(1.0 / line.frequency_hz),
                  g(line.amplitude_deg_h), g(std::sqrt(line.variance)), g(line.peak_ratio));
    } else if (line.frequency_hz < 1.0) {  // a slow line's period reads better
      text += say(language, Text::an_line_slow, g(line.frequency_hz), g(1.0 / line.frequency_hz),
                  g(line.width_hz), g(std::sqrt(line.variance)), g(line.peak_ratio));
    } else {
      text += say(language, Text::an_line, g(line.frequency_hz), g(line.width_hz),
                  g(std::sqrt(line.variance)), g(line.peak_ratio));
    }
  }
  if (fit.line_variance_scale != 1.0) {
    text += say(language, Text::an_lines_scale, g(fit.line_variance_scale));
  }
  return kept ? text + say(language, Text::an_lines_tail) : text;
}

std::string called_taus(const stats::AllanDriftCalls& c, std::string_view separator) {
  std::string taus;
  for (const double tau : c.tau_s) taus += (taus.empty() ? "" : std::string(separator)) + g(tau);
  return taus;
}

// The short taus' stationarity check (stats/allan_drift.h) in one sentence:
// said when it passes too, so that a reader knows it was made.
std::string stationarity_sentence(const stats::AllanDrift& d, Language language) {
  if (d.tau_s.empty()) return say(language, Text::an_drift_unchecked);
  const stats::AllanDriftCalls c = d.calls();
  if (c.tau_s.empty()) {
    return say(language, Text::an_drift_steady, g(d.tau_s.front()), g(d.tau_s.back()), d.blocks,
               fmt::format("{:.2f}", c.largest_z), fmt::format("{:.3g}", d.z_threshold));
  }
  return say(language, Text::an_drift_trend, called_taus(c),
             range_message(c.z_low, c.z_high).text(language),
             range_message(c.ratio_low, c.ratio_high).text(language));
}

std::string drift_cell(const stats::AllanDriftCalls& calls, bool checked) {
  if (!checked) return "not checked";
  if (calls.tau_s.empty()) return fmt::format("none (z within ±{:.2f})", calls.largest_z);
  return fmt::format("{} s (last/first {})", called_taus(calls),
                     range_message(calls.ratio_low, calls.ratio_high).text(Language::en));
}

std::string drift_cell(const stats::AllanDrift& d) {
  return drift_cell(d.calls(), !d.tau_s.empty());
}

std::string class_name(AccuracyClass c, Language language) {
  switch (c) {
    case AccuracyClass::strategic:
      return say(language, Text::an_class_strategic);
    case AccuracyClass::navigation:
      return say(language, Text::an_class_navigation);
    case AccuracyClass::intermediate:
      return say(language, Text::an_class_intermediate);
    case AccuracyClass::tactical:
      return say(language, Text::an_class_tactical);
    case AccuracyClass::consumer:
      break;
  }
  return say(language, Text::an_class_consumer);
}

std::string class_sentence(const model::AnalysisResult& r, Language language) {
  const ClassVerdict& v = r.verdict;
  const Text decided = v.decided_by == ClassCriterion::both  ? Text::an_class_both
                       : v.decided_by == ClassCriterion::arw ? Text::an_class_by_arw
                                                             : Text::an_class_by_bias_instability;
  return say(language, Text::an_class_sentence, class_name(v.accuracy_class, language),
             say(language, decided), g(r.bias_instability_deg_h),
             class_name(v.by_bias_instability, language), g(r.arw_deg_sqrt_h),
             class_name(v.by_arw, language));
}

std::string sensor_text(std::string_view text, Sensor sensor, Language language) {
  return in_sensor_units(text, sensor, language);
}

std::string td(std::string_view text) { return "<td>" + html_escape(text) + "</td>"; }
std::string th(std::string_view text) { return "<th>" + html_escape(text) + "</th>"; }

std::string figure_html(const Figure& f, Language language) {
  return "<figure>\n" +
         (f.svg ? *f.svg
                : "<p class=\"warn\">" + html_escape(say(language, Text::plot_skipped, f.error)) +
                      "</p>") +
         "\n<figcaption>" + html_escape(f.caption) + "</figcaption>\n</figure>\n";
}

const char* const kCss =
    R"(body{font-family:system-ui,-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}
h1{font-size:1.6em;border-bottom:2px solid #0072b2;padding-bottom:.2em}
h2{font-size:1.35em;margin-top:2em;border-bottom:1px solid #ccc}
h3{font-size:1.1em;margin-top:1.5em}
table{border-collapse:collapse;margin:.6em 0;font-size:.92em}
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:left;vertical-align:top}
tr:first-child th{background:#eef4fa}
table.meta th{background:#f6f6f6;font-weight:normal;color:#444}
tr.absent td{color:#888}
tr.upper_bound td{color:#555;font-style:italic}
figure{margin:1em 0}
figure svg{max-width:100%;height:auto;border:1px solid #e4e4e4}
figcaption{font-size:.9em;color:#444}
.warn{background:#fff4e0;border-left:4px solid #e69f00;padding:.4em .8em}
.note{color:#444;font-size:.92em}
.verdict{font-weight:bold}
td.truth{background:#f3f8f3;color:#333}
table.lab2 td:first-child{font-weight:600}
nav ul{columns:2;font-size:.95em}
.title-block{border:1px solid #ccc;padding:.4em 1em;margin:1em 0;text-align:center}
.title-block p{margin:.25em 0}
footer{margin-top:3em;font-size:.85em;color:#777})";

RenderedFigures render_figures(const std::vector<Plot>& plots, const std::vector<FigureSpec>& specs,
                               const ReportOptions& options) {
  RenderedFigures out;
  std::vector<std::future<PlotOutcome>> pending;
  if (options.plots) {
    for (std::size_t i = 0; i < plots.size(); ++i) {
      PlotOptions po = options.plot;
      po.id_prefix = fmt::format("{}{}_", options.id_prefix, specs.at(i).name);
      pending.push_back(
          std::async(std::launch::async, [&plots, i, po] { return render_svg(plots[i], po); }));
    }
  }
  std::string skip_reason = options.plots ? "" : say(options.language, Text::an_plots_off);
  for (std::size_t i = 0; i < plots.size(); ++i) {
    Figure fig;
    fig.name = specs.at(i).name;
    fig.caption = specs.at(i).caption;
    if (options.plots) {
      PlotOutcome drawn = pending[i].get();
      if (drawn.gnuplot_missing) {
        skip_reason = say(options.language, Text::an_gnuplot_missing, drawn.error);
      } else {
        fig.svg = std::move(drawn.svg);
        fig.error = drawn.error;
      }
    }
    out.figures.push_back(std::move(fig));
  }
  if (!skip_reason.empty()) {
    for (Figure& f : out.figures) {
      f.svg.reset();
      f.error = skip_reason;
    }
    out.skipped = true;
    out.note = say(options.language, Text::plots_skipped, skip_reason);
  }
  return out;
}

std::string record_title(const ReportInput& input, Language language) {
  if (!input.title.empty()) return input.title;
  if (input.channel.empty()) return input.file_name;
  return say(language, Text::an_record_title, input.file_name, input.channel);
}

}  // namespace detail

using namespace detail;

namespace {

// ---- text helpers --------------------------------------------------------------

std::string coefficient_unit(std::size_t j, Language language) {
  return j == 0   ? say(language, Text::unit_deg_h)
         : j == 1 ? say(language, Text::unit_deg_h_per_degc)
                  : say(language, Text::unit_deg_h_per_degc_k, j);
}

// The unit the samples were read in, as the user gave it (English) or in the manual's units.
std::string input_unit_text(const std::string& unit, Language language) {
  if (language == Language::en) return unit;
  try {
    switch (rate_unit_from_string(unit)) {
      case SampleUnit::deg_per_hour:
        return say(language, Text::unit_deg_h);
      case SampleUnit::deg_per_second:
        return say(language, Text::unit_deg_s);
      case SampleUnit::rad_per_second:
        return say(language, Text::unit_rad_s);
      case SampleUnit::m_per_s2:
        return say(language, Text::unit_m_s2);
      case SampleUnit::standard_gravity:
        return "g";
      case SampleUnit::milli_g:
        return say(language, Text::unit_mg);
    }
  } catch (const UsageError&) {
  }
  return unit;  // not one foglab names (a list of an IMU's units, ...): as given
}

std::string status_text(model::TermStatus status, Language language) {
  switch (status) {
    case model::TermStatus::resolved:
      return say(language, Text::an_status_resolved);
    case model::TermStatus::upper_bound:
      return say(language, Text::an_status_upper_bound);
    case model::TermStatus::absent:
      break;
  }
  return say(language, Text::an_status_absent);
}

// The words of each of kNoiseParameters (core/noise_model.h), in its order: symbol, meaning
// (a gyroscope's, an accelerometer's) and unit.
struct ParameterWords {
  Text name, meaning, meaning_accelerometer, unit;
};
constexpr std::array<ParameterWords, kNoiseParameters.size()> kParameterWords = {{
    {Text::an_sym_n, Text::an_meaning_n, Text::an_meaning_n_accel, Text::unit_deg_h_sqrt_hz},
    {Text::an_sym_b, Text::an_meaning_b, Text::an_meaning_b, Text::unit_deg_h},
    {Text::an_sym_k, Text::an_meaning_k, Text::an_meaning_k, Text::unit_deg_h_sqrt_s},
    {Text::an_sym_r, Text::an_meaning_r, Text::an_meaning_r, Text::unit_deg_h_s},
    {Text::an_sym_q, Text::an_meaning_q, Text::an_meaning_q, Text::unit_deg_h_times_s},
    {Text::an_param_gm_sigma, Text::an_meaning_gm_sigma, Text::an_meaning_gm_sigma,
     Text::unit_deg_h},
    {Text::an_param_gm_tc, Text::an_meaning_gm_tc, Text::an_meaning_gm_tc, Text::unit_s},
}};

}  // namespace

Text detail::parameter_unit(std::size_t parameter) { return kParameterWords.at(parameter).unit; }

namespace {

std::vector<Message> all_notes(const model::AnalysisResult& r, const ReportInput& in) {
  std::vector<Message> notes = in.notes;
  for (const Message& n : r.notes) {
    if (r.systematic && n == r.systematic->note) continue;  // shown with the systematic part
    if (std::find(notes.begin(), notes.end(), n) == notes.end()) notes.push_back(n);
  }
  return notes;
}

// ---- HTML ----------------------------------------------------------------------------

std::string html_tables(const model::AnalysisResult& r, const ReportInput& in, Language l) {
  const std::string deg_h = say(l, Text::unit_deg_h);
  std::string h;
  // The recording.
  h += "<h3>" + html_escape(say(l, Text::an_recording)) + "</h3>\n<table class=\"meta\">\n";
  auto row = [&](std::string_view k, const std::string& v) {
    h += "<tr>" + th(k) + td(v) + "</tr>\n";
  };
  row(say(l, Text::an_file), in.file_name.empty() ? "-" : in.file_name);
  row(say(l, Text::an_rate_channel), in.channel.empty() ? "-" : in.channel);
  row(say(l, Text::an_temperature_channel),
      in.temperature_channel.empty() ? say(l, Text::an_none) : in.temperature_channel);
  row(say(l, Text::an_input_unit), say(l, Text::an_analysed_in, input_unit_text(in.input_unit, l)));
  row(say(l, Text::an_samples), fmt::format("{}", r.samples));
  row(say(l, Text::an_sample_rate), g(r.sample_rate_hz) + " " + say(l, Text::unit_hz));
  row(say(l, Text::an_duration),
      say(l, Text::an_duration_value, r.duration_s, r.duration_s / kSecondsPerHour));
  h += "</table>\n";

  // Systematic part.
  h += "<h3>" + html_escape(say(l, Text::an_systematic)) + "</h3>\n";
  if (r.systematic) {
    const model::SystematicFit& s = *r.systematic;
    h += "<p>" +
         html_escape(say(l, Text::an_systematic_fit, s.degree, s.t_ref_c,
                         s.degree_chosen ? say(l, Text::an_degree_chosen) : "",
                         s.constant_fallback ? say(l, Text::an_constant_fallback_why) : "")) +
         "</p>\n";
    h += "<table>\n<tr>" + th(say(l, Text::an_coefficient)) + th(say(l, Text::value)) +
         th(say(l, Text::an_standard_error)) + th(say(l, Text::unit)) + "</tr>\n";
    for (std::size_t j = 0; j < s.coefficients.size(); ++j) {
      const double se = j < s.standard_errors.size() ? s.standard_errors[j] : kNaN;
      h += "<tr>" + td(fmt::format("c{}", j)) + td(fmt::format("{:.6g}", s.coefficients[j])) +
           td(g(se)) + td(coefficient_unit(j, l)) + "</tr>\n";
    }
    h += "</table>\n<table class=\"meta\">\n";
    row(say(l, Text::an_systematic_bias), fmt::format("{:.6g} {}", s.bias_deg_h, deg_h));
    row(say(l, Text::an_lab_constant),
        fmt::format("{:.6g} {}{}", s.lab_constant_term_deg_h, deg_h,
                    s.lab_constant_meaningful ? "" : say(l, Text::an_not_meaningful)));
    row(say(l, Text::an_temperature_span), say(l, Text::an_span_value, s.temperature_span_c,
                                               s.temperature_min_c, s.temperature_max_c));
    row(say(l, Text::an_residual_rms), g(s.residual_rms_deg_h) + " " + deg_h);
    h += "</table>\n";
    if (!s.note.empty()) h += "<p class=\"note\">" + html_escape(s.note.text(l)) + "</p>\n";
  } else {
    h += "<p>" +
         html_escape(in.record_mean_deg_h
                         ? say(l, Text::an_no_temperature_mean, *in.record_mean_deg_h)
                         : say(l, Text::an_no_temperature)) +
         "</p>\n";
  }

  // Noise model.
  h += "<h3>" + html_escape(say(l, Text::an_noise_model)) + "</h3>\n";
  h += "<p>" +
       html_escape(say(l, Text::an_terms_chosen, terms_text(r.noise.terms, l), r.noise.points,
                       r.noise.dispersion)) +
       "</p>\n";
  h += fmt::format("<p class=\"fit-{}\">{}</p>\n", model::to_string(r.noise.status),
                   html_escape(say(l, Text::an_fit, model::fit_sentence(r.noise, l))));
  h += "<table>\n<tr>" + th(say(l, Text::an_parameter)) + th(say(l, Text::an_meaning)) +
       th(say(l, Text::value)) + th(say(l, Text::interval95)) + th(say(l, Text::an_status)) +
       th(say(l, Text::unit)) + "</tr>\n";
  for (std::size_t i = 0; i < kNoiseParameters.size(); ++i) {
    const ParameterWords& words = kParameterWords[i];
    const model::ParameterEstimate& e = r.noise.estimate(kNoiseParameters[i]);
    const ParameterText t = parameter_text(e, l);
    h += fmt::format("<tr class=\"{}\">", model::to_string(e.status)) + td(say(l, words.name)) +
         td(say(l, in.sensor == Sensor::gyroscope ? words.meaning : words.meaning_accelerometer)) +
         td(t.value) + td(t.interval) + td(status_text(e.status, l)) + td(say(l, words.unit)) +
         "</tr>\n";
  }
  h += "</table>\n<table class=\"meta\">\n";
  if (in.sensor == Sensor::gyroscope) {
    row(say(l, Text::an_arw), g(r.arw_deg_sqrt_h) + " " + say(l, Text::unit_deg_sqrt_h));
  } else {
    row(say(l, Text::an_vrw),
        g(velocity_random_walk_m_s_sqrt_h(r.noise.model.N)) + " " + say(l, Text::unit_m_s_sqrt_h));
  }
  row(say(l, Text::an_bandwidth), bandwidth_sentence(r.noise, l));
  row(say(l, Text::an_lines), lines_sentence(r.noise, l));
  row(say(l, Text::an_drift), stationarity_sentence(r.allan_drift, l));
  row(say(l, Text::an_steps),
      r.steps.indices.empty() ? say(l, Text::an_none)
                              : fmt::format("{}{}", r.steps.indices.size(),
                                            say(l, r.steps.left_as_noise() ? Text::an_steps_as_noise
                                                   : r.steps.removed       ? Text::an_steps_levelled
                                                                           : Text::an_left_in)));
  row(say(l, Text::an_spikes),
      (r.spikes.count == 0
           ? say(l, Text::an_none)
           : say(l, Text::an_spikes_value, r.spikes.count, g(r.spikes.threshold_deg_h),
                 say(l, r.spikes.removed ? Text::an_spikes_replaced : Text::an_left_in))) +
          (r.spikes.heavy_tailed
               ? say(l, Text::an_heavy_tail, g(r.spikes.tail_index), g(r.spikes.threshold_deg_h))
               : std::string()));
  row(say(l, Text::an_quantisation),
      r.output_quantisation.detected
          ? say(l, Text::an_quantisation_value, g(r.output_quantisation.lsb_deg_h),
                g(r.output_quantisation.white_level_deg_h_sqrt_hz))
          : say(l, Text::an_quantisation_none));
  row(say(l, Text::an_bias_instability),
      say(l, Text::an_bias_instability_value, g(r.bias_instability_deg_h),
          g(r.bias_instability_tau_s),
          r.bias_instability_at_edge ? say(l, Text::an_at_edge_why) : ""));
  row(say(l, Text::an_eq17), eq17_sentence(r.psd_allan, l));
  h += "</table>\n";

  // Readings beside the fit.
  h += "<h3>" + html_escape(say(l, Text::an_readings)) + "</h3>\n";
  h += "<table>\n<tr>" + th(say(l, Text::an_quantity)) + th(say(l, Text::an_adev_reading)) +
       th(say(l, Text::an_psd_reading)) + th(say(l, Text::an_fit_interval)) +
       th(say(l, Text::unit)) + "</tr>\n";
  auto fit_value = [l](const model::ParameterEstimate& e) {
    const ParameterText t = parameter_text(e, l);
    return t.interval.empty() ? t.value : t.value + " " + t.interval;
  };
  h += "<tr>" + td(say(l, Text::an_reading_n)) + td(g(r.adev_readings.N, l)) +
       td(g(r.psd_readings.N, l)) + td(fit_value(r.noise.N)) +
       td(say(l, Text::unit_deg_h_sqrt_hz)) + "</tr>\n";
  h += "<tr>" + td(say(l, Text::an_reading_k)) + td(g(r.adev_readings.K, l)) +
       td(g(r.psd_readings.K, l)) + td(fit_value(r.noise.K)) + td(say(l, Text::unit_deg_h_sqrt_s)) +
       "</tr>\n";
  h += "<tr>" + td(say(l, Text::an_reading_bias_instability)) +
       td(say(l, Text::an_value_at, g(r.adev_readings.bias_instability_deg_h),
              g(r.adev_readings.bias_instability_tau_s))) +
       td("-") + td(fit_value(r.noise.B)) + td(deg_h) + "</tr>\n";
  h += "</table>\n";
  if (in.sensor == Sensor::gyroscope) {
    for (const std::string& line : manual_conventions(r, l)) {
      h += "<p class=\"note\">" + html_escape(line) + "</p>\n";
    }
  }

  // Random bias.
  const model::RandomBiasEvidence& ev = r.evidence;
  h += "<h3>" + html_escape(say(l, Text::an_random_bias)) + "</h3>\n<p><strong>" +
       html_escape(say(l, Text::an_random_bias_is, random_bias_answer(r, l))) + "</strong></p>\n";
  if (!ev.summary.empty()) h += "<p>" + html_escape(ev.summary.text(l)) + "</p>\n";
  h += "<table>\n<tr>" + th(say(l, Text::an_hypothesis)) + th(say(l, Text::an_deviance)) +
       th(say(l, Text::an_criterion)) + "</tr>\n";
  h += "<tr>" + td(say(l, Text::an_no_random_bias)) + td(g(ev.deviance_none)) +
       td(g(ev.criterion_none)) + "</tr>\n";
  h += "<tr>" + td(say(l, Text::an_wiener_process)) + td(g(ev.deviance_wiener)) +
       td(g(ev.criterion_wiener)) + "</tr>\n";
  h += "<tr>" + td(say(l, Text::an_gauss_markov_process)) + td(g(ev.deviance_gauss_markov)) +
       td(g(ev.criterion_gauss_markov)) + "</tr>\n</table>\n";
  h += "<p>" +
       html_escape(say(l, Text::an_slopes, g(ev.adev_end_slope), g(ev.psd_low_frequency_slope))) +
       "</p>\n";

  // Class.
  if (in.sensor == Sensor::gyroscope) {
    h += "<h3>" + html_escape(say(l, Text::an_class)) + "</h3>\n<p class=\"verdict\">" +
         html_escape(class_sentence(r, l)) + "</p>\n";
  } else {
    h += "<h3>" + html_escape(say(l, Text::an_class_accel)) + "</h3>\n<p>" +
         html_escape(say(l, Text::an_no_accelerometer_class)) + "</p>\n";
  }

  const std::vector<Message> notes = all_notes(r, in);
  if (!notes.empty()) {
    h += "<h3>" + html_escape(say(l, Text::an_notes)) + "</h3>\n<ul>\n";
    for (const Message& n : notes) h += "<li>" + html_escape(n.text(l)) + "</li>\n";
    h += "</ul>\n";
  }
  return sensor_text(h, in.sensor, l);
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string markdown_summary(const model::AnalysisResult& r, const ReportInput& in, Language l) {
  const std::string deg_h = say(l, Text::unit_deg_h);
  std::string md = fmt::format("## {}\n\n", record_title(in, l));
  md += say(l, Text::an_md_recording, in.file_name.empty() ? "-" : in.file_name,
            in.channel.empty() ? "-" : in.channel,
            in.temperature_channel.empty() ? say(l, Text::an_none) : in.temperature_channel,
            r.samples, g(r.sample_rate_hz), r.duration_s / kSecondsPerHour,
            r.gaps.empty() ? std::string()
                           : say(l, Text::an_md_gaps, r.gaps.size(), missing_samples(r.gaps))) +
        "\n\n";

  md += "### " + say(l, Text::an_md_systematic) + "\n\n";
  if (r.systematic) {
    const model::SystematicFit& s = *r.systematic;
    md += say(l, Text::an_md_polynomial, s.degree, s.t_ref_c,
              s.degree_chosen ? say(l, Text::an_degree_chosen) : "",
              s.constant_fallback ? say(l, Text::an_constant_fallback) : "") +
          "\n\n";
    md += fmt::format("| {} | {} | {} | {} |\n|---|---:|---:|---|\n", say(l, Text::an_coefficient),
                      say(l, Text::value), say(l, Text::an_standard_error), say(l, Text::unit));
    for (std::size_t j = 0; j < s.coefficients.size(); ++j) {
      const double se = j < s.standard_errors.size() ? s.standard_errors[j] : kNaN;
      md += fmt::format("| c{} | {:.6g} | {} | {} |\n", j, s.coefficients[j], g(se),
                        coefficient_unit(j, l));
    }
    md += "\n- " +
          say(l, Text::an_md_systematic_bias, s.t_ref_c, s.bias_deg_h, s.temperature_span_c) + "\n";
    md +=
        fmt::format("- {}: {:.6g} {}{}\n", say(l, Text::an_lab_constant), s.lab_constant_term_deg_h,
                    deg_h, s.lab_constant_meaningful ? "" : say(l, Text::an_not_meaningful));
    if (!s.note.empty()) md += "- " + s.note.text(l) + "\n";
    md += "\n";
  } else {
    md += (in.record_mean_deg_h ? say(l, Text::an_md_no_temperature_mean, *in.record_mean_deg_h)
                                : say(l, Text::an_md_no_temperature)) +
          "\n\n";
  }

  md += "### " + say(l, Text::an_md_noise, terms_text(r.noise.terms, l)) + "\n\n" +
        say(l, Text::an_fit, model::fit_sentence(r.noise, l)) + "\n\n";
  md += fmt::format("| {} | {} | {} | {} | {} |\n|---|---:|---|---|---|\n",
                    say(l, Text::an_parameter), say(l, Text::value), say(l, Text::interval95),
                    say(l, Text::an_status), say(l, Text::unit));
  for (std::size_t i = 0; i < kNoiseParameters.size(); ++i) {
    const model::ParameterEstimate& e = r.noise.estimate(kNoiseParameters[i]);
    const ParameterText t = parameter_text(e, l);
    md += fmt::format("| {} | {} | {} | {} | {} |\n", say(l, kParameterWords[i].name), t.value,
                      t.interval, status_text(e.status, l), say(l, kParameterWords[i].unit));
  }
  const std::string at_edge = r.bias_instability_at_edge ? say(l, Text::an_md_at_edge) : "";
  if (in.sensor == Sensor::gyroscope) {
    md += "\n- " +
          say(l, Text::an_md_arw, g(r.arw_deg_sqrt_h), g(r.bias_instability_deg_h),
              g(r.bias_instability_tau_s), at_edge) +
          "\n";
  } else {
    md += "\n- " +
          say(l, Text::an_md_vrw, g(velocity_random_walk_m_s_sqrt_h(r.noise.model.N)),
              g(r.bias_instability_deg_h), g(r.bias_instability_deg_h / kStandardGravity * 1000.0),
              g(r.bias_instability_tau_s), at_edge) +
          "\n";
  }
  md += "- " +
        say(l, Text::an_md_readings, g(r.adev_readings.N, l), g(r.adev_readings.K, l),
            g(r.adev_readings.bias_instability_deg_h), g(r.psd_readings.N, l),
            g(r.psd_readings.K, l)) +
        "\n";
  if (in.sensor == Sensor::gyroscope) {
    for (const std::string& line : manual_conventions(r, l)) md += "  " + line + "\n";
  }
  md += "- " + say(l, Text::an_eq17) + ": " + eq17_sentence(r.psd_allan, l) + "\n";
  md += "- " + say(l, Text::an_bandwidth) + ": " + bandwidth_sentence(r.noise, l) + "\n";
  md += "- " + say(l, Text::an_lines) + ": " + lines_sentence(r.noise, l) + "\n";
  md += "- " + say(l, Text::an_drift) + ": " + stationarity_sentence(r.allan_drift, l) + "\n";
  md += "- " + say(l, Text::an_md_random_bias) + ": " + random_bias_answer(r, l) + "\n";
  if (!r.evidence.summary.empty()) md += "  (" + r.evidence.summary.text(l) + ")\n";
  md += in.sensor == Sensor::gyroscope
            ? "- " + say(l, Text::an_md_class) + ": **" + class_sentence(r, l) + "**\n"
            : "- " + say(l, Text::an_md_class) + ": " + say(l, Text::an_no_accelerometer_class) +
                  "\n";
  const std::vector<Message> notes = all_notes(r, in);
  if (!notes.empty()) {
    md += "\n" + say(l, Text::an_notes) + ":\n\n";
    for (const Message& n : notes) md += "- " + n.text(l) + "\n";
  }
  return sensor_text(md, in.sensor, l);
}

std::string kalibr_imu_yaml(const model::AnalysisResult& r, const ReportInput& in,
                            std::string_view rostopic) {
  if (in.sensor != Sensor::gyroscope) {
    ImuAxis axis{in.channel, in.sensor, &r};
    return kalibr_imu_yaml(std::span<const ImuAxis>(&axis, 1), in.file_name, r.sample_rate_hz,
                           rostopic);
  }
  std::string y = fmt::format(
      "# Kalibr IMU noise model (imu.yaml) of the gyroscope in '{}'{}, written by foglab {}.\n"
      "# Continuous-time densities, from the noise model fitted to the Allan variance\n"
      "# (N [deg/h/sqrt(Hz)] and K [deg/h/sqrt(s)] times (pi/180)/3600).\n"
      "# Kalibr advises inflating these for real-world use (vibration, temperature).\n\n",
      in.file_name, in.channel.empty() ? "" : " channel " + in.channel, version());
  const FilterNoise f = filter_noise(r, Sensor::gyroscope);
  y += "# No accelerometer in this recording: Kalibr's accelerometer fields are not measured.\n";
  y += "#accelerometer_noise_density: 0.0  # [m/s^2/sqrt(Hz)]\n";
  y += "#accelerometer_random_walk: 0.0    # [m/s^3/sqrt(Hz)]\n\n";
  y += "# Gyroscope\n";
  y += fmt::format("gyroscope_noise_density: {:.9g}  # [rad/s/sqrt(Hz)] {}\n",
                   noise_density_rad_s_sqrt_hz(f.white), f.white_source);
  y += fmt::format("gyroscope_random_walk: {:.9g}  # [rad/s^2/sqrt(Hz)] {}\n\n",
                   random_walk_rad_s2_sqrt_hz(f.random_walk), f.random_walk_source);
  y += fmt::format("rostopic: {}  # the IMU's ROS topic: set it to yours\n", rostopic);
  y += fmt::format("update_rate: {:.9g}  # [Hz] the sample rate of the recording\n",
                   r.sample_rate_hz);
  return y;
}

Report make_report(const model::AnalysisResult& result, const ReportInput& input,
                   const ReportOptions& options) {
  const Language l = options.language;
  Report rep;
  rep.title = record_title(input, l);
  rep.language = l;
  const std::vector<Plot> plots = report_plots(result, input, options);
  const std::vector<FigureSpec> specs = report_figure_specs(result, input, l);
  RenderedFigures drawn = render_figures(plots, specs, options);
  rep.figures = std::move(drawn.figures);
  rep.plots_skipped = drawn.skipped;
  rep.plots_note = std::move(drawn.note);

  // HTML section.
  std::string& h = rep.html_section;
  h += "<section>\n<h2>" + html_escape(rep.title) + "</h2>\n";
  if (rep.plots_skipped) {
    h += "<p class=\"warn\">" + html_escape(rep.plots_note) + "</p>\n";
  } else {
    for (const Figure& f : rep.figures) h += figure_html(f, l);
  }
  h += html_tables(result, input, l);
  h += "</section>\n";

  rep.markdown = markdown_summary(result, input, l);
  if (rep.plots_skipped) rep.markdown += "\n" + rep.plots_note + "\n";
  rep.kalibr_yaml = kalibr_imu_yaml(result, input, options.rostopic);
  return rep;
}

namespace {
std::string section_id(std::size_t k) { return fmt::format("recording-{}", k + 1); }
}  // namespace

std::string html_document(std::span<const Report> reports, std::string_view title,
                          std::string_view preface_html, Language language) {
  std::string h =
      fmt::format("<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n",
                  html_lang(language));
  h += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  h += "<title>" + html_escape(title) + "</title>\n<style>\n" + kCss + "\n</style>\n</head>\n";
  h += "<body>\n<h1>" + html_escape(title) + "</h1>\n";
  if (reports.size() > 1) {
    h += "<nav><ul>\n";
    for (std::size_t k = 0; k < reports.size(); ++k) {
      h += fmt::format("<li><a href=\"#{}\">{}</a></li>\n", section_id(k),
                       html_escape(reports[k].title));
    }
    h += "</ul></nav>\n";
  }
  h += preface_html;
  for (std::size_t k = 0; k < reports.size(); ++k) {
    h += fmt::format("<div id=\"{}\">\n", section_id(k)) + reports[k].html_section + "</div>\n";
  }
  h += "<footer>" + html_escape(say(language, Text::footer, version())) + "</footer>\n";
  h += "</body>\n</html>\n";
  return h;
}

namespace {

/// The title block's lines and the aim, in `language`.
std::pair<std::vector<std::string>, std::string> title_block_text(const TitleBlock& b, Language l) {
  std::vector<std::string> lines;
  if (b.lab != 1 && b.lab != 2) return {};
  lines.push_back(say(l, Text::title_university));
  lines.push_back(say(l, Text::title_lab, b.lab,
                      say(l, b.lab == 1 ? Text::title_lab1_name : Text::title_lab2_name)));
  if (b.variant) lines.push_back(say(l, Text::title_variant, *b.variant));
  if (!b.student.empty()) lines.push_back(say(l, Text::title_student, b.student));
  if (!b.group.empty()) lines.push_back(say(l, Text::title_group, b.group));
  if (!b.date.empty()) lines.push_back(say(l, Text::title_date, b.date));
  return {lines, say(l, b.lab == 1 ? Text::title_aim_lab1 : Text::title_aim_lab2)};
}

}  // namespace

std::string title_block_html(const TitleBlock& block, Language language) {
  const auto [lines, aim] = title_block_text(block, language);
  if (lines.empty()) return "";
  std::string h = "<div class=\"title-block\">\n";
  for (const std::string& line : lines) h += "<p>" + html_escape(line) + "</p>\n";
  h += "</div>\n<h2>" + html_escape(say(language, Text::title_aim_heading)) + "</h2>\n<p>" +
       html_escape(aim) + "</p>\n";
  return h;
}

std::string title_block_markdown(const TitleBlock& block, Language language) {
  const auto [lines, aim] = title_block_text(block, language);
  if (lines.empty()) return "";
  std::string md;
  for (const std::string& line : lines) md += line + "  \n";
  return md + "\n## " + say(language, Text::title_aim_heading) + "\n\n" + aim + "\n\n";
}

std::string html_document(const Report& report) {
  return html_document(std::span<const Report>(&report, 1),
                       say(report.language, Text::an_page_title, report.title), {},
                       report.language);
}

}  // namespace foglab::report
