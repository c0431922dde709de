// foglab — the lab-1 report (lab1.h).
#include "foglab/report/lab1.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

#include "foglab/core/language.h"
#include "foglab/core/units.h"
#include "report_internal.h"

namespace foglab::report {
namespace {

using namespace detail;

constexpr const char* kColours[] = {kGrey, kBlue, kOrange};  // none, square, sine

constexpr std::size_t kMaxPlotPoints = 1500;

/// The modulation's name as the report shows it (sim's names are for the CLI and the JSON).
std::string modulation_title(sim::Modulation m, Language l) {
  switch (m) {
    case sim::Modulation::none:
      return say(l, Text::lab1_modulation_none);
    case sim::Modulation::square:
      return say(l, Text::lab1_modulation_square);
    case sim::Modulation::sine:
      return say(l, Text::lab1_modulation_sine);
  }
  return "";
}

/// Every k-th element so that at most kMaxPlotPoints remain.
std::vector<double> thin(const std::vector<double>& v, double scale = 1.0) {
  const std::size_t step =
      std::max<std::size_t>(1, (v.size() + kMaxPlotPoints - 1) / kMaxPlotPoints);
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); i += step) out.push_back(v[i] * scale);
  return out;
}

std::vector<double> scaled(const std::vector<double>& v, double scale) {
  std::vector<double> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [scale](double x) { return x * scale; });
  return out;
}

Series line(std::string title, std::vector<double> x, std::vector<double> y, const char* color,
            int dash = 1, bool y2 = false) {
  Series s;
  s.title = std::move(title);
  s.x = std::move(x);
  s.y = std::move(y);
  s.color = color;
  s.dash_type = dash;
  s.y2 = y2;
  return s;
}

Series points(std::string title, std::vector<double> x, std::vector<double> y, const char* color,
              double size = 0.35, bool y2 = false) {
  Series s = line(std::move(title), std::move(x), std::move(y), color, 1, y2);
  s.style = SeriesStyle::points;
  s.point_size = size;
  return s;
}

// ---- plots ----------------------------------------------------------------------------

Plot intensity_plot(const sim::Lab1Result& r, Language l) {
  Plot p;
  p.title = say(l, Text::lab1_plot_intensity);
  p.x_label = say(l, Text::lab1_axis_total_phase);
  p.y_label = say(l, Text::lab1_axis_detector);
  double lo = 0.0, hi = 0.0, gamma = 0.5;
  for (const sim::Lab1OpenLoopRun& run : r.open_loop) {
    const auto& tr = run.ramp.trace;
    if (!tr.total_phase_rad.empty()) {
      lo = std::min(lo, *std::min_element(tr.total_phase_rad.begin(), tr.total_phase_rad.end()));
      hi = std::max(hi, *std::max_element(tr.total_phase_rad.begin(), tr.total_phase_rad.end()));
    }
    gamma = run.ramp.gamma;
  }
  std::vector<double> x, y;
  for (int k = 0; k <= 400; ++k) {
    const double phi = lo + (hi - lo) * k / 400.0;
    x.push_back(phi);
    y.push_back(gamma * (1.0 + std::cos(phi)));
  }
  Series curve = line(say(l, Text::lab1_legend_cosine), x, y, kGrey, 2);
  curve.sets_range = false;
  p.series.push_back(std::move(curve));
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& tr = r.open_loop[k].ramp.trace;
    p.series.push_back(points(modulation_title(r.open_loop[k].modulation, l),
                              thin(tr.total_phase_rad), thin(tr.detector), kColours[k],
                              k == 0 ? 0.5 : 0.3));
  }
  p.key = "bottom center";
  return p;
}

