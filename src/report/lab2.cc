// foglab — the lab-2 report (lab2.h).
#include "foglab/report/lab2.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <future>
#include <limits>

#include "foglab/core/error.h"
#include "foglab/model/run_comparison.h"
#include "report_internal.h"

namespace foglab::report {
namespace {

using namespace detail;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- cells -------------------------------------------------------------------------

Lab2Cell missing_cell() { return {kNaN, kNaN, kNaN, "-"}; }

Lab2Cell number_cell(double v, int digits = 4) {
  return {v, kNaN, kNaN, std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : "-"};
}

Lab2Cell reading_cell(const std::optional<double>& v) {
  if (!v) return {kNaN, kNaN, kNaN, "not visible"};
  return number_cell(*v);
}

/// A fitted parameter: "v [lo, hi]" when resolved, "< bound" when left out.
Lab2Cell estimate_cell(const model::ParameterEstimate& p) {
  const ParameterText t = parameter_text(p);
  if (p.status == model::TermStatus::resolved) {
    return {p.value, p.ci95_low, p.ci95_high, t.value + " " + t.interval};
  }
  if (p.status == model::TermStatus::upper_bound) return {kNaN, 0.0, p.ci95_high, t.value};
  return {kNaN, kNaN, kNaN, "absent"};
}

Lab2Cell bias_instability_cell(const model::AnalysisResult& r) {
  const auto [lo, hi] = model::adev_interval_at(r.allan, r.bias_instability_tau_s);
  std::string text =
      fmt::format("{} at {} s", g(r.bias_instability_deg_h), g(r.bias_instability_tau_s));
  if (std::isfinite(lo) && std::isfinite(hi)) text += fmt::format(" [{}, {}]", g(lo), g(hi));
  if (r.bias_instability_at_edge) text += " (range end)";
  return {r.bias_instability_deg_h, lo, hi, text};
}

std::string process_name(RandomBiasProcess p) {
  switch (p) {
    case RandomBiasProcess::wiener:
      return "Wiener";
    case RandomBiasProcess::gauss_markov:
      return "Gauss-Markov";
    case RandomBiasProcess::none:
      break;
  }
  return "not visible";
}

// ---- rows --------------------------------------------------------------------------

using CellOf = std::function<Lab2Cell(const Lab2Run&)>;
using TruthOf = std::function<std::string(const Lab2Truth&)>;

void add_row(Lab2Table& t, std::string quantity, std::string method, std::string unit,
             const CellOf& cell, const TruthOf& truth) {
  Lab2Row row{std::move(quantity), std::move(method), std::move(unit), {}, {}};
  std::array<std::string, 2> truths;
  for (std::size_t k = 0; k < 2; ++k) {
    row.runs[k] = t.runs[k] ? cell(*t.runs[k]) : missing_cell();
    if (truth && t.runs[k] && t.runs[k]->truth) truths[k] = truth(*t.runs[k]->truth);
  }
  if (!truths[0].empty() && !truths[1].empty() && truths[0] != truths[1]) {
    row.truth = truths[0] + " (constant) / " + truths[1] + " (ramp)";
  } else {
    row.truth = truths[0].empty() ? truths[1] : truths[0];
  }
  t.rows.push_back(std::move(row));
}

bool any_run(const Lab2Table& t, const std::function<bool(const Lab2Run&)>& test) {
  return std::any_of(t.runs.begin(), t.runs.end(),
                     [&](const Lab2Run* r) { return r != nullptr && test(*r); });
}

void build_rows(Lab2Table& t) {
  const auto fit = [](model::ParameterEstimate model::NoiseFitResult::*p) -> CellOf {
    return [p](const Lab2Run& r) { return estimate_cell(r.result.noise.*p); };
  };
  const auto truth_number = [](double Lab2Truth::*p) -> TruthOf {
    return [p](const Lab2Truth& tr) {
      return std::isfinite(tr.*p) ? fmt::format("{:.4g}", tr.*p) : std::string("-");
    };
  };

  add_row(
      t, "systematic bias", "lab: constant term of polyfit(T, Y, 2)", "deg/h",
      [](const Lab2Run& r) {
        if (!r.result.systematic) return missing_cell();
        const model::SystematicFit& s = *r.result.systematic;
        Lab2Cell c = number_cell(s.lab_constant_term_deg_h, 5);
        if (!s.lab_constant_meaningful) c.text += " (not meaningful: T barely moves)";
        return c;
      },
      truth_number(&Lab2Truth::lab_constant_term_deg_h));
  add_row(
      t, "systematic bias", "fit: at the mean temperature", "deg/h",
      [](const Lab2Run& r) {
        if (!r.result.systematic) return missing_cell();
        const model::SystematicFit& s = *r.result.systematic;
        // No interval: the intercept's standard error counts only the
        // stationary noise (systematic.h), while flicker and a random walk
        // move the record's mean too; the comparison below uses the ADEV.
        Lab2Cell c = number_cell(s.bias_deg_h, 5);
        c.text += fmt::format(" at {:.4g} degC", s.t_ref_c);
        return c;
      },
      truth_number(&Lab2Truth::bias_at_t_ref_deg_h));
  add_row(
      t, "temperature coefficient c1", "fit: polynomial in (T - mean)", "deg/h/degC",
      [](const Lab2Run& r) {
        if (!r.result.systematic) return missing_cell();
        const model::SystematicFit& s = *r.result.systematic;
        if (s.coefficients.size() < 2) {
          return Lab2Cell{kNaN, kNaN, kNaN,
                          s.constant_fallback ? "- (T barely moves)" : "- (degree 0 chosen)"};
        }
        const double se = s.standard_errors.size() > 1 ? s.standard_errors[1] : kNaN;
        Lab2Cell c = number_cell(s.coefficients[1]);
        if (std::isfinite(se)) {
          c.ci95_low = s.coefficients[1] - 1.96 * se;
          c.ci95_high = s.coefficients[1] + 1.96 * se;
          c.text += fmt::format(" +- {}", g(1.96 * se));
        }
        return c;
      },
      truth_number(&Lab2Truth::c1_deg_h_per_c));
  add_row(
      t, "random bias process", "fit: model choice", "-",
      [](const Lab2Run& r) {
        return Lab2Cell{kNaN, kNaN, kNaN, process_name(r.result.noise.random_bias_process)};
      },
      [](const Lab2Truth& tr) { return process_name(tr.random_bias_process); });

  const bool wiener = any_run(t, [](const Lab2Run& r) {
    return r.result.noise.random_bias_process == RandomBiasProcess::wiener ||
           (r.truth && r.truth->random_bias_process == RandomBiasProcess::wiener);
  });
  const bool gauss_markov = any_run(t, [](const Lab2Run& r) {
    return r.result.noise.random_bias_process == RandomBiasProcess::gauss_markov ||
           (r.truth && r.truth->random_bias_process == RandomBiasProcess::gauss_markov);
  });
  // The Wiener rows always: the lab asks for K "when present", and a reading
  // that finds no -2 slope is the answer that it is not.
  add_row(
      t, "Wiener intensity K", "PSD: -2 slope at 1 Hz", "deg/h/sqrt(s)",
      [](const Lab2Run& r) { return reading_cell(r.result.psd_readings.K); },
      truth_number(&Lab2Truth::K));
  add_row(
      t, "Wiener intensity K", "Allan: +1/2 line at 3 s", "deg/h/sqrt(s)",
      [](const Lab2Run& r) { return reading_cell(r.result.adev_readings.K); },
      truth_number(&Lab2Truth::K));
  if (wiener || !gauss_markov) {
    add_row(t, "Wiener intensity K", "fit [95 %]", "deg/h/sqrt(s)", fit(&model::NoiseFitResult::K),
            truth_number(&Lab2Truth::K));
  }
  if (gauss_markov) {
    add_row(t, "Gauss-Markov sigma", "fit [95 %]", "deg/h", fit(&model::NoiseFitResult::gm_sigma),
            truth_number(&Lab2Truth::gm_sigma));
    add_row(t, "Gauss-Markov Tc", "fit [95 %]", "s", fit(&model::NoiseFitResult::gm_tc),
            truth_number(&Lab2Truth::gm_tc));
  }

  add_row(
      t, "white noise N", "PSD: flat level", "deg/h/sqrt(Hz)",
      [](const Lab2Run& r) { return reading_cell(r.result.psd_readings.N); },
      truth_number(&Lab2Truth::N));
  add_row(
      t, "white noise N", "Allan: -1/2 line at 1 s", "deg/h/sqrt(Hz)",
      [](const Lab2Run& r) { return reading_cell(r.result.adev_readings.N); },
      truth_number(&Lab2Truth::N));
  add_row(t, "white noise N", "fit [95 %]", "deg/h/sqrt(Hz)", fit(&model::NoiseFitResult::N),
          truth_number(&Lab2Truth::N));
  add_row(
      t, "angle random walk", "fit: N/60", "deg/sqrt(h)",
      [](const Lab2Run& r) { return number_cell(r.result.arw_deg_sqrt_h); },
      [](const Lab2Truth& tr) { return fmt::format("{:.4g}", arw_deg_sqrt_h(tr.N)); });
  add_row(
      t, "bias instability", "Allan: minimum [95 %]", "deg/h",
      [](const Lab2Run& r) { return bias_instability_cell(r.result); },
      truth_number(&Lab2Truth::bias_instability_deg_h));
  add_row(
      t, "accuracy class", "Table 1: worse of BI and ARW", "-",
      [](const Lab2Run& r) {
        const ClassVerdict& v = r.result.verdict;
        return Lab2Cell{kNaN, kNaN, kNaN,
                        fmt::format("{} ({})", to_string(v.accuracy_class),
                                    v.decided_by == ClassCriterion::both
                                        ? "both criteria"
                                        : "by " + std::string(to_string(v.decided_by)))};
      },
      [](const Lab2Truth& tr) { return std::string(to_string(tr.accuracy_class)); });
}

// ---- the written comparison ----------------------------------------------------------

/// "what: a -> b unit (+x %)" and the verdict on the 95 % intervals.
std::string change_text(std::string_view what, std::string_view unit, const model::ValueChange& c) {
  std::string text = fmt::format("{}: {} -> {} {} ({:+.1f} %)", what, g(c.before), g(c.after),
                                 unit, 100.0 * c.relative);
  switch (c.verdict) {
    case model::Change::changed:
      return text + "; the 95 % intervals do not overlap: the ramp changed it.";
    case model::Change::unchanged:
      return text + "; the 95 % intervals overlap: unchanged within the uncertainty.";
    case model::Change::not_comparable:
      break;
  }
  return text + ".";
}

std::vector<std::string> systematic_sentences(const model::SystematicChange& s) {
  std::string text =
      fmt::format("Temperature: the ramp run spans {:.3g} degC (the constant run {:.2g} degC). ",
                  s.span_after_c, s.span_before_c);
  if (s.degree_after > 0) {
    text += fmt::format(
        "Its fitted polynomial (degree {}) moves the bias by {} deg/h over the ramp, {:.3g} "
        "times the bias instability: without removing it the ramp would pass for a large "
        "drift and spoil the Allan deviation at long tau.",
        s.degree_after, g(s.polynomial_range_deg_h), s.range_over_bias_instability);
  } else {
    text += "The criterion found no temperature dependence in it.";
  }
  std::string bias = fmt::format(
      "Systematic bias at the mean temperature: {:.5g} deg/h (constant, {:.4g} degC) and "
      "{:.5g} deg/h (ramp, {:.4g} degC), {} deg/h apart",
      s.bias_before_deg_h, s.t_ref_before_c, s.bias_after_deg_h, s.t_ref_after_c,
      g(s.bias_difference_deg_h));
  if (std::isfinite(s.wander_deg_h) && s.wander_deg_h > 0.0) {
    bias += fmt::format(
        " — {:.2g} times the fitted model's Allan deviation at half the record ({} deg/h), "
        "the scale on which the random bias moves the mean of a record",
        s.bias_difference_deg_h / s.wander_deg_h, g(s.wander_deg_h));
  }
  bias += s.lab_constant_meaningful_before
              ? "."
              : "; at constant temperature the lab's polyfit constant term is not meaningful "
                "(the temperature moves too little to extrapolate to 0 degC), so compare these.";
  return {text, bias};
}

std::string random_bias_sentence(const model::RunComparison& c) {
  if (c.process_before != c.process_after) {
    return fmt::format(
        "Random bias: {} at constant temperature, {} during the ramp. Over a record this short "
        "a Gauss-Markov process whose correlation time is near the end of the tau range looks "
        "like a random walk, so the two answers can differ on the same gyro; the run whose "
        "Allan deviation reaches further past the hump decides.",
        process_name(c.process_before), process_name(c.process_after));
  }
  std::string text = "Random bias: " + process_name(c.process_before) + " in both runs";
  if (c.random_walk) return text + "; " + change_text("K", "deg/h/sqrt(s)", *c.random_walk);
  if (c.gm_sigma && c.gm_tc) {
    return text + fmt::format("; sigma {} -> {} deg/h, Tc {} -> {} s.", g(c.gm_sigma->before),
                              g(c.gm_sigma->after), g(c.gm_tc->before), g(c.gm_tc->after));
  }
  return text + ".";
}

std::string changed_item_name(model::ChangedItem item, const model::RunComparison& c,
                              std::size_t& term) {
  switch (item) {
    case model::ChangedItem::white_noise:
      return "the white noise";
    case model::ChangedItem::bias_instability:
      return "the bias instability";
    case model::ChangedItem::random_walk:
      return "the Wiener intensity";
    case model::ChangedItem::random_bias_process:
      return "the random-bias answer";
    case model::ChangedItem::term:
      return fmt::format("the {} term", to_string(c.terms_in_one_run[term++].term));
  }
  return "";
}

std::vector<std::string> compare_runs(const Lab2Run& constant, const Lab2Run& ramp) {
  const model::RunComparison c = model::compare_runs(constant.result, ramp.result);
  std::vector<std::string> out;
  if (c.systematic) out = systematic_sentences(*c.systematic);
  if (c.white_noise) out.push_back(change_text("White noise N (fit)", "deg/h/sqrt(Hz)", *c.white_noise));
  out.push_back(change_text("Bias instability (ADEV minimum)", "deg/h", c.bias_instability));
  out.push_back(random_bias_sentence(c));
  for (const model::TermInOneRun& t : c.terms_in_one_run) {
    const NoiseParameter& p = kNoiseParameters[static_cast<std::size_t>(t.term)];
    out.push_back(fmt::format(
        "Only the {} run resolves {} = {} {}{}.", t.in_after ? "ramp" : "constant", p.name,
        g(t.value), p.unit,
        t.term == NoiseTerm::ramp && t.in_after
            ? ": a drift the temperature polynomial does not remove (e.g. a dependence on the "
              "rate of temperature change)"
            : ""));
  }
  out.push_back(c.class_before == c.class_after
                    ? fmt::format("Accuracy class: {} in both runs.", to_string(c.class_before))
                    : fmt::format("Accuracy class: {} at constant temperature, {} during "
                                  "the ramp.",
                                  to_string(c.class_before), to_string(c.class_after)));
  if (c.changed.empty()) {
    out.push_back(
        "Conclusion: once the temperature polynomial is removed, the ramp leaves the random "
        "error unchanged within the 95 % intervals: the temperature acts on the systematic "
        "part, which the polynomial captures.");
  } else {
    std::string list;
    std::size_t term = 0;
    for (std::size_t k = 0; k < c.changed.size(); ++k) {
      list += (k == 0 ? "" : k + 1 == c.changed.size() ? " and " : ", ") +
              changed_item_name(c.changed[k], c, term);
    }
    out.push_back("Conclusion: the ramp changed " + list +
                  ", beyond what the polynomial removes; check the residual's Allan deviation at "
                  "long tau and the bias-temperature plot for hysteresis.");
  }
  return out;
}

std::string class_text(const Lab2Table& t) {
  std::string text = t.gyro + ":";
  bool first = true;
  for (std::size_t k = 0; k < 2; ++k) {
    if (!t.runs[k]) continue;
    const ClassVerdict& v = t.runs[k]->result.verdict;
    text += fmt::format("{} {} {} ({})", first ? "" : ",", to_string(v.accuracy_class),
                        k == 0 ? "at constant temperature" : "during the temperature ramp",
                        v.decided_by == ClassCriterion::both  ? "both criteria agree"
                        : v.decided_by == ClassCriterion::arw ? "decided by the ARW"
                                                              : "decided by the bias instability");
    first = false;
  }
  return text;
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : ""; }

std::string file_of(const Lab2Table& t) {
  for (const Lab2Run* r : t.runs) {
    if (r != nullptr && !r->input.file_name.empty()) return r->input.file_name;
  }
  return "";
}

}  // namespace

std::string_view to_string(Lab2Condition condition) {
  return condition == Lab2Condition::constant ? "constant temperature" : "temperature ramp";
}

Lab2Truth lab2_truth(const sim::Lab2Gyro& g, const sim::Lab2Run& r) {
  const bool wiener = g.random_bias == RandomBiasProcess::wiener;
  Lab2Truth t;
  t.random_bias_process = g.random_bias;
  t.N = g.model.noise.N;
  t.K = wiener ? g.model.noise.K : kNaN;
  t.gm_sigma = wiener ? kNaN : g.model.noise.gm_sigma;
  t.gm_tc = wiener ? kNaN : g.model.noise.gm_tc;
  t.bias_instability_deg_h = r.bias_instability.adev_deg_h;
  t.bias_at_t_ref_deg_h = r.bias_at_t_ref_deg_h;
  t.lab_constant_term_deg_h = r.lab_constant_term_deg_h;
  t.c1_deg_h_per_c = g.model.temp_coefs.empty() ? 0.0 : g.model.temp_coefs[0];
  t.accuracy_class = g.verdict.accuracy_class;
  return t;
}

std::vector<Lab2Table> lab2_tables(std::span<const Lab2Run> runs) {
  std::vector<Lab2Table> tables;
  for (const Lab2Run& run : runs) {
    auto it = std::find_if(tables.begin(), tables.end(),
                           [&](const Lab2Table& t) { return t.gyro == run.gyro; });
    if (it == tables.end()) {
      tables.push_back({});
      tables.back().gyro = run.gyro;
      it = std::prev(tables.end());
    }
    const std::size_t k = run.condition == Lab2Condition::constant ? 0 : 1;
    if (it->runs[k] != nullptr) {
      throw UsageError(fmt::format("lab 2: two {} runs of {} ('{}' and '{}')",
                                   to_string(run.condition), run.gyro, it->runs[k]->input.file_name,
                                   run.input.file_name));
    }
    it->runs[k] = &run;
  }
  for (Lab2Table& t : tables) {
    t.has_truth = any_run(t, [](const Lab2Run& r) { return r.truth.has_value(); });
    build_rows(t);
    t.class_sentence = class_text(t);
    if (t.runs[0] && t.runs[1]) t.comparison = compare_runs(*t.runs[0], *t.runs[1]);
  }
  return tables;
}

std::string lab2_tables_markdown(std::span<const Lab2Table> tables) {
  std::string md;
  for (const Lab2Table& t : tables) {
    const std::string file = file_of(t);
    md += fmt::format("## {}{}\n\n", t.gyro, file.empty() ? "" : " (" + file + ")");
    md += "| quantity | method | constant temperature | temperature ramp |";
    md += t.has_truth ? " answer key | unit |\n|---|---|---|---|---|---|\n"
                      : " unit |\n|---|---|---|---|---|\n";
    for (const Lab2Row& row : t.rows) {
      md += fmt::format("| {} | {} | {} | {} |", row.quantity, row.method, row.runs[0].text,
                        row.runs[1].text);
      if (t.has_truth) md += " " + (row.truth.empty() ? std::string("-") : row.truth) + " |";
      md += " " + row.unit + " |\n";
    }
    md += "\n**Accuracy class** — " + t.class_sentence + ".\n\n";
    if (!t.comparison.empty()) {
      md += "What the temperature ramp changed:\n\n";
      for (const std::string& s : t.comparison) md += "- " + s + "\n";
      md += "\n";
    }
  }
  return md;
}

std::string lab2_tables_html(std::span<const Lab2Table> tables) {
  std::string h;
  for (const Lab2Table& t : tables) {
    const std::string file = file_of(t);
    h += "<section>\n<h2>" + html_escape(t.gyro) +
         (file.empty() ? "" : " <small>(" + html_escape(file) + ")</small>") +
         ": the lab's table</h2>\n";
    h += "<table class=\"lab2\">\n<tr>" + th("quantity") + th("method") +
         th("constant temperature") + th("temperature ramp");
    if (t.has_truth) h += th("answer key");
    h += th("unit") + "</tr>\n";
    for (const Lab2Row& row : t.rows) {
      h += "<tr>" + td(row.quantity) + td(row.method) + td(row.runs[0].text) + td(row.runs[1].text);
      if (t.has_truth) h += "<td class=\"truth\">" + html_escape(row.truth) + "</td>";
      h += td(row.unit) + "</tr>\n";
    }
    h += "</table>\n<p class=\"verdict\">Accuracy class — " + html_escape(t.class_sentence) +
         ".</p>\n";
    if (!t.comparison.empty()) {
      h += "<h3>What the temperature ramp changed</h3>\n<ul>\n";
      for (const std::string& s : t.comparison) h += "<li>" + html_escape(s) + "</li>\n";
      h += "</ul>\n";
    }
    h += "</section>\n";
  }
  return h;
}

std::string lab2_tables_csv(std::span<const Lab2Table> tables) {
  std::string out =
      "# foglab lab 2: one line per table cell; value and the 95 % interval in the unit "
      "column's unit (empty: none), text as shown in the report\n"
      "gyro,quantity,method,unit,condition,value,ci95_low,ci95_high,text,truth\n";
  for (const Lab2Table& t : tables) {
    for (const Lab2Row& row : t.rows) {
      for (std::size_t k = 0; k < 2; ++k) {
        if (!t.runs[k]) continue;
        const Lab2Cell& c = row.runs[k];
        out +=
            fmt::format("{},{},{},{},{},{},{},{},{},{}\n", csv_field(t.gyro),
                        csv_field(row.quantity), csv_field(row.method), csv_field(row.unit),
                        k == 0 ? "constant" : "ramp", csv_number(c.value), csv_number(c.ci95_low),
                        csv_number(c.ci95_high), csv_field(c.text), csv_field(row.truth));
      }
    }
  }
  return out;
}

Lab2Report make_lab2_report(std::span<const Lab2Run> runs, std::string_view title,
                            std::string_view intro, const ReportOptions& options) {
  Lab2Report out;
  out.tables = lab2_tables(runs);

  // The plots: one task per run (each runs its gnuplots one after another).
  std::vector<std::future<Report>> pending;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    ReportOptions o = options;
    o.id_prefix = fmt::format("{}{}", options.id_prefix, k + 1);
    pending.push_back(std::async(std::launch::async, [&runs, k, o] {
      return make_report(runs[k].result, runs[k].input, o);
    }));
  }
  for (auto& p : pending) out.runs.push_back(p.get());
  for (const Report& r : out.runs) {
    if (r.plots_skipped) {
      out.plots_skipped = true;
      out.plots_note = r.plots_note;
    }
  }

  std::string preface = "<p>" + html_escape(intro) + "</p>\n";
  if (out.plots_skipped) preface += "<p class=\"warn\">" + html_escape(out.plots_note) + "</p>\n";
  preface += lab2_tables_html(out.tables);
  out.html = html_document(out.runs, title, preface);

  out.markdown_summary =
      fmt::format("# {}\n\n{}\n\n", title, intro) + lab2_tables_markdown(out.tables);
  if (out.plots_skipped) out.markdown_summary += out.plots_note + "\n\n";
  out.markdown = out.markdown_summary;
  for (const Report& r : out.runs) out.markdown += r.markdown + "\n";
  out.csv = lab2_tables_csv(out.tables);
  return out;
}

}  // namespace foglab::report
