// foglab — the plots of one analysed recording (report.h): the record
// against time, the bias against temperature, the PSD and the Allan
// deviation with the fitted model, and the decimated preview they are drawn
// from.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/units.h"
#include "foglab/report/report.h"
#include "report_internal.h"

namespace foglab::report {

using namespace detail;

namespace {

std::vector<double> log_space(double lo, double hi, int n) {
  std::vector<double> out;
  if (!(lo > 0.0) || !(hi > lo) || n < 2) return out;
  const double a = std::log10(lo), b = std::log10(hi);
  for (int k = 0; k < n; ++k) out.push_back(std::pow(10.0, a + (b - a) * k / (n - 1)));
  return out;
}

double polynomial(const model::SystematicFit& s, double t_c) {
  double v = 0.0, p = 1.0;
  for (double c : s.coefficients) {
    v += c * p;
    p *= t_c - s.t_ref_c;
  }
  return v;
}

// ---- the four plots ----------------------------------------------------------

// A region from x_low to x_high shaded over the whole height of a plot
// (whose y axis is logarithmic when `log_y`); it does not set the ranges.
Series full_height_band(std::string title, const char* color, double opacity, double x_low,
                        double x_high, bool log_y) {
  Series region;
  region.title = std::move(title);
  region.style = SeriesStyle::band;
  region.color = color;
  region.fill_opacity = opacity;
  region.sets_range = false;
  region.x = {x_low, x_high};
  const double bottom = log_y ? 1e-30 : -1e30;
  region.y_low = {bottom, bottom};
  region.y_high = {1e30, 1e30};
  return region;
}

// The gaps of the time axis, shaded over the whole height.
void mark_gaps(Plot& plot, const model::AnalysisResult& r, Language l) {
  const std::vector<GapSpan> spans = gap_spans_s(r.gaps, r.sample_rate_hz);
  for (std::size_t i = 0; i < spans.size(); ++i) {
    plot.series.push_back(full_height_band(
        i == 0 ? say(l, Text::an_plot_gap, r.gaps.size()) : std::string(), kGrey, 0.25,
        spans[i].start_s / kSecondsPerHour, spans[i].end_s / kSecondsPerHour, false));
  }
}

// A vertical line at `hour` over the rate's span [lo, hi].
Series vertical_line(std::string title, double hour, double lo, double hi, int dash_type) {
  Series line;
  line.title = std::move(title);
  line.x = {hour, hour};
  line.y = {lo, hi};
  line.color = kOrange;
  line.dash_type = dash_type;
  line.line_width = 1.5;
  line.sets_range = false;
  return line;
}

// The bias steps (dashed vertical lines over the rate's span; levelled), the
// jumps of the bias across gaps judged significant (dotted, where the record
// resumes; measured, not levelled) and spikes (a mark at the edge of their
// preview block) the analysis found.
void mark_steps_and_spikes(Plot& plot, const model::AnalysisResult& r, const RecordPreview& p,
                           const std::vector<double>& hours, Language l) {
  if (hours.empty() || !(r.sample_rate_hz > 0.0)) return;
  const auto [lo, hi] = [&] {
    double a = 0.0, b = 0.0;
    bool any = false;
    for (std::size_t k = 0; k < hours.size(); ++k) {
      const double l = p.block_samples > 1 ? p.rate_min_deg_h[k] : p.rate_mean_deg_h[k];
      const double h = p.block_samples > 1 ? p.rate_max_deg_h[k] : p.rate_mean_deg_h[k];
      if (!std::isfinite(l) || !std::isfinite(h)) continue;
      a = any ? std::min(a, l) : l;
      b = any ? std::max(b, h) : h;
      any = true;
    }
    return std::pair{a, b};
  }();
  for (std::size_t i = 0; i < r.steps.indices.size(); ++i) {
    const double t = elapsed_s(r.steps.indices[i], r.gaps, r.sample_rate_hz) / kSecondsPerHour;
    plot.series.push_back(vertical_line(
        i == 0 ? say(l, r.steps.left_as_noise() ? Text::an_plot_step_as_noise : Text::an_plot_step,
                     r.steps.indices.size())
               : std::string(),
        t, lo, hi, 2));
  }
  const auto significant = std::count_if(r.steps.across_gaps.begin(), r.steps.across_gaps.end(),
                                         [](const model::GapJump& j) { return j.significant; });
  bool first_jump = true;
  for (const model::GapJump& j : r.steps.across_gaps) {
    if (!j.significant) continue;
    const double t = elapsed_s(j.before_sample, r.gaps, r.sample_rate_hz) / kSecondsPerHour;
    plot.series.push_back(vertical_line(
        first_jump ? say(l, Text::an_plot_gap_jump, significant) : std::string(), t, lo, hi, 3));
    first_jump = false;
  }
  if (r.spikes.indices.empty()) return;
  Series spikes;
  spikes.title = say(l, Text::an_plot_spike, r.spikes.count);
  spikes.style = SeriesStyle::points;
  spikes.color = kPurple;
  spikes.point_type = 9;  // a filled triangle
  spikes.point_size = 1.0;
  spikes.sets_range = false;
  const double block_h = hours.size() > 1 ? hours[1] - hours[0] : 1.0;
  for (std::size_t i = 0; i < r.spikes.indices.size(); ++i) {
    const double t = elapsed_s(r.spikes.indices[i], r.gaps, r.sample_rate_hz) / kSecondsPerHour;
    const auto k = static_cast<std::size_t>(std::clamp(std::round((t - hours.front()) / block_h),
                                                       0.0, static_cast<double>(hours.size() - 1)));
    const bool up = r.spikes.sizes_deg_h[i] > 0.0;
    const double y = p.block_samples > 1 ? (up ? p.rate_max_deg_h[k] : p.rate_min_deg_h[k])
                                         : p.rate_mean_deg_h[k];
    spikes.x.push_back(t);
    spikes.y.push_back(std::isfinite(y) ? y : (up ? hi : lo));
  }
  plot.series.push_back(std::move(spikes));
}

Plot time_plot(const ReportInput& in, const model::AnalysisResult& r, const std::string& title,
               Language l) {
  const RecordPreview& p = in.preview;
  Plot plot;
  plot.title = say(l, Text::an_plot_time, title);
  plot.x_label = say(l, Text::an_axis_time);
  plot.y_label = say(l, Text::an_axis_rate);
  plot.y2_label = say(l, Text::an_axis_temperature);
  plot.key = "top left";
  std::vector<double> hours(p.time_s.size());
  for (std::size_t k = 0; k < hours.size(); ++k) hours[k] = p.time_s[k] / kSecondsPerHour;
  if (p.block_samples > 1) {
    Series env;
    env.title = say(l, Text::an_legend_envelope, p.block_samples);
    env.style = SeriesStyle::band;
    env.x = hours;
    env.y_low = p.rate_min_deg_h;
    env.y_high = p.rate_max_deg_h;
    env.color = kLightBlue;
    env.fill_opacity = 0.35;
    plot.series.push_back(std::move(env));
  }
  Series mean;
  mean.title = say(l, p.block_samples > 1 ? Text::an_legend_block_mean : Text::an_legend_rate);
  mean.x = hours;
  mean.y = p.rate_mean_deg_h;
  mean.color = kBlue;
  mean.line_width = 1.0;
  plot.series.push_back(std::move(mean));
  if (!p.temperature_c.empty()) {
    Series t;
    t.title = in.temperature_channel.empty()
                  ? say(l, Text::an_legend_temperature)
                  : say(l, Text::an_legend_temperature_channel, in.temperature_channel);
    t.x = hours;
    t.y = p.temperature_c;
    t.color = kRed;
    t.line_width = 2.0;
    t.y2 = true;
    plot.series.push_back(std::move(t));
  }
  mark_gaps(plot, r, l);
  mark_steps_and_spikes(plot, r, p, hours, l);
  return plot;
}

Plot bias_plot(const model::SystematicFit& s, const ReportInput& in, const std::string& title,
               std::size_t points, Language l) {
  const RecordPreview& p = in.preview;
  Plot plot;
  plot.title = say(l, Text::an_plot_bias, title);
  plot.x_label = say(l, Text::an_axis_temperature);
  plot.y_label = say(l, Text::an_axis_bias);
  plot.key = "top left";
  // Regroup the preview's blocks into about `points` means.
  const std::size_t n = std::min(p.rate_mean_deg_h.size(), p.temperature_c.size());
  const std::size_t group =
      std::max<std::size_t>(1, (n + points - 1) / std::max<std::size_t>(points, 1));
  Series dots;
  dots.style = SeriesStyle::points;
  dots.color = kBlue;
  dots.point_size = 0.5;
  double t_lo = std::numeric_limits<double>::infinity(), t_hi = -t_lo;
  for (std::size_t k = 0; k < n; k += group) {
    double sr = 0.0, st = 0.0;
    std::size_t m = 0;
    for (std::size_t j = k; j < std::min(n, k + group); ++j) {
      if (!std::isfinite(p.rate_mean_deg_h[j]) || !std::isfinite(p.temperature_c[j])) continue;
      sr += p.rate_mean_deg_h[j];
      st += p.temperature_c[j];
      ++m;
    }
    if (m == 0) continue;
    dots.x.push_back(st / static_cast<double>(m));
    dots.y.push_back(sr / static_cast<double>(m));
    t_lo = std::min(t_lo, dots.x.back());
    t_hi = std::max(t_hi, dots.x.back());
  }
  const double seconds =
      static_cast<double>(group) * (p.time_s.size() > 1 ? (p.time_s[1] - p.time_s[0]) : 0.0);
  dots.title = seconds > 0.0 ? say(l, Text::an_legend_block_means_s, seconds)
                             : say(l, Text::an_legend_block_means);
  plot.series.push_back(std::move(dots));
  if (!(t_hi >= t_lo)) {
    t_lo = s.temperature_min_c;
    t_hi = s.temperature_max_c;
  }
  if (!(t_hi > t_lo)) {
    t_lo -= 0.5;
    t_hi += 0.5;
  }
  Series fit;
  fit.title = say(l, Text::an_legend_polynomial, s.degree, s.t_ref_c,
                  s.constant_fallback ? say(l, Text::an_constant_fallback) : "");
  fit.color = kRed;
  fit.line_width = 2.5;
  for (int k = 0; k <= 100; ++k) {
    const double t = t_lo + (t_hi - t_lo) * k / 100.0;
    fit.x.push_back(t);
    fit.y.push_back(polynomial(s, t));
  }
  plot.series.push_back(std::move(fit));
  return plot;
}

// The lab's graphical reading of a line from the PSD, or the fit's value
// (resolved terms only) when the PSD shows none, with where it came from.
std::pair<std::optional<double>, std::string> reading_or_fit(const std::optional<double>& reading,
                                                             const model::ParameterEstimate& fit,
                                                             Language l) {
  if (reading) return {reading, say(l, Text::an_source_psd)};
  if (fit.status == model::TermStatus::resolved) return {fit.value, say(l, Text::an_source_fit)};
  return {std::nullopt, ""};
}

// A dashed reference line that does not set the plot's range.
Series reference_line(std::string title, const char* color) {
  Series line;
  line.title = std::move(title);
  line.color = color;
  line.dash_type = 2;
  line.line_width = 2.0;
  line.sets_range = false;
  return line;
}

Plot psd_plot(const model::AnalysisResult& r, const std::string& title, Language l) {
  const stats::PsdResult& psd = r.psd_smoothed.frequency_hz.empty() ? r.psd : r.psd_smoothed;
  Plot plot;
  plot.title = say(l, Text::an_plot_psd, title);
  plot.x_label = say(l, Text::an_axis_frequency);
  plot.y_label = say(l, Text::an_axis_sqrt_psd);
  plot.log_x = plot.log_y = true;
  plot.equal_decades = true;
  plot.key = "bottom left";
  Series data;
  data.title =
      say(l, &psd == &r.psd_smoothed ? Text::an_legend_welch_smoothed : Text::an_legend_welch);
  data.style = SeriesStyle::linespoints;
  data.color = kBlue;
  data.line_width = 1.0;
  data.point_size = 0.4;
  data.x = psd.frequency_hz;
  data.y.resize(psd.psd.size());
  for (std::size_t k = 0; k < psd.psd.size(); ++k) data.y[k] = std::sqrt(psd.psd[k]);
  plot.series.push_back(std::move(data));
  if (psd.frequency_hz.empty()) return plot;
  const double f_lo = psd.frequency_hz.front(), f_hi = psd.frequency_hz.back();

  // Each spectral line the analysis found, shaded over its bins (at least
  // one bin of the raw estimate wide, so a single-bin line shows).
  const double bin_hz =
      r.psd.frequency_hz.size() > 1 ? r.psd.frequency_hz[1] - r.psd.frequency_hz[0] : 0.0;
  // A periodic disturbance's harmonics each on its own (one key).
  for (const SpectralLine& line : r.noise.lines) {
    if (line.bin_frequency_hz.empty()) continue;
    const Text legend = !line.harmonics.empty()    ? Text::an_legend_periodic_band
                        : line.removed_from_record ? Text::an_legend_line_removed_band
                                                   : Text::an_legend_line_band;
    std::string title = say(l, legend, g(line.frequency_hz), g(std::sqrt(line.variance)));
    if (!line.harmonics.empty()) {
      for (const double f : line.bin_frequency_hz) {
        plot.series.push_back(full_height_band(std::exchange(title, std::string()), kPurple, 0.2,
                                               f - 0.5 * bin_hz, f + 0.5 * bin_hz, true));
      }
      continue;
    }
    const auto [low, high] =
        std::minmax_element(line.bin_frequency_hz.begin(), line.bin_frequency_hz.end());
    plot.series.push_back(full_height_band(std::move(title), kPurple, 0.2, *low - 0.5 * bin_hz,
                                           *high + 0.5 * bin_hz, true));
  }

  const auto [n, n_source] = reading_or_fit(r.psd_readings.N, r.noise.N, l);
  if (n) {
    Series white = reference_line(say(l, Text::an_legend_white_level, g(*n), n_source), kGreen);
    white.x = {f_lo, f_hi};
    white.y = {*n, *n};
    plot.series.push_back(std::move(white));
  }
  const auto [k, k_source] = reading_or_fit(r.psd_readings.K, r.noise.K, l);
  if (k) {
    Series walk = reference_line(say(l, Text::an_legend_random_walk, g(*k), k_source), kRed);
    // From the lowest frequency to 1 Hz (where the lab reads it), or to the
    // white level when that is crossed later.
    const NoiseModel walk_model{.K = *k};
    double f_end = std::max(1.0, n ? *k / (2.0 * std::numbers::pi * *n) : 1.0);
    f_end = std::min(f_end, f_hi);
    walk.x = log_space(f_lo, std::max(f_end, f_lo * 1.01), 50);
    for (double f : walk.x) {
      walk.y.push_back(std::sqrt(rate_psd(walk_model, NoiseTerm::random_walk, f, 0.0)));
    }
    plot.series.push_back(std::move(walk));
  }
  return plot;
}

struct TermLine {
  NoiseTerm term;
  Text label;
  const char* color;
  int dash;
};

Plot adev_plot(const model::AnalysisResult& r, const std::string& title, Language l) {
  const stats::AllanResult& a = r.allan;
  Plot plot;
  plot.title = say(l, Text::an_plot_adev, title);
  plot.x_label = say(l, Text::an_axis_tau);
  plot.y_label = say(l, Text::an_axis_adev);
  plot.log_x = plot.log_y = true;
  plot.equal_decades = true;
  plot.headroom_decades = 1;
  plot.key = "top right";
  if (a.ci95_low.size() == a.tau_s.size() && a.ci95_high.size() == a.tau_s.size()) {
    Series band;
    band.title = say(l, Text::interval95);
    band.style = SeriesStyle::band;
    band.color = kLightBlue;
    band.fill_opacity = 0.35;
    band.x = a.tau_s;
    band.y_low = a.ci95_low;
    band.y_high = a.ci95_high;
    plot.series.push_back(std::move(band));
  }
  if (r.noise.bandwidth.resolved && !a.tau_s.empty()) {
    // Where the filter takes more than 1 % off the white level's Allan
    // variance: from the first tau to the end of that region.
    const model::BandwidthEstimate& b = r.noise.bandwidth;
    double end = a.tau_s.front();
    while (end < a.tau_s.back() &&
           1.0 - white_allan_factor(b.bandwidth, end, b.sample_interval_s) > 0.01) {
      end *= 1.05;
    }
    if (end > a.tau_s.front()) {
      plot.series.push_back(full_height_band(say(l, Text::an_legend_bandwidth), kGrey, 0.12,
                                             a.tau_s.front(), end, true));
    }
  }
  if (const int k = r.noise.first_taus_left_out;
      k > 0 && r.noise.left_out_below_tau_s > a.tau_s.front()) {
    plot.series.push_back(full_height_band(say(l, Text::an_legend_first_taus, k), kOrange, 0.12,
                                           a.tau_s.front(), r.noise.left_out_below_tau_s, true));
  }
  Series dev;
  dev.title = say(l, Text::an_legend_oadev);
  dev.style = SeriesStyle::linespoints;
  dev.color = kBlue;
  dev.line_width = 1.0;
  dev.point_size = 0.6;
  dev.x = a.tau_s;
  dev.y = a.dev;
  plot.series.push_back(std::move(dev));
  if (a.tau_s.empty()) return plot;

  const NoiseModel& m = r.noise.model;
  const std::vector<double> taus = log_space(a.tau_s.front(), a.tau_s.back(), 80);
  static const TermLine kTerms[] = {
      {NoiseTerm::quantisation, Text::an_legend_term_q, kPurple, 4},
      {NoiseTerm::white, Text::an_legend_term_n, kGreen, 2},
      {NoiseTerm::flicker, Text::an_legend_term_b, kOrange, 2},
      {NoiseTerm::random_walk, Text::an_legend_term_k, kRed, 2},
      {NoiseTerm::ramp, Text::an_legend_term_r, kYellow, 4},
      {NoiseTerm::gauss_markov, Text::an_legend_term_gm, kGrey, 5},
  };
  for (const TermLine& t : kTerms) {
    if (!(m.coefficient(t.term) > 0.0)) continue;
    Series line;
    line.title = say(l, t.label);
    line.color = t.color;
    line.dash_type = t.dash;
    line.line_width = 1.5;
    line.sets_range = false;
    line.x = taus;
    if (t.term == NoiseTerm::white && r.noise.bandwidth.resolved) {
      line.title = say(l, Text::an_legend_white_bandwidth, g(r.noise.bandwidth.cutoff_hz));
    }
    for (double tau : taus) {
      line.y.push_back(std::sqrt(model::fitted_allan_variance(r.noise, t.term, tau)));
    }
    plot.series.push_back(std::move(line));
  }
  // The lines the fit took (those taken out of the record are not in its
  // Allan deviation either).
  std::vector<double> kept_hz;
  for (const SpectralLine& line : r.noise.lines) {
    if (!line.removed_from_record) kept_hz.push_back(line.frequency_hz);
  }
  if (!kept_hz.empty()) {
    Series line;
    line.title = kept_hz.size() == 1 ? say(l, Text::an_legend_line, g(kept_hz.front()))
                                     : say(l, Text::an_legend_lines, kept_hz.size());
    line.color = kPurple;
    line.dash_type = 3;
    line.line_width = 1.5;
    line.sets_range = false;
    line.x = taus;
    for (double tau : taus) line.y.push_back(std::sqrt(model::lines_allan_variance(r.noise, tau)));
    plot.series.push_back(std::move(line));
  }
  Series fit;
  fit.title = say(l, Text::an_legend_fit, terms_text(r.noise.terms, l));
  fit.color = kBlack;
  fit.line_width = 2.0;
  fit.sets_range = false;
  fit.x = taus;
  for (double tau : taus) fit.y.push_back(std::sqrt(model::fitted_allan_variance(r.noise, tau)));
  plot.series.push_back(std::move(fit));
  if (!r.psd_allan.tau_s.empty()) {
    // The manual's eq. (17): the same model through its PSD, at the measured taus.
    Series psd;
    psd.title = say(l, Text::an_legend_eq17);
    psd.color = kLightBlue;
    psd.dash_type = 2;
    psd.line_width = 2.5;
    psd.sets_range = false;
    psd.x = r.psd_allan.tau_s;
    psd.y = r.psd_allan.adev_deg_h;
    plot.series.push_back(std::move(psd));
  }
  if (r.bias_instability_tau_s > 0.0 && r.bias_instability_deg_h > 0.0) {
    Series min;
    min.title =
        say(l, Text::an_legend_minimum, g(r.bias_instability_deg_h), g(r.bias_instability_tau_s));
    min.style = SeriesStyle::points;
    min.point_type = 6;
    min.point_size = 1.6;
    min.color = kRed;
    min.x = {r.bias_instability_tau_s};
    min.y = {r.bias_instability_deg_h};
    plot.series.push_back(std::move(min));
  }
  if (const stats::AllanDrift& d = r.allan_drift; d.any()) {
    // The taus whose Allan variance trends over the run, on the measured
    // curve (log-log interpolated where the reported grid is not octaves).
    Series drift;
    drift.title = say(l, Text::an_legend_drift, d.blocks);
    drift.style = SeriesStyle::points;
    drift.point_type = 8;
    drift.point_size = 1.4;
    drift.color = kOrange;
    drift.sets_range = false;
    for (std::size_t i = 0; i < d.tau_s.size(); ++i) {
      const double tau = d.tau_s[i];
      if (!d.drifting[i] || tau < a.tau_s.front() || tau > a.tau_s.back()) continue;
      const auto hi = std::ranges::lower_bound(a.tau_s, tau * (1.0 - 1e-9));
      const auto k = static_cast<std::size_t>(hi - a.tau_s.begin());
      double dev = a.dev[k];
      if (a.tau_s[k] > tau * (1.0 + 1e-9) && k > 0) {
        const double w = std::log(tau / a.tau_s[k - 1]) / std::log(a.tau_s[k] / a.tau_s[k - 1]);
        dev = std::exp((1.0 - w) * std::log(a.dev[k - 1]) + w * std::log(a.dev[k]));
      }
      drift.x.push_back(tau);
      drift.y.push_back(dev);
    }
    if (!drift.x.empty()) plot.series.push_back(std::move(drift));
  }
  // The key sits in the decade of headroom: past ten entries (a filter, a
  // line, the first taus left out, a drift) its lines are set smaller so
  // that it stays clear of the first taus.
  if (std::ranges::count_if(plot.series, [](const Series& s) { return !s.title.empty(); }) > 10) {
    plot.key_font = ",8";
  }
  return plot;
}

// The short taus' Allan deviation block by block over the run (allan_drift),
// as a change from the blocks' mean (their Allan variances averaged): the
// taus the trend test calls in colour, the others in grey, which show how
// far the blocks of a stationary record scatter.
Plot drift_plot(const stats::AllanDrift& d, const std::string& title, Language l) {
  static constexpr const char* kColours[] = {kRed, kOrange, kGreen, kBlue, kPurple, kYellow};
  Plot plot;
  plot.title = say(l, Text::an_plot_drift, title);
  plot.x_label = say(l, Text::an_axis_time);
  plot.y_label = say(l, Text::an_axis_drift_change);
  plot.key = "top left";
  std::vector<double> hours;
  for (const double t : d.block_time_s) hours.push_back(t / kSecondsPerHour);
  std::string steady_taus;
  std::optional<std::size_t> first_steady;  // the grey line that carries their legend entry
  std::size_t called = 0;
  for (std::size_t i = 0; i < d.tau_s.size(); ++i) {
    const std::vector<double>& adev = d.block_adev[i];
    double sum = 0.0;
    int used = 0;
    for (const double v : adev) {
      if (std::isfinite(v)) sum += v * v, ++used;
    }
    const double mean_adev = std::sqrt(sum / used);
    Series s;
    s.x = hours;
    for (const double v : adev) s.y.push_back(100.0 * (v / mean_adev - 1.0));
    if (d.drifting[i]) {
      s.title = say(l, Text::an_legend_drift_tau, g(d.tau_s[i]),
                    fmt::format("{:+.2f}", d.trend_z[i]), g(d.last_to_first[i]));
      s.style = SeriesStyle::linespoints;
      s.color = kColours[called++ % std::size(kColours)];
      s.line_width = 1.5;
      s.point_size = 0.7;
    } else {
      steady_taus += (steady_taus.empty() ? "" : ", ") + g(d.tau_s[i]);
      if (!first_steady) first_steady = plot.series.size();
      s.color = kGrey;
      s.line_width = 1.0;
    }
    plot.series.push_back(std::move(s));
  }
  if (first_steady) {
    plot.series[*first_steady].title = say(l, Text::an_legend_drift_steady, steady_taus);
  }
  // The lines fill the plot's width: room above them for the key.
  double low = 0.0, high = 0.0;
  for (const Series& s : plot.series) {
    for (const double y : s.y) {
      if (std::isfinite(y)) low = std::min(low, y), high = std::max(high, y);
    }
  }
  const double pad = 0.05 * (high - low);
  plot.y_range = AxisRange{low - pad, high + (0.12 + 0.07 * called) * (high - low) + 4.0 * pad};
  return plot;
}

bool has_bias_plot(const model::AnalysisResult& r, const ReportInput& in) {
  return r.systematic && !in.preview.temperature_c.empty();
}

}  // namespace

std::vector<FigureSpec> detail::report_figure_specs(const model::AnalysisResult& result,
                                                    const ReportInput& input, Language l) {
  std::vector<FigureSpec> specs{{"time", say(l, Text::an_caption_time)}};
  if (has_bias_plot(result, input)) {
    specs.push_back({"bias_temperature", say(l, Text::an_caption_bias)});
  }
  specs.push_back({"psd", say(l, Text::an_caption_psd)});
  specs.push_back({"adev", say(l, Text::an_caption_adev)});
  if (result.allan_drift.any()) {
    specs.push_back({"allan_drift", say(l, Text::an_caption_drift, result.allan_drift.blocks)});
  }
  return specs;
}

RecordPreview preview_record(std::span<const double> rate_deg_h,
                             std::span<const double> temperature_c, double sample_rate_hz,
                             std::size_t points, std::span<const Gap> gaps) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(
        fmt::format("preview_record: sample rate {} Hz: expected > 0", sample_rate_hz));
  }
  if (!temperature_c.empty() && temperature_c.size() != rate_deg_h.size()) {
    throw UsageError(
        fmt::format("preview_record: {} temperature samples for {} rate samples: expected as many",
                    temperature_c.size(), rate_deg_h.size()));
  }
  if (points < 1) throw UsageError("preview_record: points 0: expected at least 1");
  RecordPreview p;
  const std::size_t n = rate_deg_h.size();
  if (n == 0) return p;
  check_gaps(gaps, static_cast<std::int64_t>(n), "preview_record");
  const std::size_t block = (n + points - 1) / points;
  p.block_samples = static_cast<std::int64_t>(block);
  const std::vector<Stretch> stretches = contiguous_stretches(static_cast<std::int64_t>(n), gaps);
  const std::vector<GapSpan> spans = gap_spans_s(gaps, sample_rate_hz);
  std::int64_t missing_before = 0;  // of the stretch at hand
  auto time_of = [&](std::size_t k) {
    return static_cast<double>(static_cast<std::int64_t>(k) + missing_before) / sample_rate_hz;
  };
  for (std::size_t j = 0; j < stretches.size(); ++j) {
    const auto first = static_cast<std::size_t>(stretches[j].begin);
    const auto last = static_cast<std::size_t>(stretches[j].end);
    if (j > 0) {
      // a point without values in the gap, so that no line crosses it
      missing_before += gaps[j - 1].missing_samples;
      p.time_s.push_back(0.5 * (spans[j - 1].start_s + spans[j - 1].end_s));
      p.rate_mean_deg_h.push_back(kNaN);
      p.rate_min_deg_h.push_back(kNaN);
      p.rate_max_deg_h.push_back(kNaN);
      if (!temperature_c.empty()) p.temperature_c.push_back(kNaN);
    }
    for (std::size_t start = first; start < last; start += block) {
      const std::size_t end = std::min(last, start + block);
      double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo, tsum = 0.0;
      std::size_t m = 0, tm = 0;
      for (std::size_t k = start; k < end; ++k) {
        const double v = rate_deg_h[k];
        if (std::isfinite(v)) {
          sum += v;
          lo = std::min(lo, v);
          hi = std::max(hi, v);
          ++m;
        }
        if (!temperature_c.empty() && std::isfinite(temperature_c[k])) {
          tsum += temperature_c[k];
          ++tm;
        }
      }
      p.time_s.push_back(0.5 * (time_of(start) + time_of(end - 1)));
      p.rate_mean_deg_h.push_back(m > 0 ? sum / static_cast<double>(m) : kNaN);
      p.rate_min_deg_h.push_back(m > 0 ? lo : kNaN);
      p.rate_max_deg_h.push_back(m > 0 ? hi : kNaN);
      if (!temperature_c.empty()) {
        p.temperature_c.push_back(tm > 0 ? tsum / static_cast<double>(tm) : kNaN);
      }
    }
  }
  return p;
}

std::vector<Plot> report_plots(const model::AnalysisResult& result, const ReportInput& input,
                               const ReportOptions& options) {
  const Language l = options.language;
  const std::string title = record_title(input, l);
  std::vector<Plot> plots;
  plots.push_back(time_plot(input, result, title, l));
  if (has_bias_plot(result, input)) {
    plots.push_back(bias_plot(*result.systematic, input, title, options.bias_points, l));
  }
  plots.push_back(psd_plot(result, title, l));
  plots.push_back(adev_plot(result, title, l));
  if (result.allan_drift.any()) plots.push_back(drift_plot(result.allan_drift, title, l));
  if (input.sensor != Sensor::gyroscope) {
    // An accelerometer's plots say m/s^2, and its noise terms by their names.
    for (Plot& p : plots) {
      for (std::string* text : {&p.title, &p.x_label, &p.y_label, &p.y2_label}) {
        *text = sensor_text(*text, input.sensor, l);
      }
      for (Series& s : p.series) s.title = sensor_text(s.title, input.sensor, l);
    }
  }
  return plots;
}

}  // namespace foglab::report