Plot output_plot(const sim::Lab1Result& r, Language l) {
  Plot p;
  p.title = say(l, Text::lab1_plot_output);
  p.x_label = say(l, Text::lab1_axis_input_rate);
  p.y_label = say(l, Text::lab1_axis_output_mean);
  for (std::size_t k = 0; k < 3; ++k) {
    const sim::Lab1OpenLoopRun& run = r.open_loop[k];
    const auto& ps = run.ramp.periods;
    p.series.push_back(
        line(say(l, Text::lab1_legend_time_simulation, modulation_title(run.modulation, l)),
             thin(ps.rate_rad_s, kDegPerRad), thin(ps.demodulated), kColours[k]));
    sim::OpticsOptions o;
    o.modulation = run.modulation;
    std::vector<double> x, y;
    for (int i = 0; i <= 100; ++i) {
      const double rate = r.numbers.omega_pi2_rad_s * (-1.0 + 2.0 * i / 100.0);
      x.push_back(rate * kDegPerRad);
      y.push_back(sim::steady_state_output(r.coil, rate, o));
    }
    Series a = line(k == 2 ? say(l, Text::lab1_legend_steady_state) : "", x, y, kRed, 2);
    a.line_width = 1.0;
    p.series.push_back(std::move(a));
  }
  p.key = "bottom right";
  return p;
}

Plot trace_plot(const sim::OpticsResult& run, const std::string& title, const char* color,
                Language l) {
  Plot p;
  p.title = title;
  p.x_label = say(l, Text::lab1_axis_time_us);
  p.y_label = say(l, Text::lab1_axis_detector);
  p.y2_label = say(l, Text::lab1_axis_modulation_phase);
  const auto& tr = run.trace;
  const std::vector<double> t_us = scaled(tr.time_s, 1e6);
  Series det = line(say(l, Text::lab1_legend_detector), t_us, tr.detector, color);
  det.style = SeriesStyle::linespoints;
  det.point_size = 0.4;
  p.series.push_back(std::move(det));
  p.series.push_back(
      line(say(l, Text::lab1_legend_modulation_phase), t_us, tr.modulation_rad, kGreen, 2, true));
  p.key = "bottom right";
  return p;
}

Plot ramp_time_plot(const sim::Lab1Result& r, Language l) {
  Plot p;
  p.title = say(l, Text::lab1_plot_ramp_time);
  p.x_label = say(l, Text::lab1_axis_time_ms);
  p.y_label = say(l, Text::lab1_axis_output_lowpassed);
  p.y2_label = say(l, Text::lab1_axis_input_rate);
  for (std::size_t k = 1; k < 3; ++k) {
    const auto& ps = r.open_loop[k].ramp.periods;
    p.series.push_back(line(modulation_title(r.open_loop[k].modulation, l), thin(ps.time_s, 1e3),
                            thin(ps.output), kColours[k]));
  }
  const auto& ps = r.open_loop[1].ramp.periods;
  p.series.push_back(line(say(l, Text::lab1_legend_input_rate), thin(ps.time_s, 1e3),
                          thin(ps.rate_rad_s, kDegPerRad), kGreen, 2, true));
  p.key = "top left";
  return p;
}

