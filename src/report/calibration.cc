#include "foglab/report/calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "foglab/core/version.h"
#include "foglab/core/language.h"
#include "report_internal.h"

namespace foglab::report {

using namespace detail;

namespace {

constexpr const char* kPalette[] = {kBlue, kOrange, kGreen, kRed, kPurple, kLightBlue, kYellow};
constexpr double kSameTemperatureC = 0.5;  // as model/calibration.cc groups the plateaus
constexpr const auto& kAxis = model::kTriadAxes;

// " +c1 X +c2 X^2 ..." of a power series with coefficients c_1, c_2, ...
std::string series_text(const std::vector<model::CalibratedValue>& coefs, std::string_view x) {
  std::string out;
  for (std::size_t k = 0; k < coefs.size(); ++k) {
    out += fmt::format(" {:+.7g} {}{}", coefs[k].value, x, k == 0 ? "" : fmt::format("^{}", k + 1));
  }
  return out;
}

// The plateaus at each of the run's distinct temperatures.
std::vector<std::vector<const model::CalibrationPlateau*>> by_temperature(
    const model::Calibration& c) {
  std::vector<std::vector<const model::CalibrationPlateau*>> groups(c.temperatures_c.size());
  for (const auto& p : c.plateaus) {
    for (std::size_t k = 0; k < c.temperatures_c.size(); ++k) {
      if (std::abs(p.temperature_c - c.temperatures_c[k]) <= kSameTemperatureC) {
        groups[k].push_back(&p);
        break;
      }
    }
  }
  return groups;
}

// The output at rest at one temperature: the zero-rate plateaus' mean, else the fitted bias.
double output_at_rest(const model::Calibration& c,
                      const std::vector<const model::CalibrationPlateau*>& group, double t) {
  double sum = 0.0, samples = 0.0;
  for (const auto* p : group) {
    if (p->rate_deg_s != 0.0) continue;
    sum += p->output_mean_lsb * static_cast<double>(p->samples);
    samples += static_cast<double>(p->samples);
  }
  return samples > 0.0 ? sum / samples : model::calibrated_output_lsb(c, 0.0, t);
}

// Significant digits enough to show a value's interval's width (at least 4).
int digits(const model::CalibratedValue& v, double scale) {
  const double width = std::abs(v.ci95_high - v.ci95_low) * scale;
  const double size = std::abs(v.value * scale);
  return width > 0.0 && size > 0.0
             ? std::clamp(static_cast<int>(std::ceil(std::log10(size / width))) + 2, 4, 12)
             : 7;
}

// One row of the coefficient table: name, value, 95 % interval, unit.
struct Row {
  std::string name, value, interval, unit;
};

std::vector<Row> coefficient_rows(const model::Calibration& c, Language l) {
  const auto row = [](std::string name, const model::CalibratedValue& v, double scale,
                      std::string unit) {
    const int n = digits(v, scale);
    return Row{std::move(name), fmt::format("{:.{}g}", v.value * scale, n),
               fmt::format("[{:.{}g}, {:.{}g}]", v.ci95_low * scale, n, v.ci95_high * scale, n),
               std::move(unit)};
  };
  std::vector<Row> rows;
  rows.push_back(
      row(say(l, Text::cal_row_s), c.scale_factor, 1.0, say(l, Text::unit_lsb_per_deg_s)));
  for (std::size_t k = 0; k < c.scale_factor_temp.size(); ++k) {
    rows.push_back(row(say(l, Text::cal_row_sk, k + 1), c.scale_factor_temp[k], 1e6,
                       say(l, Text::unit_ppm_per_degc_k, k + 1)));
  }
  for (std::size_t k = 0; k < c.nonlinearity.size(); ++k) {
    rows.push_back(row(say(l, Text::cal_row_ak, k + 1), c.nonlinearity[k],
                       std::pow(c.full_scale_deg_s, static_cast<double>(k + 1)) * 1e6,
                       say(l, Text::unit_ppm_fs)));
  }
  if (std::isfinite(c.asymmetry.value)) {
    rows.push_back(row(say(l, Text::cal_row_a), c.asymmetry, 1e6, say(l, Text::unit_ppm)));
  }
  rows.push_back(row(say(l, Text::cal_row_u0), c.bias, 1.0, say(l, Text::unit_lsb)));
  rows.push_back(row(say(l, Text::cal_row_u0_rate), c.bias_deg_h, 1.0, say(l, Text::unit_deg_h)));
  for (std::size_t k = 0; k < c.bias_temp.size(); ++k) {
    rows.push_back(row(say(l, Text::cal_row_bk, k + 1), c.bias_temp[k], 1.0,
                       say(l, Text::unit_lsb_per_degc_k, k + 1)));
  }
  return rows;
}

// The sentences both forms of the report say, in order.
struct Sentences {
  std::string run, nonlinearity, noise, weighting;
};

Sentences sentences(const model::Calibration& c, Language l) {
  Sentences t;
  t.run = say(l, Text::cal_run, c.plateaus.size(), c.temperatures_c.size(), g(c.full_scale_deg_s),
              g(c.reference_c));
  t.nonlinearity = say(l, Text::cal_nonlinearity, g(c.nonlinearity_ieee_ppm_fs),
                       g(c.nonlinearity_lab1_percent), c.nonlinearity_degree);
  t.noise = say(l, Text::cal_noise, g(c.white_noise_deg_h_rt_hz),
                g(c.white_noise_deg_h_rt_hz / 60.0), g(c.residual_rms_lsb), c.dof);
  t.weighting = c.noise_covariance
                    ? say(l, Text::cal_weighting_noise, g(c.noise.N), g(c.noise.B), g(c.noise.K),
                          g(c.noise.gm_sigma), g(c.noise.gm_tc), g(c.dispersion))
                    : say(l, Text::cal_weighting_alike);
  return t;
}

constexpr Text kBudgetColumns[] = {Text::cal_budget_bias, Text::cal_budget_scale_factor,
                                   Text::cal_budget_nonlinearity, Text::cal_budget_noise};

std::vector<std::string> budget_cells(const model::Calibration& c) {
  return {g(c.budget.bias_deg_h), g(c.budget.scale_factor_deg_h), g(c.budget.nonlinearity_deg_h),
          g(c.budget.noise_1s_deg_h)};
}

// The numbers of one gyro's calibration as Markdown (its heading at `level`).
std::string calibration_markdown(const model::Calibration& c, std::string_view title,
                                 const std::string& level, Language l) {
  const Sentences t = sentences(c, l);
  std::string m = fmt::format("{} {}\n\n{}\n\n", level, title, t.run);
  m += fmt::format("| {} | {} | {} | {} |\n|---|---|---|---|\n", say(l, Text::cal_coefficient),
                   say(l, Text::value), say(l, Text::interval95), say(l, Text::unit));
  for (const Row& r : coefficient_rows(c, l)) {
    m += fmt::format("| {} | {} | {} | {} |\n", r.name, r.value, r.interval, r.unit);
  }
  m += "\n" + t.nonlinearity + "\n\n" + t.noise + "\n\n" + t.weighting + "\n\n";
  m += say(l, Text::cal_budget) + "\n\n|";
  for (const Text column : kBudgetColumns) m += " " + say(l, column) + " |";
  m += "\n|---|---|---|---|\n|";
  for (const std::string& cell : budget_cells(c)) m += " " + cell + " |";
  m += "\n\n" + say(l, Text::cal_corrected_rate) + " `" + corrected_rate_equation(c, l) + "`\n";
  for (const Message& note : c.notes) m += "\n" + say(l, Text::note, note.text(l)) + "\n";
  return m;
}

// One gyro's HTML section: the figures, the tables, the plateaus.
std::string calibration_html(const model::Calibration& c, std::string_view title,
                             std::span<const Figure> figures, Language l) {
  const Sentences t = sentences(c, l);
  std::string h = "<section>\n<h2>" + html_escape(title) + "</h2>\n";
  h += "<p>" + html_escape(t.run) + "</p>\n";
  h += "<table>\n<tr>" + th(say(l, Text::cal_coefficient)) + th(say(l, Text::value)) +
       th(say(l, Text::interval95)) + th(say(l, Text::unit)) + "</tr>\n";
  for (const Row& r : coefficient_rows(c, l)) {
    h += "<tr>" + td(r.name) + td(r.value) + td(r.interval) + td(r.unit) + "</tr>\n";
  }
  h += "</table>\n";
  for (const Figure& f : figures) h += figure_html(f, l);
  for (const std::string* paragraph : {&t.nonlinearity, &t.noise, &t.weighting}) {
    h += "<p>" + html_escape(*paragraph) + "</p>\n";
  }
  h += "<p>" + html_escape(say(l, Text::cal_budget)) + "</p>\n<table>\n<tr>";
  for (const Text column : kBudgetColumns) h += th(say(l, column));
  h += "</tr>\n<tr>";
  for (const std::string& cell : budget_cells(c)) h += td(cell);
  h += "</tr>\n</table>\n";
  h += "<p>" + html_escape(say(l, Text::cal_corrected_rate)) + " <code>" +
       html_escape(corrected_rate_equation(c, l)) + "</code></p>\n";
  for (const Message& note : c.notes) {
    h += "<p class=\"warn\">" + html_escape(say(l, Text::note, note.text(l))) + "</p>\n";
  }
  h += "<details><summary>" + html_escape(say(l, Text::cal_plateaus)) + "</summary>\n<table>\n<tr>";
  for (const Text column : {Text::cal_col_rate, Text::cal_col_samples, Text::cal_col_mean,
                            Text::cal_col_sd, Text::cal_col_temperature, Text::cal_col_residual}) {
    h += th(say(l, column));
  }
  h += "</tr>\n";
  for (const auto& p : c.plateaus) {
    h += "<tr>" + td(g(p.rate_deg_s)) + td(std::to_string(p.samples)) +
         td(fmt::format("{:.10g}", p.output_mean_lsb)) + td(g(p.output_sd_lsb)) +
         td(g(p.temperature_c)) + td(g(p.residual_lsb)) + "</tr>\n";
  }
  h += "</table>\n</details>\n</section>\n";
  return h;
}

std::vector<FigureSpec> figure_specs(Language l) {
  return {{"output", say(l, Text::cal_fig_output)},
          {"scale_factor", say(l, Text::cal_fig_scale_factor)},
          {"residual_rate", say(l, Text::cal_fig_residual_rate)},
          {"residual_temperature", say(l, Text::cal_fig_residual_temperature)}};
}

CalibrationReport assemble(std::vector<Figure> figures, std::string html, std::string markdown,
                           const RenderedFigures& drawn) {
  CalibrationReport rep;
  rep.figures = std::move(figures);
  rep.html = std::move(html);
  rep.markdown = std::move(markdown);
  rep.plots_skipped = drawn.skipped;
  rep.plots_note = drawn.note;
  if (rep.plots_skipped) rep.markdown += "\n" + rep.plots_note + "\n";
  return rep;
}

Plot plot_of(std::string title, std::string x_label, std::string y_label) {
  Plot p;
  p.title = std::move(title);
  p.x_label = std::move(x_label);
  p.y_label = std::move(y_label);
  p.key = "top left";
  return p;
}

Series series_of(std::string title, SeriesStyle style, std::string color) {
  Series s;
  s.title = std::move(title);
  s.style = style;
  s.color = std::move(color);
  return s;
}

}  // namespace

std::string interval_text(const model::CalibratedValue& v, double scale) {
  const int n = digits(v, scale);
  return fmt::format("{:.{}g} [{:.{}g}, {:.{}g}]", v.value * scale, n, v.ci95_low * scale, n,
                     v.ci95_high * scale, n);
}

std::string corrected_rate_equation(const model::Calibration& r, Language l) {
  const std::string w(text(l, Text::symbol_rate)), dt(text(l, Text::symbol_dt));
  std::string f = series_text(r.nonlinearity, w);
  if (std::isfinite(r.asymmetry.value)) {
    f += fmt::format(" {:+.7g} sign({})", 0.5 * r.asymmetry.value, w);
  }
  return say(l, Text::cal_equation, r.bias.value, series_text(r.bias_temp, dt),
             r.scale_factor.value, series_text(r.scale_factor_temp, dt), f, r.reference_c);
}

std::vector<Plot> calibration_plots(const model::Calibration& c, Language l) {
  const auto groups = by_temperature(c);
  Plot output = plot_of(say(l, Text::cal_plot_output), say(l, Text::cal_axis_rate),
                        say(l, Text::cal_axis_output));
  Plot scale = plot_of(say(l, Text::cal_plot_scale_factor), say(l, Text::cal_axis_rate),
                       say(l, Text::cal_axis_scale_factor));
  Plot residual_rate = plot_of(say(l, Text::cal_plot_residual_rate), say(l, Text::cal_axis_rate),
                               say(l, Text::cal_axis_residual));
  Plot residual_temperature =
      plot_of(say(l, Text::cal_plot_residual_temperature), say(l, Text::cal_axis_temperature),
              say(l, Text::cal_axis_residual));
  constexpr int kCurvePoints = 201;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const double t = c.temperatures_c[k];
    const std::string color = kPalette[k % std::size(kPalette)];
    Series points = series_of(say(l, Text::cal_legend_temperature, t), SeriesStyle::points, color);
    Series factors = points, residuals = points;
    const double rest = output_at_rest(c, groups[k], t);
    for (const auto* p : groups[k]) {
      points.x.push_back(p->rate_deg_s);
      points.y.push_back(p->output_mean_lsb);
      residuals.x.push_back(p->rate_deg_s);
      residuals.y.push_back(p->residual_lsb);
      if (p->rate_deg_s != 0.0) {
        factors.x.push_back(p->rate_deg_s);
        factors.y.push_back((p->output_mean_lsb - rest) / p->rate_deg_s);
      }
    }
    Series curve = series_of("", SeriesStyle::lines, color);
    Series factor_curve = curve;
    const double bias = model::calibrated_output_lsb(c, 0.0, t);
    for (int j = 0; j < kCurvePoints; ++j) {
      const double w = c.full_scale_deg_s * (2.0 * j / (kCurvePoints - 1) - 1.0);
      const double u = model::calibrated_output_lsb(c, w, t);
      curve.x.push_back(w);
      curve.y.push_back(u);
      if (w != 0.0) {
        factor_curve.x.push_back(w);
        factor_curve.y.push_back((u - bias) / w);
      }
    }
    output.series.push_back(std::move(points));
    output.series.push_back(std::move(curve));
    scale.series.push_back(std::move(factors));
    scale.series.push_back(std::move(factor_curve));
    residual_rate.series.push_back(std::move(residuals));
  }
  Series all = series_of(say(l, Text::cal_legend_plateaus), SeriesStyle::points, kBlue);
  for (const auto& p : c.plateaus) {
    all.x.push_back(p.temperature_c);
    all.y.push_back(p.residual_lsb);
  }
  residual_temperature.series.push_back(std::move(all));
  return {output, scale, residual_rate, residual_temperature};
}

