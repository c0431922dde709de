// foglab — the lab-1 report (lab1.h).
#include "foglab/report/lab1.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "foglab/core/units.h"
#include "report_internal.h"

namespace foglab::report {
namespace {

using namespace detail;

constexpr const char* kColours[] = {kGrey, kBlue, kOrange};  // none, square, sine

constexpr std::size_t kMaxPlotPoints = 1500;

std::string modulation_title(sim::Modulation m) {
  switch (m) {
    case sim::Modulation::none:
      return "no modulation";
    case sim::Modulation::square:
      return "square modulation";
    case sim::Modulation::sine:
      return "sine modulation";
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

Plot intensity_plot(const sim::Lab1Result& r) {
  Plot p;
  p.title =
      "Intensity at the detector against the total phase (I vs fi), rate ramp over "
      "+-Omega_pi/2";
  p.x_label = "total phase phi_s + dphi_m [rad]";
  p.y_label = "detector output [a.u.]";
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
  Series curve = line("gamma (1 + cos phi)", x, y, kGrey, 2);
  curve.sets_range = false;
  p.series.push_back(std::move(curve));
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& tr = r.open_loop[k].ramp.trace;
    p.series.push_back(points(modulation_title(r.open_loop[k].modulation), thin(tr.total_phase_rad),
                              thin(tr.detector), kColours[k], k == 0 ? 0.5 : 0.3));
  }
  p.key = "bottom center";
  return p;
}

Plot output_plot(const sim::Lab1Result& r) {
  Plot p;
  p.title = "Demodulated output against rate (S vs Om), open loop";
  p.x_label = "input rate [deg/s]";
  p.y_label = "output [a.u.] (no modulation: the detector's mean)";
  for (std::size_t k = 0; k < 3; ++k) {
    const sim::Lab1OpenLoopRun& run = r.open_loop[k];
    const auto& ps = run.ramp.periods;
    p.series.push_back(line(modulation_title(run.modulation) + ", time simulation",
                            thin(ps.rate_rad_s, kDegPerRad), thin(ps.demodulated), kColours[k]));
    sim::OpticsOptions o;
    o.modulation = run.modulation;
    std::vector<double> x, y;
    for (int i = 0; i <= 100; ++i) {
      const double rate = r.numbers.omega_pi2_rad_s * (-1.0 + 2.0 * i / 100.0);
      x.push_back(rate * kDegPerRad);
      y.push_back(sim::steady_state_output(r.coil, rate, o));
    }
    Series a = line(k == 2 ? "analytic steady state" : "", x, y, kRed, 2);
    a.line_width = 1.0;
    p.series.push_back(std::move(a));
  }
  p.key = "bottom right";
  return p;
}

Plot trace_plot(const sim::OpticsResult& run, const std::string& title, const char* color) {
  Plot p;
  p.title = title;
  p.x_label = "time [us]";
  p.y_label = "detector output [a.u.]";
  p.y2_label = "phase difference dphi_m [rad]";
  const auto& tr = run.trace;
  const std::vector<double> t_us = scaled(tr.time_s, 1e6);
  Series det = line("detector", t_us, tr.detector, color);
  det.style = SeriesStyle::linespoints;
  det.point_size = 0.4;
  p.series.push_back(std::move(det));
  p.series.push_back(
      line("modulation phase difference (right axis)", t_us, tr.modulation_rad, kGreen, 2, true));
  p.key = "bottom right";
  return p;
}

Plot ramp_time_plot(const sim::Lab1Result& r) {
  Plot p;
  p.title = "Open loop over the rate ramp: output and rate against time";
  p.x_label = "time [ms]";
  p.y_label = "demodulated output, low-passed [a.u.]";
  p.y2_label = "input rate [deg/s]";
  for (std::size_t k = 1; k < 3; ++k) {
    const auto& ps = r.open_loop[k].ramp.periods;
    p.series.push_back(line(modulation_title(r.open_loop[k].modulation), thin(ps.time_s, 1e3),
                            thin(ps.output), kColours[k]));
  }
  const auto& ps = r.open_loop[1].ramp.periods;
  p.series.push_back(line("input rate (right axis)", thin(ps.time_s, 1e3),
                          thin(ps.rate_rad_s, kDegPerRad), kGreen, 2, true));
  p.key = "top left";
  return p;
}

Plot sweep_plot(const sim::Lab1Result& r) {
  Plot p;
  p.title = "The lab's sweep: scale factor against rate";
  p.x_label = "input rate [deg/s]";
  p.y_label = "open-loop scale factor S/Omega [a.u. per deg/s]";
  p.y2_label = "closed-loop scale factor [1]";
  auto add = [&](const sim::SweepResult& s, const std::string& title, const char* color,
                 SeriesStyle style, bool y2, double unit) {
    Series series = line(title, scaled(s.rates_rad_s, kDegPerRad), scaled(s.scale_factors, unit),
                         color, style == SeriesStyle::lines ? 2 : 1, y2);
    series.style = style;
    series.point_size = 0.9;
    p.series.push_back(std::move(series));
  };
  // Open-loop S per rad/s -> per deg/s: divide by kDegPerRad.
  add(r.sweep_square_analytic, "square, analytic", kRed, SeriesStyle::lines, false,
      1.0 / kDegPerRad);
  add(r.sweep_square, "square, time simulation", kBlue, SeriesStyle::points, false,
      1.0 / kDegPerRad);
  add(r.sweep_sine, "sine, time simulation", kOrange, SeriesStyle::points, false, 1.0 / kDegPerRad);
  add(r.sweep_closed, "closed loop (right axis)", kGreen, SeriesStyle::linespoints, true, 1.0);
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

Plot closed_ramp_plot(const sim::Lab1Result& r) {
  Plot p;
  p.title = "Rate ramp beyond Omega_pi/2: closed loop against open loop";
  p.x_label = "input rate [deg/s]";
  p.y_label = "closed-loop output [deg/s]";
  p.y2_label = "open-loop output S [a.u.]";
  const auto& c = r.closed_ramp.periods;
  const auto& o = r.open_ramp.periods;
  const std::vector<double> x = thin(c.rate_rad_s, kDegPerRad);
  Series ideal = line("output = input", x, x, kGrey, 2);
  ideal.line_width = 1.0;
  p.series.push_back(std::move(ideal));
  p.series.push_back(line("closed loop", x, thin(c.output, kDegPerRad), kGreen));
  p.series.push_back(line("open loop, square (right axis)", thin(o.rate_rad_s, kDegPerRad),
                          thin(o.demodulated), kBlue, 1, true));
  const double w = r.numbers.omega_pi2_deg_s;
  const double top = x.empty() ? w : x.back();
  Series edge = line("+Omega_pi/2", {w, w}, {0.0, top}, kRed, 3);
  edge.sets_range = false;
  p.series.push_back(std::move(edge));
  // Room above the curves for the legend.
  p.y_range = AxisRange{0.0, 1.45 * top};
  p.y2_range = AxisRange{-1.1, 2.3};
  p.key = "top left";
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

Block sweep_table(const sim::SweepResult& s, const sim::SweepResult* analytic) {
  Block b;
  b.kind = Block::Kind::table;
  if (s.closed_loop) {
    b.rows.push_back({"rate [deg/s]", "output [deg/s]", "scale factor [1]"});
  } else if (analytic) {
    b.rows.push_back({"rate [deg/s]", "S, time [a.u.]", "S, analytic [a.u.]",
                      "SF, time [a.u. per deg/s]", "SF, analytic [a.u. per deg/s]"});
  } else {
    b.rows.push_back({"rate [deg/s]", "S [a.u.]", "SF [a.u. per deg/s]"});
  }
  for (std::size_t i = 0; i < s.rates_rad_s.size(); ++i) {
    const double rate_deg = s.rates_rad_s[i] * kDegPerRad;
    if (s.closed_loop) {
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

std::vector<Block> blocks(const sim::Lab1Result& r, const sim::ClosedLoopOptions& loop) {
  const sim::CoilNumbers& n = r.numbers;
  std::vector<Block> out;
  out.push_back(heading("The coil (item 1.1)"));
  Block coil;
  coil.kind = Block::Kind::table;
  coil.rows = {
      {"quantity", "value", "unit"},
      {"fibre length L", fmt::format("{:.6g}", r.coil.length_m), "m"},
      {"coil radius R", fmt::format("{:.6g}", r.coil.radius_m), "m"},
      {"wavelength lambda", fmt::format("{:.6g}", r.coil.wavelength_m * 1e9), "nm"},
      {"group index n_g", fmt::format("{:.6g}", r.coil.group_index), "-"},
      {"Sagnac scale factor K_s = 4 pi R L / (lambda c)", fmt::format("{:.6g}", n.scale_factor_s),
       "s (rad per rad/s)"},
      {"range Omega_pi/2 = (pi/2) / K_s", fmt::format("{:.6g}", n.omega_pi2_rad_s), "rad/s"},
      {"range Omega_pi/2", fmt::format("{:.6g}", n.omega_pi2_deg_s), "deg/s"},
      {"transit time tau0 = n_g L / c", fmt::format("{:.6g}", n.transit_time_s * 1e6), "us"},
      {"modulation frequency f_m = 1/(2 tau0)",
       fmt::format("{:.6g}", n.modulation_frequency_hz * 1e-3), "kHz"}};
  out.push_back(std::move(coil));

  out.push_back(
      heading("Open loop: no, square and sine modulation (items 2.4-2.10)", {0, 1, 2, 3, 4}));
  out.push_back(heading("Open loop, square modulation: the ten-rate sweep (items 3.1-3.6)"));
  out.push_back(sweep_table(r.sweep_square, &r.sweep_square_analytic));
  out.push_back(paragraph(fmt::format(
      "Nonlinearity over +-Omega_pi/2: {:.3f} % (time simulation), {:.3f} % (analytic, "
      "(sinc(pi/10) - sinc(pi/2)) / mean).",
      r.sweep_square.nonlinearity_percent, r.sweep_square_analytic.nonlinearity_percent)));
  if (r.range_30_rad_s) {
    out.push_back(paragraph(fmt::format(
        "Range with 30 % nonlinearity (bisection to 0.1 %): +-{:.5g} deg/s = {:.4f} Omega_pi/2 "
        "(time simulation); analytic +-{:.5g} deg/s.",
        *r.range_30_rad_s * kDegPerRad, *r.range_30_rad_s / n.omega_pi2_rad_s,
        r.range_30_analytic_rad_s ? *r.range_30_analytic_rad_s * kDegPerRad : NAN)));
  }
  out.push_back(heading("Open loop, sine modulation (phi_m = 1.8 rad): the sweep"));
  out.push_back(sweep_table(r.sweep_sine, nullptr));
  out.push_back(paragraph(
      fmt::format("Nonlinearity over +-Omega_pi/2: {:.3f} %.", r.sweep_sine.nonlinearity_percent)));
  out.push_back(
      heading("Closed loop: the ramp and the ten-rate sweep (items 4.2, 5.1-5.4)", {5, 6}));
  out.push_back(sweep_table(r.sweep_closed, nullptr));
  out.push_back(paragraph(fmt::format("Nonlinearity over +-Omega_pi/2: {:.3g} ppm ({:.3g} %).",
                                      r.sweep_closed.nonlinearity_percent * 1e4,
                                      r.sweep_closed.nonlinearity_percent)));

  const sim::Lab1OpenLoopRun& sq = r.open_loop[1];
  const sim::Lab1OpenLoopRun& si = r.open_loop[2];
  const Tracking t = ramp_tracking(r, loop);
  const double ramp_end_rad_s =
      r.closed_ramp.periods.rate_rad_s.empty() ? NAN : r.closed_ramp.periods.rate_rad_s.back();
  const double j1 = si.full_scale / sq.full_scale;
  out.push_back(heading("Checks against theory", {7}));
  Block checks;
  checks.kind = Block::Kind::list;
  checks.items = {
      fmt::format("Square modulation: the time simulation follows S = 2 gamma sin(phi_s) within "
                  "{:.2g} % of full scale at the sweep rates (goal 0.1 %).",
                  100.0 * sq.worst_deviation_of_full_scale),
      fmt::format("Sine modulation: it follows S = 2 gamma J1(phi_m) sin(phi_s) within {:.2g} % of "
                  "full scale; J1(1.8) = {:.4f}.",
                  100.0 * si.worst_deviation_of_full_scale, j1),
      fmt::format("Closed loop: {:.3g} ppm nonlinearity over +-Omega_pi/2; under the ramp to "
                  "{:.4g} deg/s ({:.3g} Omega_pi/2) the output stays on the input with a lag of "
                  "{:.3g} deg/s at the end (a type-1 loop's ramp lag, theory {:.3g} deg/s), where "
                  "the open loop has folded.",
                  r.sweep_closed.nonlinearity_percent * 1e4, ramp_end_rad_s * kDegPerRad,
                  ramp_end_rad_s / n.omega_pi2_rad_s, t.lag_deg_s, t.theory_deg_s),
      fmt::format("Square modulation at {:.3g} f_m: the phase difference is 0 in {:.1f} % of the "
                  "samples (the transition spikes; theory {:.1f} %) and the signal falls to "
                  "{:.4f} of the proper one (theory, with the gate: {:.4f}).",
                  r.off_frequency.modulation_frequency_hz / n.modulation_frequency_hz,
                  100.0 * r.off_frequency_spike_fraction,
                  100.0 * (1.0 - 2.0 * r.off_frequency.modulation_frequency_hz * n.transit_time_s),
                  r.off_frequency_signal_ratio, r.off_frequency_theory_ratio)};
  out.push_back(std::move(checks));

  out.push_back(heading("Conclusions"));
  Block conclusions;
  conclusions.kind = Block::Kind::list;
  conclusions.items = {
      "Without modulation the detector gives gamma (1 + cos phi_s): flat at zero rate (no "
      "sensitivity to small rates) and blind to the sign of the rate.",
      fmt::format("Square modulation at f_m = {:.4g} kHz biases the interferometer to +-pi/2: the "
                  "demodulated output 2 gamma sin(phi_s) is the steepest and odd in the rate; it "
                  "needs exactly the proper frequency (off it: spikes and a loss of signal).",
                  n.modulation_frequency_hz * 1e-3),
      fmt::format("Sine modulation gives J1(phi_m) = {:.3f} of that at phi_m = 1.8 rad, with the "
                  "same sine-shaped nonlinearity, and degrades gracefully off frequency.",
                  j1),
      fmt::format("Both open-loop outputs are sinusoidal in the rate: {:.1f} % nonlinearity over "
                  "+-Omega_pi/2, 30 % reached at +-{:.4g} deg/s, and past Omega_pi/2 the output "
                  "folds back, so the rate becomes ambiguous.",
                  r.sweep_square.nonlinearity_percent,
                  r.range_30_rad_s ? *r.range_30_rad_s * kDegPerRad : NAN),
      fmt::format("The closed loop holds the interferometer at zero phase with the phase ramp and "
                  "reads the rate from the feedback: linear ({:.2g} ppm) and not limited to "
                  "Omega_pi/2.",
                  r.sweep_closed.nonlinearity_percent * 1e4)};
  out.push_back(std::move(conclusions));
  return out;
}

std::string to_markdown(const std::vector<Block>& bs, std::string_view title) {
  std::string md = fmt::format("# {}\n\n", title);
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

std::string to_html(const std::vector<Block>& bs, const std::vector<Figure>& figures) {
  std::string h;
  for (const Block& b : bs) {
    switch (b.kind) {
      case Block::Kind::heading:
        h += "<h2>" + html_escape(b.text) + "</h2>\n";
        for (const std::size_t i : b.figures) {
          h += figure_html(figures.at(i));
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

std::vector<Plot> lab1_plots(const sim::Lab1Result& r) {
  std::vector<Plot> plots;
  plots.push_back(intensity_plot(r));
  plots.push_back(output_plot(r));
  plots.push_back(trace_plot(r.open_loop[1].window,
                             "Square modulation at a constant rate: detector and phase difference",
                             kBlue));
  plots.push_back(trace_plot(r.open_loop[2].window,
                             "Sine modulation at a constant rate: detector and phase difference",
                             kOrange));
  plots.push_back(ramp_time_plot(r));
  plots.push_back(sweep_plot(r));
  plots.push_back(closed_ramp_plot(r));
  plots.push_back(trace_plot(
      r.off_frequency,
      fmt::format("Square modulation at {:.3g} f_m: transition spikes",
                  r.off_frequency.modulation_frequency_hz / r.numbers.modulation_frequency_hz),
      kPurple));
  return plots;
}

Lab1Report make_lab1_report(const sim::Lab1Result& r, std::string_view title,
                            const sim::ClosedLoopOptions& loop, const ReportOptions& options) {
  Lab1Report rep;
  const std::vector<Plot> plots = lab1_plots(r);
  static const char* const kNames[][2] = {
      {"intensity", "Intensity at the detector against the total phase (items 2.5, 2.7, 2.9)."},
      {"output", "Demodulated output against the input rate, each modulation (items 2.7, 2.9)."},
      {"trace_square", "Time traces, square modulation at 0.5 Omega_pi/2."},
      {"trace_sine", "Time traces, sine modulation at 0.5 Omega_pi/2."},
      {"ramp_time", "The open loop over the rate ramp against time."},
      {"sweep", "Scale factors of the ten-rate sweeps (items 3.4, 5.3)."},
      {"closed_ramp",
       "The closed loop follows a ramp well beyond Omega_pi/2; the open loop "
       "folds (item 4.2)."},
      {"off_frequency", "Square modulation away from the proper frequency."},
  };
  std::vector<FigureSpec> specs;
  for (const auto& [name, caption] : kNames) specs.push_back({name, caption});
  RenderedFigures drawn = render_figures(plots, specs, options);
  rep.figures = std::move(drawn.figures);
  rep.plots_skipped = drawn.skipped;
  rep.plots_note = std::move(drawn.note);

  const std::vector<Block> text = blocks(r, loop);
  rep.markdown = to_markdown(text, title);
  if (rep.plots_skipped) rep.markdown += rep.plots_note + "\n";
  rep.sweep_csv = sweep_csv(r);
  Report page;
  page.title = std::string(title);
  page.html_section = to_html(text, rep.figures);
  const std::string preface =
      rep.plots_skipped ? "<p class=\"warn\">" + html_escape(rep.plots_note) + "</p>\n" : "";
  rep.html = html_document(std::span<const Report>(&page, 1), title, preface);
  return rep;
}

}  // namespace foglab::report