Plot sweep_plot(const sim::Lab1Result& r, Language l) {
  Plot p;
  p.title = say(l, Text::lab1_plot_sweep);
  p.x_label = say(l, Text::lab1_axis_input_rate);
  p.y_label = say(l, Text::lab1_axis_open_scale_factor);
  p.y2_label = say(l, Text::lab1_axis_closed_scale_factor);
  auto add = [&](const sim::SweepResult& s, const std::string& title, const char* color,
                 SeriesStyle style, bool y2, double unit) {
    Series series = line(title, scaled(s.rates_rad_s, kDegPerRad), scaled(s.scale_factors, unit),
                         color, style == SeriesStyle::lines ? 2 : 1, y2);
    series.style = style;
    series.point_size = 0.9;
    p.series.push_back(std::move(series));
  };
  // Open-loop S per rad/s -> per deg/s: divide by kDegPerRad.
  add(r.sweep_square_analytic, say(l, Text::lab1_legend_square_analytic), kRed, SeriesStyle::lines,
      false, 1.0 / kDegPerRad);
  add(r.sweep_square, say(l, Text::lab1_legend_square_time), kBlue, SeriesStyle::points, false,
      1.0 / kDegPerRad);
  add(r.sweep_sine, say(l, Text::lab1_legend_sine_time), kOrange, SeriesStyle::points, false,
      1.0 / kDegPerRad);
  add(r.sweep_closed, say(l, Text::lab1_legend_closed_right), kGreen, SeriesStyle::linespoints,
      true, 1.0);
  p.y2_range = AxisRange{0.0, 1.2};
  p.y_range =
      AxisRange{0.0, 1.2 *
                         std::max(r.sweep_square.scale_factors.empty()
                                      ? 1.0
                                      : *std::max_element(r.sweep_square.scale_factors.begin(),
                                                          r.sweep_square.scale_factors.end()),
                                  1e-300) /
                         kDegPerRad};
  p.key = "bottom center";
  return p;
}

Plot closed_ramp_plot(const sim::Lab1Result& r, Language l) {
  Plot p;
  p.title = say(l, Text::lab1_plot_closed_ramp);
  p.x_label = say(l, Text::lab1_axis_input_rate);
  p.y_label = say(l, Text::lab1_axis_closed_output);
  p.y2_label = say(l, Text::lab1_axis_open_output);
  const auto& c = r.closed_ramp.periods;
  const auto& o = r.open_ramp.periods;
  const std::vector<double> x = thin(c.rate_rad_s, kDegPerRad);
  Series ideal = line(say(l, Text::lab1_legend_ideal), x, x, kGrey, 2);
  ideal.line_width = 1.0;
  p.series.push_back(std::move(ideal));
  p.series.push_back(line(say(l, Text::lab1_legend_closed), x, thin(c.output, kDegPerRad), kGreen));
  p.series.push_back(line(say(l, Text::lab1_legend_open_square_right),
                          thin(o.rate_rad_s, kDegPerRad), thin(o.demodulated), kBlue, 1, true));
  const double w = r.numbers.omega_pi2_deg_s;
  const double top = x.empty() ? w : x.back();
  Series edge = line(say(l, Text::lab1_legend_range_edge), {w, w}, {0.0, top}, kRed, 3);
  edge.sets_range = false;
  p.series.push_back(std::move(edge));
  // Room above the curves for the legend.
  p.y_range = AxisRange{0.0, 1.45 * top};
  p.y2_range = AxisRange{-1.1, 2.3};
  p.key = "top left";
  return p;
}

// Item 4.2's figure ("Скорость и выходной сигнал"): the rate ramp and the
// closed loop's output against time, in foglab's form (the rate -u/K_s,
// left) and the manual's (the feedback phase step u, right), with the open
// loop's range edge.
Plot closed_ramp_time_plot(const sim::Lab1Result& r, Language l) {
  Plot p;
  p.title = say(l, Text::lab1_plot_closed_ramp_time);
  p.x_label = say(l, Text::lab1_axis_time_ms);
  p.y_label = say(l, Text::lab1_axis_closed_output);
  p.y2_label = say(l, Text::lab1_axis_feedback_step);
  const auto& c = r.closed_ramp.periods;
  const std::vector<double> t = thin(c.time_s, 1e3);
  p.series.push_back(
      line(say(l, Text::lab1_legend_rate), t, thin(c.rate_rad_s, kDegPerRad), kGrey, 2));
  p.series.push_back(
      line(say(l, Text::lab1_legend_closed_output), t, thin(c.output, kDegPerRad), kGreen));
  p.series.push_back(
      line(say(l, Text::lab1_legend_feedback_step), t, thin(c.feedback_step_rad), kBlue, 1, true));
  const double w = r.numbers.omega_pi2_deg_s;
  Series edge = line(say(l, Text::lab1_legend_range_edge),
                     {t.empty() ? 0.0 : t.front(), t.empty() ? 0.0 : t.back()}, {w, w}, kRed, 3);
  edge.sets_range = false;
  p.series.push_back(std::move(edge));
  // u = -K_s rate is negative: the right axis spans the left one's range times -K_s, so u
  // falls from the top as the rate rises.
  const double top = c.rate_rad_s.empty() ? w : c.rate_rad_s.back() * kDegPerRad;
  p.y_range = AxisRange{0.0, 1.15 * top};
  p.y2_range = AxisRange{-1.15 * top / kDegPerRad * r.numbers.scale_factor_s, 0.0};
  // The rate rises from the bottom left, u falls from the top left: the bottom middle is free.
  p.key = "bottom center";
  return p;
}

