// foglab — the report of a fleet (fleet.h).
#include "foglab/report/fleet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "foglab/core/csv.h"
#include "foglab/core/numeric.h"
#include "foglab/core/version.h"
#include "report_internal.h"

namespace foglab::report {

using namespace detail;

namespace {

/// The value the fleet statistics take: the estimate of a resolved term.
double resolved(const FleetTerm& t) { return t.status == "resolved" ? t.value : kNaN; }

/// "0.0512 [0.0498, 0.0527]", "< 0.0012" or "-".
std::string term_text(const FleetTerm& t) {
  if (!std::isfinite(t.value)) return "-";
  if (t.status != "resolved") return "< " + g(t.value);
  if (std::isfinite(t.ci95_low) && std::isfinite(t.ci95_high)) {
    return fmt::format("{} [{}, {}]", g(t.value), g(t.ci95_low), g(t.ci95_high));
  }
  return g(t.value);
}

/// The parameters each unit stands out on ("N+, B-"), by unit name.
std::map<std::string, std::string> outliers_by_unit(const FleetReport& fleet) {
  std::map<std::string, std::string> out;
  for (const model::FleetOutlier& o : fleet.summary.outliers) {
    std::string& text = out[o.unit];
    if (!text.empty()) text += " ";
    text += o.parameter + (o.modified_z > 0 ? "+" : "-");
  }
  return out;
}

const char* unit_of(const std::string& parameter) {
  for (const FleetParameter& p : kFleetParameters) {
    if (parameter == p.name) return p.unit;
  }
  return "";
}

/// The classes in Table 1's order, then any other, with their counts.
std::vector<std::pair<std::string, std::size_t>> class_counts(const FleetReport& fleet) {
  std::vector<std::pair<std::string, std::size_t>> out;
  for (const AccuracyClass c :
       {AccuracyClass::strategic, AccuracyClass::navigation, AccuracyClass::intermediate,
        AccuracyClass::tactical, AccuracyClass::consumer}) {
    const std::string name(to_string(c));
    const auto found = fleet.summary.classes.find(name);
    out.emplace_back(name, found == fleet.summary.classes.end() ? 0 : found->second);
  }
  for (const auto& entry : fleet.summary.classes) {
    if (std::none_of(out.begin(), out.end(),
                     [&](const auto& e) { return e.first == entry.first; })) {
      out.push_back(entry);
    }
  }
  return out;
}

std::string summary_sentence(const FleetReport& fleet) {
  const auto trending = std::count_if(fleet.rows.begin(), fleet.rows.end(), [](const FleetRow& r) {
    return !r.short_tau_trend.tau_s.empty();
  });
  return fmt::format(
      "{} unit(s) analysed{}, {} failed; {} stand(s) out of the fleet (modified z-score beyond "
      "{:g} on log10 of a parameter); the short-tau noise trends over the run on {} (a "
      "warm-up, or a sensor whose noise changes: the units' table says at which taus).",
      fleet.rows.size(),
      fleet.reused > 0 ? fmt::format(" ({} kept from an earlier run)", fleet.reused) : "",
      fleet.failures.size(), outliers_by_unit(fleet).size(), fleet.outlier_z, trending);
}

/// The check in the units' table (drift_cell) of a row.
std::string trend_cell(const FleetRow& r) {
  return drift_cell(r.short_tau_trend, r.short_tau_checked);
}

}  // namespace

std::vector<model::FleetUnit> fleet_units(const std::vector<FleetRow>& rows) {
  std::vector<model::FleetUnit> units;
  units.reserve(rows.size());
  for (const FleetRow& r : rows) {
    model::FleetUnit u;
    u.name = r.unit;
    u.values = {{"N", resolved(r.N)},
                {"B", resolved(r.B)},
                {"K", resolved(r.K)},
                {"bias_instability", r.bias_instability_deg_h}};
    for (const auto& [name, term] : {std::pair{"N", &r.N}, {"B", &r.B}, {"K", &r.K}}) {
      if (term->status == "resolved") u.ci95[name] = {term->ci95_low, term->ci95_high};
    }
    u.ci95["bias_instability"] = {r.bias_instability_ci95_low, r.bias_instability_ci95_high};
    u.accuracy_class = r.accuracy_class;
    units.push_back(std::move(u));
  }
  return units;
}

std::string fleet_csv(const FleetReport& fleet) {
  std::string csv =
      "unit,file,channel,"
      "N_deg_h_sqrt_hz,N_ci95_low_deg_h_sqrt_hz,N_ci95_high_deg_h_sqrt_hz,N_status,"
      "B_deg_h,B_ci95_low_deg_h,B_ci95_high_deg_h,B_status,"
      "K_deg_h_sqrt_s,K_ci95_low_deg_h_sqrt_s,K_ci95_high_deg_h_sqrt_s,K_status,"
      "bias_instability_deg_h,bias_instability_tau_s,arw_deg_sqrt_h,random_bias,accuracy_class,"
      "stands_out_on,short_tau_trend_tau_s\n";
  const std::map<std::string, std::string> outliers = outliers_by_unit(fleet);
  for (const FleetRow& r : fleet.rows) {
    const auto found = outliers.find(r.unit);
    csv += fmt::format("{},{},{}", csv_field(r.unit), csv_field(r.file), csv_field(r.channel));
    for (const FleetTerm* t : {&r.N, &r.B, &r.K}) {
      csv += fmt::format(",{},{},{},{}", csv_number(t->value), csv_number(t->ci95_low),
                         csv_number(t->ci95_high), csv_field(t->status));
    }
    // the taus that trend, space-separated; "none", or "not_checked"
    const std::string trend = !r.short_tau_checked ? "not_checked"
                              : r.short_tau_trend.tau_s.empty()
                                  ? "none"
                                  : called_taus(r.short_tau_trend, " ");
    csv += fmt::format(",{},{},{},{},{},{},{}\n", csv_number(r.bias_instability_deg_h),
                       csv_number(r.bias_instability_tau_s), csv_number(r.arw_deg_sqrt_h),
                       csv_field(r.random_bias), csv_field(r.accuracy_class),
                       found == outliers.end() ? "" : csv_field(found->second), trend);
  }
  return csv;
}

std::string fleet_markdown(const FleetReport& fleet) {
  std::string md = "# " + fleet.title + "\n\n" + summary_sentence(fleet) + "\n\n";
  md +=
      "## The fleet\n\nMedian, spread (1.4826 MAD of log10, as a factor) and range of each "
      "parameter over the units where it was resolved.\n\n"
      "| parameter | unit | units | median | spread factor | 5 % | 95 % | min | max |\n"
      "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const model::ParameterSpread& p : fleet.summary.parameters) {
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", p.name, unit_of(p.name),
                      p.units, g(p.median), g(p.spread_factor), g(p.p05), g(p.p95), g(p.minimum),
                      g(p.maximum));
  }
  md += "\n## Units that stand out\n\n";
  if (fleet.summary.outliers.empty()) {
    md += "None.\n";
  } else {
    md +=
        "| unit | parameter | value | unit of value | x median | modified z |\n"
        "|---|---|---:|---|---:|---:|\n";
    for (const model::FleetOutlier& o : fleet.summary.outliers) {
      md += fmt::format("| {} | {} | {} | {} | {} | {:+.2f} |\n", o.unit, o.parameter, g(o.value),
                        unit_of(o.parameter), g(o.times_median), o.modified_z);
    }
  }
  md += "\n## Accuracy classes (lab manual, Table 1)\n\n| class | units | |\n|---|---:|---|\n";
  for (const auto& [name, count] : class_counts(fleet)) {
    md += fmt::format("| {} | {} | {} |\n", name, count, std::string(count, '#'));
  }
  if (!fleet.failures.empty()) {
    md += "\n## Records that failed\n\n| input | exit code | error |\n|---|---:|---|\n";
    for (const FleetFailure& f : fleet.failures) {
      std::string message = f.message;
      std::replace(message.begin(), message.end(), '\n', ' ');
      std::replace(message.begin(), message.end(), '|', '/');
      md += fmt::format("| {} | {} | {} |\n", f.input, f.exit_code, message);
    }
  }
  md +=
      "\n## Units\n\n95 % intervals in brackets; '< x': not resolved, its 95 % upper bound.\n\n"
      "| unit | N [deg/h/sqrt(Hz)] | B [deg/h] | K [deg/h/sqrt(s)] | bias instability [deg/h] "
      "| ARW [deg/sqrt(h)] | random bias | class | stands out on | short-tau trend over the run "
      "|\n"
      "|---|---|---|---|---:|---:|---|---|---|---|\n";
  const std::map<std::string, std::string> outliers = outliers_by_unit(fleet);
  for (const FleetRow& r : fleet.rows) {
    const auto found = outliers.find(r.unit);
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.unit,
                      term_text(r.N), term_text(r.B), term_text(r.K), g(r.bias_instability_deg_h),
                      g(r.arw_deg_sqrt_h), r.random_bias,
                      r.accuracy_class.empty() ? "-" : r.accuracy_class,
                      found == outliers.end() ? "" : found->second, trend_cell(r));
  }
  return md;
}