CalibrationReport make_calibration_report(const model::Calibration& c, std::string_view title,
                                          const ReportOptions& options) {
  const Language l = options.language;
  const RenderedFigures drawn = render_figures(calibration_plots(c, l), figure_specs(l), options);
  std::string preface;
  if (drawn.skipped) preface = "<p class=\"warn\">" + html_escape(drawn.note) + "</p>\n";
  Report page;
  page.title = std::string(title);
  page.html_section =
      preface +
      calibration_html(c, say(l, Text::cal_section),
                       drawn.skipped ? std::span<const Figure>{} : std::span(drawn.figures), l);
  const std::string heading = say(l, Text::cal_title, title);
  return assemble(drawn.figures, html_document(std::span<const Report>(&page, 1), heading, {}, l),
                  calibration_markdown(c, heading, "#", l), drawn);
}

CalibrationReport make_triad_report(const model::TriadCalibration& t, std::string_view title,
                                    const std::vector<std::string>& titles,
                                    const ReportOptions& options) {
  const Language l = options.language;
  std::vector<Plot> plots;
  std::vector<FigureSpec> specs;
  for (int i = 0; i < 3; ++i) {
    for (Plot& p : calibration_plots(t.axes[i], l)) {
      p.title = say(l, Text::cal_gyro_plot, kAxis[i], p.title);
      plots.push_back(std::move(p));
    }
    for (FigureSpec s : figure_specs(l)) {
      s.name = fmt::format("{}_{}", kAxis[i], s.name);
      s.caption = say(l, Text::cal_gyro_figure, kAxis[i], s.caption);
      specs.push_back(std::move(s));
    }
  }
  const RenderedFigures drawn = render_figures(plots, specs, options);
  // The misalignment matrix first: what a triad's calibration adds.
  const std::string heading = say(l, Text::cal_triad_title, title);
  std::string preface = "<h2>" + html_escape(say(l, Text::cal_misalignment)) + "</h2>\n<p>" +
                        html_escape(say(l, Text::cal_misalignment_text)) + "</p>\n<table>\n<tr>" +
                        th(say(l, Text::cal_gyro)) + th("x") + th("y") + th("z") + "</tr>\n";
  std::string markdown = fmt::format(
      "# {}\n\n## {}\n\n{}\n\n| {} | x | y | z |\n|---|---|---|---|\n", heading,
      say(l, Text::cal_misalignment), say(l, Text::cal_misalignment_text), say(l, Text::cal_gyro));
  for (int i = 0; i < 3; ++i) {
    preface += "<tr>" + th(kAxis[i]);
    markdown += fmt::format("| {} |", kAxis[i]);
    for (int j = 0; j < 3; ++j) {
      const std::string cell =
          i == j ? say(l, Text::cal_own_axis) : interval_text(t.misalignment_rad[i][j], 1e3);
      preface += td(cell);
      markdown += " " + cell + " |";
    }
    preface += "</tr>\n";
    markdown += "\n";
  }
  preface += "</table>\n";
  if (drawn.skipped) preface += "<p class=\"warn\">" + html_escape(drawn.note) + "</p>\n";
  std::vector<Report> pages(3);
  for (int i = 0; i < 3; ++i) {
    const std::string name = say(l, Text::cal_gyro_section, kAxis[i], titles.at(i));
    pages[i].title = name;
    const std::span<const Figure> figures =
        drawn.skipped ? std::span<const Figure>{} : std::span(drawn.figures).subspan(4 * i, 4);
    pages[i].html_section = calibration_html(t.axes[i], name, figures, l);
    markdown += "\n" + calibration_markdown(t.axes[i], name, "##", l);
  }
  return assemble(drawn.figures, html_document(pages, heading, preface, l), markdown, drawn);
}

}  // namespace foglab::report