// The closed loop at a constant rate (Fig. 11): the output (per modulation
// period) and the phase ramp psi (every sample: its steps and 2 pi resets)
// against time.
Plot closed_trace_plot(const sim::Lab1Result& r, std::size_t k, Language l) {
  const sim::OpticsResult& run = r.closed_traces.at(k);
  const auto& ps = run.periods;
  const double rate_deg_s = ps.rate_rad_s.empty() ? NAN : ps.rate_rad_s.back() * kDegPerRad;
  Plot p;
  p.title =
      say(l, Text::lab1_plot_closed_trace, rate_deg_s, rate_deg_s / r.numbers.omega_pi2_deg_s);
  p.x_label = say(l, Text::lab1_axis_time_us);
  p.y_label = say(l, Text::lab1_axis_closed_output);
  p.y2_label = say(l, Text::lab1_axis_feedback_phase);
  const std::vector<double> t = scaled(ps.time_s, 1e6);
  p.series.push_back(
      line(say(l, Text::lab1_legend_ideal), t, scaled(ps.rate_rad_s, kDegPerRad), kGrey, 2));
  p.series.push_back(
      line(say(l, Text::lab1_legend_closed_output), t, scaled(ps.output, kDegPerRad), kGreen));
  p.series.push_back(line(say(l, Text::lab1_legend_feedback_phase), scaled(run.trace.time_s, 1e6),
                          run.trace.ramp_phase_rad, kBlue, 1, true));
  p.y2_range = AxisRange{0.0, 2.0 * std::numbers::pi};
  p.key = "bottom right";
  return p;
}

// ---- text: one list of blocks, written as Markdown and as HTML -----------------------------

struct Block {
  enum class Kind { heading, paragraph, table, list };
  Kind kind = Kind::paragraph;
  std::string text;                            ///< heading, paragraph
  std::vector<std::vector<std::string>> rows;  ///< table, the first row the header
  std::vector<std::string> items;              ///< list
  std::vector<std::size_t> figures;            ///< figures shown after a heading (HTML)
};

Block heading(std::string text, std::vector<std::size_t> figures = {}) {
  Block b;
  b.kind = Block::Kind::heading;
  b.text = std::move(text);
  b.figures = std::move(figures);
  return b;
}

Block paragraph(std::string text) {
  Block b;
  b.text = std::move(text);
  return b;
}