std::vector<Plot> fleet_plots(const FleetReport& fleet) {
  const std::vector<model::FleetUnit> units = fleet_units(fleet.rows);
  std::vector<Plot> plots;
  for (const model::ParameterSpread& p : fleet.summary.parameters) {
    if (p.units < 2) continue;
    std::vector<std::pair<double, std::string>> values;
    for (const model::FleetUnit& u : units) {
      const double v = u.values.at(p.name);
      if (std::isfinite(v) && v > 0.0) values.emplace_back(v, u.name);
    }
    std::sort(values.begin(), values.end());
    Series all, out;
    all.title = "units";
    all.style = out.style = SeriesStyle::points;
    all.color = kBlue;
    out.title = "stand out";
    out.color = kRed;
    out.point_size = 1.1;
    const double n = static_cast<double>(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) {
      const double rank = 100.0 * (static_cast<double>(k) + 0.5) / n;
      const bool flagged = std::any_of(fleet.summary.outliers.begin(), fleet.summary.outliers.end(),
                                       [&](const model::FleetOutlier& o) {
                                         return o.parameter == p.name && o.unit == values[k].second;
                                       });
      Series& s = flagged ? out : all;
      s.x.push_back(rank);
      s.y.push_back(values[k].first);
    }
    Plot plot;
    plot.title = fmt::format("{} across the fleet ({} units)", p.name, p.units);
    plot.x_label = "units ranked by value [% of the units]";
    plot.y_label = fmt::format("{} [{}]", p.name, unit_of(p.name));
    plot.log_y = true;
    plot.x_range = AxisRange{0.0, 100.0};
    plot.key = "top left";
    auto across = [](std::string title, double y, const char* color, int dash) {
      Series s;
      s.title = std::move(title);
      s.x = {0.0, 100.0};
      s.y = {y, y};
      s.color = color;
      s.line_width = 1.2;
      s.dash_type = dash;
      s.sets_range = false;
      return s;
    };
    plot.series.push_back(across(fmt::format("median {}", g(p.median)), p.median, kBlack, 2));
    if (p.spread_log10 > 0.0) {
      const double factor = std::pow(10.0, fleet.outlier_z * p.spread_log10);
      plot.series.push_back(across(fmt::format("outlier limits (z = {:g})", fleet.outlier_z),
                                   p.median * factor, kGrey, 3));
      plot.series.push_back(across("", p.median / factor, kGrey, 3));
    }
    plot.series.push_back(std::move(all));
    if (!out.x.empty()) plot.series.push_back(std::move(out));
    plots.push_back(std::move(plot));
  }
  return plots;
}

