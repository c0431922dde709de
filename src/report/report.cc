// foglab — the report of one analysed recording (report.h).
#include "foglab/report/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <numbers>
#include <utility>

#include "foglab/core/error.h"
#include "foglab/core/units.h"
#include "foglab/core/version.h"
#include "foglab/report/imu.h"
#include "report_internal.h"

namespace foglab::report {

namespace detail {

// ---- shared with lab2.cc (report_internal.h) ----------------------------------

std::string g(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "-"; }
std::string g(const std::optional<double>& v) { return v ? g(*v) : std::string("not visible"); }

ParameterText parameter_text(const model::ParameterEstimate& p) {
  ParameterText t;
  if (p.status == model::TermStatus::resolved) {
    t.value = g(p.value);
    t.interval = fmt::format("[{}, {}]", g(p.ci95_low), g(p.ci95_high));
  } else if (p.status == model::TermStatus::upper_bound) {
    const double bound = std::isfinite(p.upper_95) ? p.upper_95 : p.value;
    t.value = std::isfinite(bound) ? "< " + g(bound) : "-";
    t.interval = std::isfinite(p.ci95_high) ? fmt::format("[0, {}]", g(p.ci95_high))
                                            : std::string("no bound");
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

std::string random_bias_answer(const model::AnalysisResult& r) {
  switch (r.noise.random_bias_process) {
    case RandomBiasProcess::wiener:
      return fmt::format("a Wiener process (rate random walk), K = {} deg/h/sqrt(s)",
                         parameter_text(r.noise.K).value);
    case RandomBiasProcess::gauss_markov:
      return fmt::format("a first-order Gauss-Markov process, sigma = {} deg/h, Tc = {} s",
                         parameter_text(r.noise.gm_sigma).value,
                         parameter_text(r.noise.gm_tc).value);
    case RandomBiasProcess::none:
      break;
  }
  return "not visible in this record (neither a Wiener nor a Gauss-Markov process is supported "
         "by the data)";
}

std::string bandwidth_sentence(const model::BandwidthEstimate& b) {
  if (!b.resolved) {
    return "none resolved (the first taus follow N/sqrt(tau): the samples' white noise is not "
           "visibly filtered)";
  }
  if (b.bandwidth.moving_average()) {
    return fmt::format(
        "a moving average over {} samples (cut-off {} Hz), on {} % of the white noise (lag-1 "
        "correlation of its samples {}); it lowers the Allan variance at the first tau by {} %, "
        "and N is the white level above it",
        b.bandwidth.moving_average_samples, g(b.cutoff_hz),
        g(100.0 * b.bandwidth.filtered_fraction), g(b.lag1_correlation),
        g(100.0 * b.first_tau_reduction));
  }
  if (b.bandwidth.butterworth()) {
    return fmt::format(
        "a second-order Butterworth low-pass at {} Hz, on {} % of the white noise (lag-1 "
        "correlation of its samples {}); it lowers the Allan variance at the first tau by {} %, "
        "and N is the white level above it",
        g(b.cutoff_hz), g(100.0 * b.bandwidth.filtered_fraction), g(b.lag1_correlation),
        g(100.0 * b.first_tau_reduction));
  }
  return fmt::format(
      "time constant {} s, first-order cut-off {} Hz, on {} % of the white noise (lag-1 "
      "correlation of its samples {}); it lowers the Allan variance at the first tau by {} %, and "
      "N is the white level above it",
      g(b.bandwidth.time_constant_s), g(b.cutoff_hz), g(100.0 * b.bandwidth.filtered_fraction),
      g(b.lag1_correlation), g(100.0 * b.first_tau_reduction));
}

std::string lines_sentence(const model::NoiseFitResult& fit) {
  if (fit.lines.empty()) return "none found in the PSD";
  std::string text;
  for (const SpectralLine& line : fit.lines) {
    text += fmt::format("{}{} Hz ({} Hz wide), {} deg/h rms, {} times the PSD's floor",
                        text.empty() ? "" : "; ", g(line.frequency_hz), g(line.width_hz),
                        g(std::sqrt(line.variance)), g(line.peak_ratio));
  }
  if (fit.line_variance_scale != 1.0) {
    text += fmt::format(
        " (the variance the fit used: {} times the PSD bins', as the Allan deviation's first taus "
        "show it)",
        g(fit.line_variance_scale));
  }
  return text + " (its Allan variance is part of the fit, not of any noise term)";
}

std::string class_sentence(const model::AnalysisResult& r) {
  const ClassVerdict& v = r.verdict;
  std::string decided = v.decided_by == ClassCriterion::both ? "both criteria agree"
                        : v.decided_by == ClassCriterion::arw
                            ? "decided by the angle random walk (the worse of the two)"
                            : "decided by the bias instability (the worse of the two)";
  return fmt::format("{} ({}; by bias instability {} deg/h: {}; by ARW {} deg/sqrt(h): {})",
                     to_string(v.accuracy_class), decided, g(r.bias_instability_deg_h),
                     to_string(v.by_bias_instability), g(r.arw_deg_sqrt_h), to_string(v.by_arw));
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
  std::string skip_reason = options.plots ? "" : "plotting was turned off";
  for (std::size_t i = 0; i < plots.size(); ++i) {
    Figure fig;
    fig.name = specs.at(i).name;
    fig.caption = specs.at(i).caption;
    if (options.plots) {
      PlotOutcome drawn = pending[i].get();
      if (drawn.gnuplot_missing) {
        skip_reason = "gnuplot could not be run (" + drawn.error +
                      "); install gnuplot (Debian: gnuplot-nox) to draw them";
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

std::string record_title(const ReportInput& input) {
  if (!input.title.empty()) return input.title;
  if (input.channel.empty()) return input.file_name;
  return fmt::format("{} ({})", input.file_name, input.channel);
}

}  // namespace detail

using namespace detail;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- text helpers --------------------------------------------------------------

std::string coefficient_unit(std::size_t j) {
  return j == 0 ? "deg/h" : j == 1 ? "deg/h/degC" : fmt::format("deg/h/degC^{}", j);
}

std::vector<std::string> all_notes(const model::AnalysisResult& r, const ReportInput& in) {
  std::vector<std::string> notes = in.notes;
  for (const std::string& n : r.notes) {
    if (r.systematic && n == r.systematic->note) continue;  // shown with the systematic part
    if (std::find(notes.begin(), notes.end(), n) == notes.end()) notes.push_back(n);
  }
  return notes;
}

// ---- HTML ----------------------------------------------------------------------------

std::string html_tables(const model::AnalysisResult& r, const ReportInput& in) {
  std::string h;
  // The recording.
  h += "<h3>Recording</h3>\n<table class=\"meta\">\n";
  auto row = [&](std::string_view k, const std::string& v) {
    h += "<tr>" + th(k) + td(v) + "</tr>\n";
  };
  row("file", in.file_name.empty() ? "-" : in.file_name);
  row("rate channel", in.channel.empty() ? "-" : in.channel);
  row("temperature channel", in.temperature_channel.empty() ? "none" : in.temperature_channel);
  row("input unit", fmt::format("{} (analysed in deg/h)", in.input_unit));
  row("samples", fmt::format("{}", r.samples));
  row("sample rate", fmt::format("{} Hz", g(r.sample_rate_hz)));
  row("duration", fmt::format("{:.1f} s ({:.3g} h)", r.duration_s, r.duration_s / kSecondsPerHour));
  h += "</table>\n";

  // Systematic part.
  h += "<h3>Systematic part (bias and its temperature dependence)</h3>\n";
  if (r.systematic) {
    const model::SystematicFit& s = *r.systematic;
    h += fmt::format(
        "<p>Least-squares polynomial of degree {} in (T - t_ref), t_ref = {:.4g} degC{}{}. "
        "Standard errors from the fitted noise model.</p>\n",
        s.degree, s.t_ref_c, s.degree_chosen ? ", degree chosen by the criterion" : "",
        s.constant_fallback ? ", constant fallback (the temperature barely moves)" : "");
    h += "<table>\n<tr>" + th("coefficient") + th("value") + th("standard error") + th("unit") +
         "</tr>\n";
    for (std::size_t j = 0; j < s.coefficients.size(); ++j) {
      const double se = j < s.standard_errors.size() ? s.standard_errors[j] : kNaN;
      h += "<tr>" + td(fmt::format("c{}", j)) + td(fmt::format("{:.6g}", s.coefficients[j])) +
           td(g(se)) + td(coefficient_unit(j)) + "</tr>\n";
    }
    h += "</table>\n<table class=\"meta\">\n";
    row("systematic bias at t_ref", fmt::format("{:.6g} deg/h", s.bias_deg_h));
    row("lab's polyfit(T, Y, 2) constant term",
        fmt::format("{:.6g} deg/h{}", s.lab_constant_term_deg_h,
                    s.lab_constant_meaningful ? "" : " (not meaningful: the span is too small)"));
    row("temperature span", fmt::format("{:.4g} degC ({:.4g} to {:.4g} degC)", s.temperature_span_c,
                                        s.temperature_min_c, s.temperature_max_c));
    row("residual rms", fmt::format("{} deg/h", g(s.residual_rms_deg_h)));
    h += "</table>\n";
    if (!s.note.empty()) h += "<p class=\"note\">" + html_escape(s.note) + "</p>\n";
  } else {
    h += in.record_mean_deg_h
             ? fmt::format(
                   "<p>No temperature: only the record mean (the constant bias), {:.6g} "
                   "deg/h, was removed.</p>\n",
                   *in.record_mean_deg_h)
             : std::string(
                   "<p>No temperature: only the record mean (the constant bias) was "
                   "removed.</p>\n");
  }

  // Noise model.
  h += fmt::format(
      "<h3>Noise model (IEEE Std 952, fitted to the Allan variance)</h3>\n"
      "<p>Terms chosen: {}; {} tau points, dispersion {:.3g}. Intervals are 95 %; a term the "
      "record cannot resolve gets a one-sided 95 % upper bound.</p>\n"
      "<p class=\"fit-{}\">Fit: {}.</p>\n",
      html_escape(to_string(r.noise.terms)), r.noise.points, r.noise.dispersion,
      model::to_string(r.noise.status), html_escape(r.noise.message));
  h += "<table>\n<tr>" + th("parameter") + th("meaning") + th("value") + th("95 % interval") +
       th("status") + th("unit") + "</tr>\n";
  for (const NoiseParameter& p : kNoiseParameters) {
    const model::ParameterEstimate& e = r.noise.estimate(p);
    const ParameterText t = parameter_text(e);
    h += fmt::format("<tr class=\"{}\">", model::to_string(e.status)) + td(p.name) + td(p.meaning) +
         td(t.value) + td(t.interval) + td(model::to_string(e.status)) + td(p.unit) + "</tr>\n";
  }
  h += "</table>\n<table class=\"meta\">\n";
  if (in.sensor == Sensor::gyroscope) {
    row("angle random walk (N/60)", fmt::format("{} deg/sqrt(h)", g(r.arw_deg_sqrt_h)));
  } else {
    row("velocity random walk (60 N)",
        fmt::format("{} m/s/sqrt(h)", g(velocity_random_walk_m_s_sqrt_h(r.noise.model.N))));
  }
  row("sensor bandwidth", bandwidth_sentence(r.noise.bandwidth));
  row("spectral lines", lines_sentence(r.noise));
  row("bias steps",
      r.steps.indices.empty()
          ? std::string("none")
          : fmt::format("{}{}", r.steps.indices.size(),
                        r.steps.removed ? ", levelled before the analysis (the notes list them)"
                                        : ", left in"));
  row("spikes", r.spikes.count == 0
                    ? std::string("none")
                    : fmt::format("{} (beyond {} deg/h from their neighbours' mean){}",
                                  r.spikes.count, g(r.spikes.threshold_deg_h),
                                  r.spikes.removed ? ", replaced by that mean" : ", left in"));
  row("output quantisation",
      r.output_quantisation.detected
          ? fmt::format("steps of {} deg/h (LSB); rounding noise {} deg/h/sqrt(Hz), inside N",
                        g(r.output_quantisation.lsb_deg_h),
                        g(r.output_quantisation.white_level_deg_h_sqrt_hz))
          : std::string("none seen in the samples"));
  row("bias instability (ADEV minimum)",
      fmt::format("{} deg/h at tau = {} s{}", g(r.bias_instability_deg_h),
                  g(r.bias_instability_tau_s),
                  r.bias_instability_at_edge ? " (at the end of the tau range: the true minimum "
                                               "may lie beyond it)"
                                             : ""));
  h += "</table>\n";

  // Readings beside the fit.
  h += "<h3>The lab's graphical readings beside the fit</h3>\n";
  h += "<table>\n<tr>" + th("quantity") + th("ADEV reading") + th("PSD reading") +
       th("fit (95 % interval)") + th("unit") + "</tr>\n";
  auto fit_text = [](const model::ParameterEstimate& e) {
    const ParameterText t = parameter_text(e);
    return t.interval.empty() ? t.value : t.value + " " + t.interval;
  };
  h += "<tr>" + td("white noise N (ADEV at tau = 1 s on the -1/2 line; PSD flat level)") +
       td(g(r.adev_readings.N)) + td(g(r.psd_readings.N)) + td(fit_text(r.noise.N)) +
       td("deg/h/sqrt(Hz)") + "</tr>\n";
  h += "<tr>" +
       td("Wiener intensity K (ADEV at tau = 3 s on the +1/2 line; PSD -2 slope at 1 Hz)") +
       td(g(r.adev_readings.K)) + td(g(r.psd_readings.K)) + td(fit_text(r.noise.K)) +
       td("deg/h/sqrt(s)") + "</tr>\n";
  h += "<tr>" + td("bias instability (ADEV minimum; fit: flicker B)") +
       td(fmt::format("{} at {} s", g(r.adev_readings.bias_instability_deg_h),
                      g(r.adev_readings.bias_instability_tau_s))) +
       td("-") + td(fit_text(r.noise.B)) + td("deg/h") + "</tr>\n";
  h += "</table>\n";

  // Random bias.
  const model::RandomBiasEvidence& ev = r.evidence;
  h += "<h3>Random bias</h3>\n<p><strong>The random part of the bias is " +
       html_escape(random_bias_answer(r)) + ".</strong></p>\n";
  if (!ev.summary.empty()) h += "<p>" + html_escape(ev.summary) + "</p>\n";
  h += "<table>\n<tr>" + th("hypothesis") + th("deviance") + th("criterion") + "</tr>\n";
  h += "<tr>" + td("no random bias") + td(g(ev.deviance_none)) + td(g(ev.criterion_none)) +
       "</tr>\n";
  h += "<tr>" + td("Wiener process") + td(g(ev.deviance_wiener)) + td(g(ev.criterion_wiener)) +
       "</tr>\n";
  h += "<tr>" + td("Gauss-Markov process") + td(g(ev.deviance_gauss_markov)) +
       td(g(ev.criterion_gauss_markov)) + "</tr>\n</table>\n";
  h += fmt::format(
      "<p>Log-log slope of the ADEV over its last three points: {} (+0.5 for a Wiener process, "
      "negative after a Gauss-Markov hump); of the PSD over its lowest decade: {} (-2 for a "
      "Wiener process, about 0 on a Gauss-Markov plateau).</p>\n",
      g(ev.adev_end_slope), g(ev.psd_low_frequency_slope));

  // Class.
  if (in.sensor == Sensor::gyroscope) {
    h += "<h3>Accuracy class (lab manual, Table 1)</h3>\n<p class=\"verdict\">" +
         html_escape(class_sentence(r)) + "</p>\n";
  } else {
    h += "<h3>Accuracy class</h3>\n<p>" + html_escape(kNoAccelerometerClass) + "</p>\n";
  }

  const std::vector<std::string> notes = all_notes(r, in);
  if (!notes.empty()) {
    h += "<h3>Notes</h3>\n<ul>\n";
    for (const std::string& n : notes) h += "<li>" + html_escape(n) + "</li>\n";
    h += "</ul>\n";
  }
  return in_sensor_units(h, in.sensor);
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

std::string markdown_summary(const model::AnalysisResult& r, const ReportInput& in) {
  std::string md = fmt::format("## {}\n\n", record_title(in));
  md += fmt::format(
      "Recording `{}`, channel {}, temperature {}: {} samples at {} Hz ({:.3g} h){}.\n\n",
      in.file_name.empty() ? "-" : in.file_name, in.channel.empty() ? "-" : in.channel,
      in.temperature_channel.empty() ? "none" : in.temperature_channel, r.samples,
      g(r.sample_rate_hz), r.duration_s / kSecondsPerHour,
      r.gaps.empty() ? std::string()
                     : fmt::format(", {} gap(s) with {} samples missing "
                                   "(analysed by contiguous stretches)",
                                   r.gaps.size(), missing_samples(r.gaps)));

  md += "### Systematic part\n\n";
  if (r.systematic) {
    const model::SystematicFit& s = *r.systematic;
    md += fmt::format("Polynomial of degree {} in (T - {:.4g} degC){}{}.\n\n", s.degree, s.t_ref_c,
                      s.degree_chosen ? ", degree chosen by the criterion" : "",
                      s.constant_fallback ? ", constant fallback" : "");
    md += "| coefficient | value | standard error | unit |\n|---|---:|---:|---|\n";
    for (std::size_t j = 0; j < s.coefficients.size(); ++j) {
      const double se = j < s.standard_errors.size() ? s.standard_errors[j] : kNaN;
      md += fmt::format("| c{} | {:.6g} | {} | {} |\n", j, s.coefficients[j], g(se),
                        coefficient_unit(j));
    }
    md += fmt::format(
        "\n- systematic bias at {:.4g} degC: **{:.6g} deg/h**; temperature span {:.4g} degC\n"
        "- lab's polyfit(T, Y, 2) constant term: {:.6g} deg/h{}\n",
        s.t_ref_c, s.bias_deg_h, s.temperature_span_c, s.lab_constant_term_deg_h,
        s.lab_constant_meaningful ? "" : " (not meaningful: the span is too small)");
    if (!s.note.empty()) md += "- " + s.note + "\n";
    md += "\n";
  } else {
    md += in.record_mean_deg_h
              ? fmt::format("No temperature: only the record mean, {:.6g} deg/h, was removed.\n\n",
                            *in.record_mean_deg_h)
              : std::string("No temperature: only the record mean was removed.\n\n");
  }

  md += fmt::format("### Noise model (terms {}, 95 % intervals)\n\nFit: {}.\n\n",
                    to_string(r.noise.terms), r.noise.message);
  md += "| parameter | value | 95 % interval | status | unit |\n|---|---:|---|---|---|\n";
  for (const NoiseParameter& p : kNoiseParameters) {
    const model::ParameterEstimate& e = r.noise.estimate(p);
    const ParameterText t = parameter_text(e);
    md += fmt::format("| {} | {} | {} | {} | {} |\n", p.name, t.value, t.interval,
                      model::to_string(e.status), p.unit);
  }
  const char* at_edge = r.bias_instability_at_edge ? " (at the end of the tau range)" : "";
  if (in.sensor == Sensor::gyroscope) {
    md += fmt::format(
        "\n- ARW {} deg/sqrt(h); bias instability (ADEV minimum) **{} deg/h** at {} s{}\n",
        g(r.arw_deg_sqrt_h), g(r.bias_instability_deg_h), g(r.bias_instability_tau_s), at_edge);
  } else {
    md += fmt::format(
        "\n- VRW {} m/s/sqrt(h); bias instability (ADEV minimum) **{} m/s^2** ({} mg) at {} "
        "s{}\n",
        g(velocity_random_walk_m_s_sqrt_h(r.noise.model.N)), g(r.bias_instability_deg_h),
        g(r.bias_instability_deg_h / kStandardGravity * 1000.0), g(r.bias_instability_tau_s),
        at_edge);
  }
  md += fmt::format("- graphical readings: ADEV N {}, K {}, minimum {} deg/h; PSD N {}, K {}\n",
                    g(r.adev_readings.N), g(r.adev_readings.K),
                    g(r.adev_readings.bias_instability_deg_h), g(r.psd_readings.N),
                    g(r.psd_readings.K));
  md += "- sensor bandwidth: " + bandwidth_sentence(r.noise.bandwidth) + "\n";
  md += "- spectral lines: " + lines_sentence(r.noise) + "\n";
  md += "- random bias: " + random_bias_answer(r) + "\n";
  if (!r.evidence.summary.empty()) md += "  (" + r.evidence.summary + ")\n";
  md += in.sensor == Sensor::gyroscope
            ? "- accuracy class: **" + class_sentence(r) + "**\n"
            : "- accuracy class: " + std::string(kNoAccelerometerClass) + "\n";
  const std::vector<std::string> notes = all_notes(r, in);
  if (!notes.empty()) {
    md += "\nNotes:\n\n";
    for (const std::string& n : notes) md += "- " + n + "\n";
  }
  return in_sensor_units(md, in.sensor);
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
  Report rep;
  rep.title = record_title(input);
  const std::vector<Plot> plots = report_plots(result, input, options);
  static const char* kCaptions[][2] = {
      {"time",
       "Rate (block means, with the minimum and maximum of each block) and temperature "
       "against time."},
      {"bias_temperature",
       "Bias (block means of the rate) against temperature, with the fitted "
       "polynomial."},
      {"psd",
       "Square root of the two-sided PSD of the residual, log-log with equal decades, with "
       "the white-noise level and the random-walk line of the graphical readings."},
      {"adev",
       "Overlapping Allan deviation of the residual with its 95 % confidence band, the "
       "fitted model and the line of each term, log-log with equal decades."},
  };
  // No bias plot without a temperature: the captions shift by one.
  const bool has_bias_plot = plots.size() == 4;
  std::vector<FigureSpec> specs;
  for (std::size_t i = 0; i < plots.size(); ++i) {
    const std::size_t kind = has_bias_plot || i == 0 ? i : i + 1;
    specs.push_back({kCaptions[kind][0], kCaptions[kind][1]});
  }
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
    for (const Figure& f : rep.figures) h += figure_html(f);
  }
  h += html_tables(result, input);
  h += "</section>\n";

  rep.markdown = markdown_summary(result, input);
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

std::string html_document(const Report& report) {
  return html_document(std::span<const Report>(&report, 1), "foglab report: " + report.title);
}

}  // namespace foglab::report