Block sweep_table(const sim::SweepResult& s, const sim::SweepResult* analytic, Language l) {
  Block b;
  b.kind = Block::Kind::table;
  if (s.phase_form) {
    b.rows.push_back({say(l, Text::lab1_col_rate), say(l, Text::lab1_col_feedback_phase_rad),
                      say(l, Text::lab1_col_scale_factor_s)});
  } else if (s.closed_loop) {
    b.rows.push_back({say(l, Text::lab1_col_rate), say(l, Text::lab1_col_output_deg_s),
                      say(l, Text::lab1_col_scale_factor_1)});
  } else if (analytic) {
    b.rows.push_back({say(l, Text::lab1_col_rate), say(l, Text::lab1_col_s_time),
                      say(l, Text::lab1_col_s_analytic), say(l, Text::lab1_col_sf_time),
                      say(l, Text::lab1_col_sf_analytic)});
  } else {
    b.rows.push_back(
        {say(l, Text::lab1_col_rate), say(l, Text::lab1_col_s), say(l, Text::lab1_col_sf)});
  }
  for (std::size_t i = 0; i < s.rates_rad_s.size(); ++i) {
    const double rate_deg = s.rates_rad_s[i] * kDegPerRad;
    if (s.phase_form) {
      b.rows.push_back({fmt::format("{:.5g}", rate_deg), fmt::format("{:.9g}", s.outputs[i]),
                        fmt::format("{:.9g}", s.scale_factors[i])});
    } else if (s.closed_loop) {
      b.rows.push_back({fmt::format("{:.5g}", rate_deg),
                        fmt::format("{:.9g}", s.outputs[i] * kDegPerRad),
                        fmt::format("{:.9f}", s.scale_factors[i])});
    } else if (analytic) {
      b.rows.push_back({fmt::format("{:.5g}", rate_deg), fmt::format("{:.6f}", s.outputs[i]),
                        fmt::format("{:.6f}", analytic->outputs[i]),
                        fmt::format("{:.6g}", s.outputs[i] / rate_deg),
                        fmt::format("{:.6g}", analytic->outputs[i] / rate_deg)});
    } else {
      b.rows.push_back({fmt::format("{:.5g}", rate_deg), fmt::format("{:.6f}", s.outputs[i]),
                        fmt::format("{:.6g}", s.outputs[i] / rate_deg)});
    }
  }
  return b;
}

/// The closed loop's tracking at the end of the ramp against the theory of
/// a type-1 loop: lag = (rate change per period) / gain.
struct Tracking {
  double lag_deg_s = 0.0, theory_deg_s = 0.0;
};

Tracking ramp_tracking(const sim::Lab1Result& r, const sim::ClosedLoopOptions& loop) {
  const auto& c = r.closed_ramp.periods;
  Tracking t;
  if (c.rate_rad_s.size() < 3) return t;
  const std::size_t i = c.rate_rad_s.size() - 2;
  t.lag_deg_s = (c.rate_rad_s[i] - c.output[i]) * kDegPerRad;
  const double rate_step = c.rate_rad_s[i] - c.rate_rad_s[i - 1];  // per period
  t.theory_deg_s = rate_step / loop.loop_gain * kDegPerRad;
  return t;
}