std::string fleet_html(const FleetReport& fleet, const ReportOptions& options) {
  std::string h = "<p>" + html_escape(summary_sentence(fleet)) + "</p>\n";
  h += "<h2>The fleet</h2>\n<table>\n<tr>" + th("parameter") + th("unit") + th("units") +
       th("median") + th("spread factor") + th("5 %") + th("95 %") + th("min") + th("max") +
       "</tr>\n";
  for (const model::ParameterSpread& p : fleet.summary.parameters) {
    h += "<tr>" + td(p.name) + td(unit_of(p.name)) + td(std::to_string(p.units)) + td(g(p.median)) +
         td(g(p.spread_factor)) + td(g(p.p05)) + td(g(p.p95)) + td(g(p.minimum)) +
         td(g(p.maximum)) + "</tr>\n";
  }
  h += "</table>\n";

  const std::vector<Plot> plots = fleet_plots(fleet);
  std::vector<FigureSpec> specs;
  for (const Plot& p : plots) {
    const std::string name = p.y_label.substr(0, p.y_label.find(' '));
    specs.push_back(
        {"fleet_" + name, fmt::format("{}: each unit's value, ranked, on a log scale; the fleet's "
                                      "median (dashed), the outlier limits (dotted) and the units "
                                      "beyond them (red).",
                                      name)});
  }
  ReportOptions o = options;
  o.id_prefix = options.id_prefix + "fleet";
  const RenderedFigures drawn = render_figures(plots, specs, o);
  if (drawn.skipped) h += "<p class=\"warn\">" + html_escape(drawn.note) + "</p>\n";
  for (const Figure& f : drawn.figures) {
    if (drawn.skipped) break;
    h += figure_html(f);
  }

  h += "<h2>Units that stand out</h2>\n";
  if (fleet.summary.outliers.empty()) {
    h += "<p>None.</p>\n";
  } else {
    h += "<table>\n<tr>" + th("unit") + th("parameter") + th("value") + th("unit of value") +
         th("x median") + th("modified z") + "</tr>\n";
    for (const model::FleetOutlier& out : fleet.summary.outliers) {
      h += "<tr>" + td(out.unit) + td(out.parameter) + td(g(out.value)) +
           td(unit_of(out.parameter)) + td(g(out.times_median)) +
           td(fmt::format("{:+.2f}", out.modified_z)) + "</tr>\n";
    }
    h += "</table>\n";
  }

  h += "<h2>Accuracy classes (lab manual, Table 1)</h2>\n<table>\n<tr>" + th("class") +
       th("units") + th("") + "</tr>\n";
  const std::size_t most = std::max<std::size_t>(1, fleet.rows.size());
  for (const auto& [name, count] : class_counts(fleet)) {
    h += "<tr>" + td(name) + td(std::to_string(count)) +
         fmt::format("<td><div style=\"background:{};height:0.9em;width:{:.1f}em\"></div></td>",
                     kBlue, 20.0 * static_cast<double>(count) / static_cast<double>(most)) +
         "</tr>\n";
  }
  h += "</table>\n";

  if (!fleet.failures.empty()) {
    h += "<h2>Records that failed</h2>\n<table>\n<tr>" + th("input") + th("exit code") +
         th("error") + "</tr>\n";
    for (const FleetFailure& f : fleet.failures) {
      h += "<tr>" + td(f.input) + td(std::to_string(f.exit_code)) + td(f.message) + "</tr>\n";
    }
    h += "</table>\n";
  }

  const std::map<std::string, std::string> outliers = outliers_by_unit(fleet);
  h += "<h2>Units</h2>\n<p>95 % intervals in brackets; &lt; x: not resolved, its 95 % upper "
       "bound.</p>\n<table>\n<tr>" +
       th("unit") + th("N [deg/h/sqrt(Hz)]") + th("B [deg/h]") + th("K [deg/h/sqrt(s)]") +
       th("bias instability [deg/h]") + th("ARW [deg/sqrt(h)]") + th("random bias") + th("class") +
       th("stands out on") + th("short-tau trend over the run") + "</tr>\n";
  for (const FleetRow& r : fleet.rows) {
    const auto found = outliers.find(r.unit);
    h += "<tr>" + td(r.unit) + td(term_text(r.N)) + td(term_text(r.B)) + td(term_text(r.K)) +
         td(g(r.bias_instability_deg_h)) + td(g(r.arw_deg_sqrt_h)) + td(r.random_bias) +
         td(r.accuracy_class.empty() ? "-" : r.accuracy_class) +
         td(found == outliers.end() ? "" : found->second) + td(trend_cell(r)) + "</tr>\n";
  }
  h += "</table>\n";
  return html_document(std::span<const Report>(), fleet.title, h);
}

}  // namespace foglab::report