std::vector<Block> blocks(const sim::Lab1Result& r, const sim::ClosedLoopOptions& loop,
                          bool phase_output, Language l) {
  const sim::CoilNumbers& n = r.numbers;
  std::vector<Block> out;
  out.push_back(heading(say(l, Text::lab1_coil)));
  Block coil;
  coil.kind = Block::Kind::table;
  coil.rows = {
      {say(l, Text::lab1_quantity), say(l, Text::value), say(l, Text::unit)},
      {say(l, Text::lab1_row_length), fmt::format("{:.6g}", r.coil.length_m),
       say(l, Text::lab1_unit_m)},
      {say(l, Text::lab1_row_radius), fmt::format("{:.6g}", r.coil.radius_m),
       say(l, Text::lab1_unit_m)},
      {say(l, Text::lab1_row_wavelength), fmt::format("{:.6g}", r.coil.wavelength_m * 1e9),
       say(l, Text::lab1_unit_nm)},
      {say(l, Text::lab1_row_group_index), fmt::format("{:.6g}", r.coil.group_index), "-"},
      {say(l, Text::lab1_row_scale_factor), fmt::format("{:.6g}", n.scale_factor_s),
       say(l, Text::lab1_unit_scale_factor)},
      {say(l, Text::lab1_row_range), fmt::format("{:.6g}", n.omega_pi2_rad_s),
       say(l, Text::unit_rad_s)},
      {say(l, Text::lab1_row_range_deg), fmt::format("{:.6g}", n.omega_pi2_deg_s),
       say(l, Text::unit_deg_s)},
      {say(l, Text::lab1_row_transit_time), fmt::format("{:.6g}", n.transit_time_s * 1e6),
       say(l, Text::lab1_unit_us)},
      {say(l, Text::lab1_row_modulation_frequency),
       fmt::format("{:.6g}", n.modulation_frequency_hz * 1e-3), say(l, Text::lab1_unit_khz)}};
  out.push_back(std::move(coil));

  out.push_back(heading(say(l, Text::lab1_open_loop), {0, 1, 2, 3, 4}));
  out.push_back(heading(say(l, Text::lab1_square_sweep)));
  out.push_back(sweep_table(r.sweep_square, &r.sweep_square_analytic, l));
  out.push_back(
      paragraph(say(l, Text::lab1_square_nonlinearity, r.sweep_square.nonlinearity_percent,
                    r.sweep_square_analytic.nonlinearity_percent)));
  if (r.range_30_rad_s) {
    out.push_back(
        paragraph(say(l, Text::lab1_range_30, *r.range_30_rad_s * kDegPerRad,
                      *r.range_30_rad_s / n.omega_pi2_rad_s,
                      r.range_30_analytic_rad_s ? *r.range_30_analytic_rad_s * kDegPerRad : NAN)));
  }
  out.push_back(heading(say(l, Text::lab1_sine_sweep)));
  out.push_back(sweep_table(r.sweep_sine, nullptr, l));
  out.push_back(paragraph(say(l, Text::lab1_sine_nonlinearity, r.sweep_sine.nonlinearity_percent)));
  out.push_back(heading(say(l, Text::lab1_closed_loop), {5, 6, 7, 8, 9}));
  const sim::SweepResult closed_phase = sim::feedback_phase_form(r.sweep_closed);
  out.push_back(sweep_table(phase_output ? closed_phase : r.sweep_closed, nullptr, l));
  out.push_back(
      paragraph(say(l, Text::lab1_closed_nonlinearity, r.sweep_closed.nonlinearity_percent * 1e4,
                    r.sweep_closed.nonlinearity_percent)));
  // The manual's form beside foglab's, with both numbers (docs/manual_notes.md).
  const double mean_phase_sf = closed_phase.scale_factors.empty()
                                   ? NAN
                                   : std::accumulate(closed_phase.scale_factors.begin(),
                                                     closed_phase.scale_factors.end(), 0.0) /
                                         static_cast<double>(closed_phase.scale_factors.size());
  out.push_back(paragraph(
      say(l, phase_output ? Text::lab1_phase_convention_shown : Text::lab1_phase_convention,
          mean_phase_sf, -n.scale_factor_s, closed_phase.nonlinearity_percent * 1e4,
          r.sweep_closed.nonlinearity_percent * 1e4)));

  const sim::Lab1OpenLoopRun& sq = r.open_loop[1];
  const sim::Lab1OpenLoopRun& si = r.open_loop[2];
  const Tracking t = ramp_tracking(r, loop);
  const double ramp_end_rad_s =
      r.closed_ramp.periods.rate_rad_s.empty() ? NAN : r.closed_ramp.periods.rate_rad_s.back();
  const double j1 = si.full_scale / sq.full_scale;
  out.push_back(heading(say(l, Text::lab1_checks), {10}));
  Block checks;
  checks.kind = Block::Kind::list;
  checks.items = {
      say(l, Text::lab1_check_square, 100.0 * sq.worst_deviation_of_full_scale),
      say(l, Text::lab1_check_sine, 100.0 * si.worst_deviation_of_full_scale, j1),
      say(l, Text::lab1_check_closed, r.sweep_closed.nonlinearity_percent * 1e4,
          ramp_end_rad_s * kDegPerRad, ramp_end_rad_s / n.omega_pi2_rad_s, t.lag_deg_s,
          t.theory_deg_s),
      say(l, Text::lab1_check_off_frequency,
          r.off_frequency.modulation_frequency_hz / n.modulation_frequency_hz,
          100.0 * r.off_frequency_spike_fraction,
          100.0 * (1.0 - 2.0 * r.off_frequency.modulation_frequency_hz * n.transit_time_s),
          r.off_frequency_signal_ratio, r.off_frequency_theory_ratio)};
  out.push_back(std::move(checks));

  out.push_back(heading(say(l, Text::lab1_conclusions)));
  Block conclusions;
  conclusions.kind = Block::Kind::list;
  conclusions.items = {
      say(l, Text::lab1_conclusion_none),
      say(l, Text::lab1_conclusion_square, n.modulation_frequency_hz * 1e-3),
      say(l, Text::lab1_conclusion_sine, j1),
      say(l, Text::lab1_conclusion_open, r.sweep_square.nonlinearity_percent,
          r.range_30_rad_s ? *r.range_30_rad_s * kDegPerRad : NAN),
      say(l, Text::lab1_conclusion_closed, r.sweep_closed.nonlinearity_percent * 1e4)};
  out.push_back(std::move(conclusions));
  return out;
}

std::string to_markdown(const std::vector<Block>& bs, std::string_view title,
                        std::string_view title_block) {
  std::string md = fmt::format("# {}\n\n{}", title, title_block);
  for (const Block& b : bs) {
    switch (b.kind) {
      case Block::Kind::heading:
        md += "## " + b.text + "\n\n";
        break;
      case Block::Kind::paragraph:
        md += b.text + "\n\n";
        break;
      case Block::Kind::table:
        for (std::size_t i = 0; i < b.rows.size(); ++i) {
          md += "|";
          for (const std::string& c : b.rows[i]) md += " " + c + " |";
          md += "\n";
          if (i == 0) {
            md += "|";
            for (std::size_t k = 0; k < b.rows[i].size(); ++k) md += "---|";
            md += "\n";
          }
        }
        md += "\n";
        break;
      case Block::Kind::list:
        for (const std::string& item : b.items) md += "- " + item + "\n";
        md += "\n";
        break;
    }
  }
  return md;
}

std::string to_html(const std::vector<Block>& bs, const std::vector<Figure>& figures, Language l) {
  std::string h;
  for (const Block& b : bs) {
    switch (b.kind) {
      case Block::Kind::heading:
        h += "<h2>" + html_escape(b.text) + "</h2>\n";
        for (const std::size_t i : b.figures) {
          h += figure_html(figures.at(i), l);
        }
        break;
      case Block::Kind::paragraph:
        h += "<p>" + html_escape(b.text) + "</p>\n";
        break;
      case Block::Kind::table:
        h += "<table>\n";
        for (std::size_t i = 0; i < b.rows.size(); ++i) {
          h += "<tr>";
          for (const std::string& c : b.rows[i]) h += i == 0 ? th(c) : td(c);
          h += "</tr>\n";
        }
        h += "</table>\n";
        break;
      case Block::Kind::list:
        h += "<ul>\n";
        for (const std::string& item : b.items) h += "<li>" + html_escape(item) + "</li>\n";
        h += "</ul>\n";
        break;
    }
  }
  return h;
}

std::string sweep_csv(const sim::Lab1Result& r) {
  std::string out =
      "# foglab lab 1 sweeps: open-loop output S [a.u.] and scale factor [a.u. per deg/s]; "
      "closed-loop output [deg/s] and scale factor [1]\n"
      "scheme,modulation,method,rate_deg_s,output,scale_factor\n";
  auto add = [&](const sim::SweepResult& s, const char* scheme, const char* modulation,
                 const char* method) {
    for (std::size_t i = 0; i < s.rates_rad_s.size(); ++i) {
      const double rate_deg = s.rates_rad_s[i] * kDegPerRad;
      const double output = s.closed_loop ? s.outputs[i] * kDegPerRad : s.outputs[i];
      out += fmt::format("{},{},{},{:.10g},{:.10g},{:.10g}\n", scheme, modulation, method, rate_deg,
                         output, output / rate_deg);
    }
  };
  add(r.sweep_square, "open-loop", "square", "time");
  add(r.sweep_square_analytic, "open-loop", "square", "analytic");
  add(r.sweep_sine, "open-loop", "sine", "time");
  add(r.sweep_closed, "closed-loop", "square", "time");
  return out;
}

}  // namespace

std::vector<Plot> lab1_plots(const sim::Lab1Result& r, Language l) {
  std::vector<Plot> plots;
  plots.push_back(intensity_plot(r, l));
  plots.push_back(output_plot(r, l));
  plots.push_back(
      trace_plot(r.open_loop[1].window, say(l, Text::lab1_plot_trace_square), kBlue, l));
  plots.push_back(
      trace_plot(r.open_loop[2].window, say(l, Text::lab1_plot_trace_sine), kOrange, l));
  plots.push_back(ramp_time_plot(r, l));
  plots.push_back(sweep_plot(r, l));
  plots.push_back(closed_ramp_plot(r, l));
  plots.push_back(closed_ramp_time_plot(r, l));
  plots.push_back(closed_trace_plot(r, 0, l));
  plots.push_back(closed_trace_plot(r, 1, l));
  plots.push_back(
      trace_plot(r.off_frequency,
                 say(l, Text::lab1_plot_off_frequency,
                     r.off_frequency.modulation_frequency_hz / r.numbers.modulation_frequency_hz),
                 kPurple, l));
  return plots;
}

Lab1Report make_lab1_report(const sim::Lab1Result& r, std::string_view title,
                            const sim::ClosedLoopOptions& loop, const ReportOptions& options) {
  const Language l = options.language;
  Lab1Report rep;
  const std::vector<Plot> plots = lab1_plots(r, l);
  static constexpr std::pair<const char*, Text> kFigures[] = {
      {"intensity", Text::lab1_fig_intensity},
      {"output", Text::lab1_fig_output},
      {"trace_square", Text::lab1_fig_trace_square},
      {"trace_sine", Text::lab1_fig_trace_sine},
      {"ramp_time", Text::lab1_fig_ramp_time},
      {"sweep", Text::lab1_fig_sweep},
      {"closed_ramp", Text::lab1_fig_closed_ramp},
      {"closed_ramp_time", Text::lab1_fig_closed_ramp_time},
      {"closed_trace_inside", Text::lab1_fig_closed_trace_inside},
      {"closed_trace_beyond", Text::lab1_fig_closed_trace_beyond},
      {"off_frequency", Text::lab1_fig_off_frequency},
  };
  std::vector<FigureSpec> specs;
  for (const auto& [name, caption] : kFigures) specs.push_back({name, say(l, caption)});
  RenderedFigures drawn = render_figures(plots, specs, options);
  rep.figures = std::move(drawn.figures);
  rep.plots_skipped = drawn.skipped;
  rep.plots_note = std::move(drawn.note);

  const std::vector<Block> text = blocks(r, loop, options.loop_output_phase, l);
  rep.markdown = to_markdown(text, title, title_block_markdown(options.title_block, l));
  if (rep.plots_skipped) rep.markdown += rep.plots_note + "\n";
  rep.sweep_csv = sweep_csv(r);
  Report page;
  page.title = std::string(title);
  page.html_section = to_html(text, rep.figures, l);
  const std::string preface =
      title_block_html(options.title_block, l) +
      (rep.plots_skipped ? "<p class=\"warn\">" + html_escape(rep.plots_note) + "</p>\n" : "");
  rep.html = html_document(std::span<const Report>(&page, 1), title, preface, l);
  return rep;
}

}  // namespace foglab::report
