// foglab — the lab-2 report (lab2.h).
#include "foglab/report/lab2.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <numbers>

#include "foglab/core/csv.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/model/run_comparison.h"
#include "report_internal.h"

namespace foglab::report {
namespace {

using namespace detail;

// ---- cells -------------------------------------------------------------------------

Lab2Cell missing_cell() { return {kNaN, kNaN, kNaN, "-"}; }

Lab2Cell number_cell(double v, int digits = 4) {
  return {v, kNaN, kNaN, std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : "-"};
}

Lab2Cell reading_cell(const std::optional<double>& v, Language l) {
  if (!v) return {kNaN, kNaN, kNaN, say(l, Text::lab2_not_visible)};
  return number_cell(*v);
}

/// A fitted parameter: "v [lo, hi]" when resolved, "< bound" when left out.
Lab2Cell estimate_cell(const model::ParameterEstimate& p, Language l) {
  const ParameterText t = parameter_text(p, l);
  if (p.status == model::TermStatus::resolved) {
    return {p.value, p.ci95_low, p.ci95_high, t.value + " " + t.interval};
  }
  if (p.status == model::TermStatus::upper_bound) return {kNaN, 0.0, p.ci95_high, t.value};
  return {kNaN, kNaN, kNaN, say(l, Text::lab2_absent)};
}

Lab2Cell bias_instability_cell(const model::AnalysisResult& r, Language l) {
  const auto [lo, hi] = model::adev_interval_at(r.allan, r.bias_instability_tau_s);
  std::string text =
      say(l, Text::lab2_bi_at, g(r.bias_instability_deg_h), g(r.bias_instability_tau_s));
  if (std::isfinite(lo) && std::isfinite(hi)) text += fmt::format(" [{}, {}]", g(lo), g(hi));
  if (r.bias_instability_at_edge) text += say(l, Text::lab2_range_end);
  return {r.bias_instability_deg_h, lo, hi, text};
}

std::string process_name(RandomBiasProcess p, Language l) {
  switch (p) {
    case RandomBiasProcess::wiener:
      return say(l, Text::lab2_process_wiener);
    case RandomBiasProcess::gauss_markov:
      return say(l, Text::lab2_process_gauss_markov);
    case RandomBiasProcess::none:
      break;
  }
  return say(l, Text::lab2_process_none);
}

// ---- rows --------------------------------------------------------------------------

using CellOf = std::function<Lab2Cell(const Lab2Run&)>;
using TruthOf = std::function<std::string(const Lab2Truth&)>;

void add_row(Lab2Table& t, Text quantity, Text method, Text unit, const CellOf& cell,
             const TruthOf& truth) {
  const Language l = t.language;
  Lab2Row row{
      say(l, quantity), say(l, method), unit == Text::verbatim ? "-" : say(l, unit), {}, {}};
  std::array<std::string, 2> truths;
  for (std::size_t k = 0; k < 2; ++k) {
    row.runs[k] = t.runs[k] ? cell(*t.runs[k]) : missing_cell();
    if (truth && t.runs[k] && t.runs[k]->truth) truths[k] = truth(*t.runs[k]->truth);
  }
  if (!truths[0].empty() && !truths[1].empty() && truths[0] != truths[1]) {
    row.truth = say(l, Text::lab2_truth_both, truths[0], truths[1]);
  } else {
    row.truth = truths[0].empty() ? truths[1] : truths[0];
  }
  t.rows.push_back(std::move(row));
}

bool any_run(const Lab2Table& t, const std::function<bool(const Lab2Run&)>& test) {
  return std::any_of(t.runs.begin(), t.runs.end(),
                     [&](const Lab2Run* r) { return r != nullptr && test(*r); });
}

/// The accuracy class and which criterion decided it: "tactical (both criteria)".
std::string class_cell_text(const ClassVerdict& v, Language l) {
  const Text decided = v.decided_by == ClassCriterion::both  ? Text::lab2_both_criteria
                       : v.decided_by == ClassCriterion::arw ? Text::lab2_by_arw
                                                             : Text::lab2_by_bias_instability;
  return say(l, Text::lab2_class_cell, class_name(v.accuracy_class, l), say(l, decided));
}

void build_rows(Lab2Table& t) {
  const Language l = t.language;
  constexpr Text kNoUnit = Text::verbatim;  // shown as "-"
  const auto fit = [l](model::ParameterEstimate model::NoiseFitResult::*p) -> CellOf {
    return [p, l](const Lab2Run& r) { return estimate_cell(r.result.noise.*p, l); };
  };
  const auto truth_number = [](double Lab2Truth::*p) -> TruthOf {
    return [p](const Lab2Truth& tr) {
      return std::isfinite(tr.*p) ? fmt::format("{:.4g}", tr.*p) : std::string("-");
    };
  };

  add_row(
      t, Text::lab2_q_systematic_bias, Text::lab2_m_lab_constant, Text::unit_deg_h,
      [l](const Lab2Run& r) {
        if (!r.result.systematic) return missing_cell();
        const model::SystematicFit& s = *r.result.systematic;
        Lab2Cell c = number_cell(s.lab_constant_term_deg_h, 5);
        if (!s.lab_constant_meaningful) c.text += say(l, Text::lab2_not_meaningful);
        return c;
      },
      truth_number(&Lab2Truth::lab_constant_term_deg_h));
  add_row(
      t, Text::lab2_q_systematic_bias, Text::lab2_m_at_mean_temperature, Text::unit_deg_h,
      [l](const Lab2Run& r) {
        if (!r.result.systematic) return missing_cell();
        const model::SystematicFit& s = *r.result.systematic;
        // No interval: the intercept's standard error counts only the
        // stationary noise (systematic.h), while flicker and a random walk
        // move the record's mean too; the comparison below uses the ADEV.
        Lab2Cell c = number_cell(s.bias_deg_h, 5);
        c.text += say(l, Text::lab2_at_temperature, s.t_ref_c);
        return c;
      },
      truth_number(&Lab2Truth::bias_at_t_ref_deg_h));
  add_row(
      t, Text::lab2_q_c1, Text::lab2_m_polynomial, Text::unit_deg_h_per_degc,
      [l](const Lab2Run& r) {
        if (!r.result.systematic) return missing_cell();
        const model::SystematicFit& s = *r.result.systematic;
        if (s.coefficients.size() < 2) {
          return Lab2Cell{
              kNaN, kNaN, kNaN,
              say(l, s.constant_fallback ? Text::lab2_t_barely_moves : Text::lab2_degree_0_chosen)};
        }
        const double se = s.standard_errors.size() > 1 ? s.standard_errors[1] : kNaN;
        Lab2Cell c = number_cell(s.coefficients[1]);
        if (std::isfinite(se)) {
          c.ci95_low = s.coefficients[1] - 1.96 * se;
          c.ci95_high = s.coefficients[1] + 1.96 * se;
          c.text += say(l, Text::lab2_plus_minus, g(1.96 * se));
        }
        return c;
      },
      truth_number(&Lab2Truth::c1_deg_h_per_c));
  add_row(
      t, Text::lab2_q_temperature_terms, Text::lab2_m_criterion, kNoUnit,
      [l](const Lab2Run& r) {
        if (!r.result.systematic || r.result.systematic->criterion_degree < 0) {
          return missing_cell();
        }
        const int d = r.result.systematic->criterion_degree;
        return Lab2Cell{
            static_cast<double>(d), kNaN, kNaN,
            d == 0 ? say(l, Text::lab2_criterion_cell_none) : say(l, Text::lab2_criterion_cell, d)};
      },
      nullptr);
  add_row(
      t, Text::lab2_q_random_bias, Text::lab2_m_model_choice, kNoUnit,
      [l](const Lab2Run& r) {
        return Lab2Cell{kNaN, kNaN, kNaN, process_name(r.result.noise.random_bias_process, l)};
      },
      [l](const Lab2Truth& tr) { return process_name(tr.random_bias_process, l); });

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
      t, Text::lab2_q_k, Text::lab2_m_psd_k, Text::unit_deg_h_sqrt_s,
      [l](const Lab2Run& r) { return reading_cell(r.result.psd_readings.K, l); },
      truth_number(&Lab2Truth::K));
  add_row(
      t, Text::lab2_q_k, Text::lab2_m_allan_k, Text::unit_deg_h_sqrt_s,
      [l](const Lab2Run& r) { return reading_cell(r.result.adev_readings.K, l); },
      truth_number(&Lab2Truth::K));
  if (wiener || !gauss_markov) {
    add_row(t, Text::lab2_q_k, Text::lab2_m_fit, Text::unit_deg_h_sqrt_s,
            fit(&model::NoiseFitResult::K), truth_number(&Lab2Truth::K));
  }
  if (gauss_markov) {
    add_row(t, Text::lab2_q_gm_sigma, Text::lab2_m_fit, Text::unit_deg_h,
            fit(&model::NoiseFitResult::gm_sigma), truth_number(&Lab2Truth::gm_sigma));
    add_row(t, Text::lab2_q_gm_tc, Text::lab2_m_fit, Text::unit_s,
            fit(&model::NoiseFitResult::gm_tc), truth_number(&Lab2Truth::gm_tc));
  }

  add_row(
      t, Text::lab2_q_n, Text::lab2_m_psd_n, Text::unit_deg_h_sqrt_hz,
      [l](const Lab2Run& r) { return reading_cell(r.result.psd_readings.N, l); },
      truth_number(&Lab2Truth::N));
  add_row(
      t, Text::lab2_q_n, Text::lab2_m_allan_n, Text::unit_deg_h_sqrt_hz,
      [l](const Lab2Run& r) { return reading_cell(r.result.adev_readings.N, l); },
      truth_number(&Lab2Truth::N));
  add_row(t, Text::lab2_q_n, Text::lab2_m_fit, Text::unit_deg_h_sqrt_hz,
          fit(&model::NoiseFitResult::N), truth_number(&Lab2Truth::N));
  add_row(
      t, Text::lab2_q_arw, Text::lab2_m_arw, Text::unit_deg_sqrt_h,
      [](const Lab2Run& r) { return number_cell(r.result.arw_deg_sqrt_h); },
      [](const Lab2Truth& tr) { return fmt::format("{:.4g}", arw_deg_sqrt_h(tr.N)); });
  add_row(
      t, Text::lab2_q_bias_instability, Text::lab2_m_allan_minimum, Text::unit_deg_h,
      [l](const Lab2Run& r) { return bias_instability_cell(r.result, l); },
      truth_number(&Lab2Truth::bias_instability_deg_h));
  add_row(
      t, Text::lab2_q_eq17, Text::lab2_m_eq17, Text::unit_percent,
      [l](const Lab2Run& r) {
        const model::PsdAllanCheck& c = r.result.psd_allan;
        if (c.compared == 0) return missing_cell();
        const double percent = 100.0 * (c.worst_ratio - 1.0);
        return Lab2Cell{
            percent, kNaN, kNaN,
            say(l, Text::lab2_eq17_cell, percent, g(c.worst_tau_s), c.inside_95, c.compared)};
      },
      nullptr);
  add_row(
      t, Text::lab2_q_class, Text::lab2_m_class, kNoUnit,
      [l](const Lab2Run& r) {
        return Lab2Cell{kNaN, kNaN, kNaN, class_cell_text(r.result.verdict, l)};
      },
      [l](const Lab2Truth& tr) { return class_name(tr.accuracy_class, l); });
}

// ---- the written comparison ----------------------------------------------------------

/// "what: a -> b unit (+x %)" and the verdict on the 95 % intervals.
std::string change_text(std::string_view what, std::string_view unit, const model::ValueChange& c,
                        Language l) {
  const std::string text =
      say(l, Text::lab2_change, what, g(c.before), g(c.after), unit, 100.0 * c.relative);
  switch (c.verdict) {
    case model::Change::changed:
      return text + say(l, Text::lab2_change_changed);
    case model::Change::unchanged:
      return text + say(l, Text::lab2_change_unchanged);
    case model::Change::not_comparable:
      break;
  }
  return text + say(l, Text::lab2_change_not_comparable);
}

/// Beside a forced polynomial (the lab's quadratic), the criterion's verdict:
/// each temperature coefficient with its 95 % interval and whether it stands
/// out of the noise (|c_j| above sqrt(penalty) standard errors, the 1 %
/// level the criterion asks), and the degree the data alone would keep.
std::string temperature_verdict(const model::SystematicFit& s, Language l) {
  if (s.criterion_degree < 0 || s.degree_chosen || !std::isfinite(s.criterion_penalty)) return "";
  const double penalty = s.criterion_penalty;
  std::string text = " ";
  for (std::size_t j = 1; j < s.coefficients.size() && j < s.standard_errors.size(); ++j) {
    const double se = s.standard_errors[j];
    if (!(se > 0.0)) continue;
    const double t = std::fabs(s.coefficients[j]) / se;
    const std::string unit = j == 1 ? say(l, Text::unit_deg_h_per_degc)
                                    : say(l, Text::unit_deg_h_per_degc_k, static_cast<int>(j));
    text += say(l, Text::lab2_verdict_term, static_cast<int>(j), g(s.coefficients[j]), g(1.96 * se),
                unit, t,
                t * t > penalty ? say(l, Text::lab2_verdict_stands_out)
                                : say(l, Text::lab2_verdict_in_noise, std::sqrt(penalty)));
  }
  text += say(l, Text::lab2_verdict_degree, penalty, s.criterion_degree);
  if (s.criterion_degree == 0) text += say(l, Text::lab2_verdict_nothing_stands_out);
  return text;
}

std::vector<std::string> systematic_sentences(const model::SystematicChange& s,
                                              const model::SystematicFit* ramp, Language l) {
  std::string text = say(l, Text::lab2_temperature_spans, s.span_after_c, s.span_before_c);
  if (s.degree_after > 0) {
    text += say(l, Text::lab2_polynomial_moves, s.degree_after, g(s.polynomial_range_deg_h),
                s.range_over_bias_instability);
  } else {
    text += say(l, Text::lab2_no_dependence);
  }
  if (ramp) text += temperature_verdict(*ramp, l);
  std::string bias = say(l, Text::lab2_bias_at_mean, s.bias_before_deg_h, s.t_ref_before_c,
                         s.bias_after_deg_h, s.t_ref_after_c, g(s.bias_difference_deg_h));
  if (std::isfinite(s.wander_deg_h) && s.wander_deg_h > 0.0) {
    bias +=
        say(l, Text::lab2_bias_wander, s.bias_difference_deg_h / s.wander_deg_h, g(s.wander_deg_h));
  }
  bias += say(l, s.lab_constant_meaningful_before ? Text::lab2_bias_end
                                                  : Text::lab2_bias_constant_not_meaningful);
  return {text, bias};
}

std::string random_bias_sentence(const model::RunComparison& c, Language l) {
  if (c.process_before != c.process_after) {
    return say(l, Text::lab2_random_bias_differs, process_name(c.process_before, l),
               process_name(c.process_after, l));
  }
  const std::string text = say(l, Text::lab2_random_bias_both, process_name(c.process_before, l));
  if (c.random_walk) {
    return text + "; " +
           change_text(say(l, Text::lab2_k_symbol), say(l, Text::unit_deg_h_sqrt_s), *c.random_walk,
                       l);
  }
  if (c.gm_sigma && c.gm_tc) {
    return text + say(l, Text::lab2_random_bias_gm, g(c.gm_sigma->before), g(c.gm_sigma->after),
                      g(c.gm_tc->before), g(c.gm_tc->after));
  }
  return text + ".";
}

std::string changed_item_name(model::ChangedItem item, const model::RunComparison& c,
                              std::size_t& term, Language l) {
  switch (item) {
    case model::ChangedItem::white_noise:
      return say(l, Text::lab2_changed_white);
    case model::ChangedItem::bias_instability:
      return say(l, Text::lab2_changed_bias_instability);
    case model::ChangedItem::random_walk:
      return say(l, Text::lab2_changed_k);
    case model::ChangedItem::random_bias_process:
      return say(l, Text::lab2_changed_process);
    case model::ChangedItem::term:
      return say(l, Text::lab2_changed_term, to_string(c.terms_in_one_run[term++].term));
  }
  return "";
}

/// What the ramp changed, as a list: "the white noise, the bias instability and the K term".
std::string changed_list(const model::RunComparison& c, Language l) {
  std::string list;
  std::size_t term = 0;
  for (std::size_t k = 0; k < c.changed.size(); ++k) {
    list += (k == 0                      ? std::string()
             : k + 1 == c.changed.size() ? say(l, Text::lab2_and)
                                         : std::string(", ")) +
            changed_item_name(c.changed[k], c, term, l);
  }
  return list;
}

std::vector<std::string> compare_runs(const Lab2Run& constant, const Lab2Run& ramp, Language l) {
  const model::RunComparison c = model::compare_runs(constant.result, ramp.result);
  std::vector<std::string> out;
  if (c.systematic) {
    out = systematic_sentences(*c.systematic,
                               ramp.result.systematic ? &*ramp.result.systematic : nullptr, l);
  }
  if (c.white_noise) {
    out.push_back(change_text(say(l, Text::lab2_white_noise_fit), say(l, Text::unit_deg_h_sqrt_hz),
                              *c.white_noise, l));
  }
  out.push_back(change_text(say(l, Text::lab2_bias_instability_minimum), say(l, Text::unit_deg_h),
                            c.bias_instability, l));
  out.push_back(random_bias_sentence(c, l));
  for (const model::TermInOneRun& t : c.terms_in_one_run) {
    out.push_back(say(l, Text::lab2_only_one_run,
                      say(l, t.in_after ? Text::lab2_run_ramp : Text::lab2_run_constant),
                      terms_text({t.term}, l), g(t.value),
                      say(l, parameter_unit(static_cast<std::size_t>(t.term))),
                      t.term == NoiseTerm::ramp && t.in_after ? say(l, Text::lab2_ramp_not_removed)
                                                              : std::string()));
  }
  out.push_back(c.class_before == c.class_after
                    ? say(l, Text::lab2_class_same, class_name(c.class_before, l))
                    : say(l, Text::lab2_class_differs, class_name(c.class_before, l),
                          class_name(c.class_after, l)));
  if (c.changed.empty()) {
    out.push_back(say(l, Text::lab2_conclusion_unchanged));
  } else {
    out.push_back(say(l, Text::lab2_conclusion_changed, changed_list(c, l)));
  }
  return out;
}

/// The manual's readings of K beside the table's (docs/manual_notes.md): the
/// +1/2 line read at tau = 1 s is K / sqrt(3), the -2 line's level at 1 Hz
/// K / (2 pi). Empty when no run reads a K.
std::string k_convention(const Lab2Table& t) {
  const Language l = t.language;
  std::array<std::string, 2> allan{"-", "-"}, psd{"-", "-"};
  bool any = false;
  for (std::size_t k = 0; k < 2; ++k) {
    if (!t.runs[k]) continue;
    if (const auto& v = t.runs[k]->result.adev_readings.K) {
      allan[k] = g(*v / std::sqrt(3.0));
      any = true;
    }
    if (const auto& v = t.runs[k]->result.psd_readings.K) {
      psd[k] = g(*v / (2.0 * std::numbers::pi));
      any = true;
    }
  }
  if (!any) return "";
  return say(l, Text::lab2_k_convention, allan[0], allan[1], psd[0], psd[1]);
}

std::string class_text(const Lab2Table& t) {
  const Language l = t.language;
  std::string text = t.gyro + ":";
  bool first = true;
  for (std::size_t k = 0; k < 2; ++k) {
    if (!t.runs[k]) continue;
    const ClassVerdict& v = t.runs[k]->result.verdict;
    const Text decided = v.decided_by == ClassCriterion::both  ? Text::lab2_class_agree
                         : v.decided_by == ClassCriterion::arw ? Text::lab2_class_decided_arw
                                                               : Text::lab2_class_decided_bi;
    text += (first ? " " : ", ") +
            say(l, Text::lab2_class_run, class_name(v.accuracy_class, l),
                say(l, k == 0 ? Text::lab2_class_at_constant : Text::lab2_class_during_ramp),
                say(l, decided));
    first = false;
  }
  return text;
}

// ---- the closing part: two gyros compared, the review question, the conclusions --------

/// One quantity of two gyros: both values with their 95 % intervals.
struct GyroValues {
  Text what;
  Text unit;
  model::ValueChange values;  ///< "before" the first gyro, "after" the second
};

std::optional<GyroValues> fitted_pair(Text what, Text unit, const model::ParameterEstimate& a,
                                      const model::ParameterEstimate& b) {
  if (a.status != model::TermStatus::resolved || b.status != model::TermStatus::resolved) {
    return std::nullopt;
  }
  return GyroValues{
      what, unit,
      model::compare_values(a.value, a.ci95_low, a.ci95_high, b.value, b.ci95_low, b.ci95_high)};
}

GyroValues bias_instability_pair(const model::AnalysisResult& a, const model::AnalysisResult& b) {
  const auto [alo, ahi] = model::adev_interval_at(a.allan, a.bias_instability_tau_s);
  const auto [blo, bhi] = model::adev_interval_at(b.allan, b.bias_instability_tau_s);
  return {Text::lab2_bias_instability_minimum, Text::unit_deg_h,
          model::compare_values(a.bias_instability_deg_h, alo, ahi, b.bias_instability_deg_h, blo,
                                bhi)};
}

std::string gyro_value_sentence(const GyroValues& v, std::string_view first,
                                std::string_view second, Language l) {
  const std::string unit = say(l, v.unit);
  std::string text =
      say(l, Text::lab2_gyros_value, say(l, v.what), first, g(v.values.before), second,
          g(v.values.after), unit, second, v.values.after / v.values.before, first);
  switch (v.values.verdict) {
    case model::Change::changed:
      return text + say(l, Text::lab2_gyros_apart);
    case model::Change::unchanged:
      return text + say(l, Text::lab2_gyros_overlap);
    case model::Change::not_comparable:
      break;
  }
  return text + ".";
}

/// The ramp run's c1 and its standard error (NaN without a slope).
std::pair<double, double> ramp_slope(const Lab2Table& t) {
  if (!t.runs[1] || !t.runs[1]->result.systematic) return {kNaN, kNaN};
  const model::SystematicFit& s = *t.runs[1]->result.systematic;
  if (s.coefficients.size() < 2 || s.standard_errors.size() < 2) return {kNaN, kNaN};
  return {s.coefficients[1], s.standard_errors[1]};
}

/// Review question 18 for one gyro: its temperature law over the ramp and
/// what the ramp did to its noise.
std::string temperature_answer(const Lab2Table& t, Language l) {
  if (!t.runs[0] || !t.runs[1]) return "";
  const model::RunComparison c = model::compare_runs(t.runs[0]->result, t.runs[1]->result);
  std::string text = t.gyro + ": ";
  const auto [c1, se] = ramp_slope(t);
  const std::optional<model::SystematicFit>& ramp_fit = t.runs[1]->result.systematic;
  const double penalty = ramp_fit ? ramp_fit->criterion_penalty : kNaN;
  if (c.systematic && std::isfinite(c1) && se > 0.0 && std::isfinite(penalty)) {
    const double z = std::fabs(c1) / se;
    text += say(
        l, Text::lab2_answer_slope, c.systematic->span_after_c, g(c1), g(1.96 * se), z,
        say(l, z * z > penalty ? Text::lab2_answer_stands_out : Text::lab2_answer_not_separated),
        g(c.systematic->polynomial_range_deg_h), c.systematic->range_over_bias_instability);
  } else {
    text += say(l, Text::lab2_answer_no_slope);
  }
  if (c.changed.empty()) return text + say(l, Text::lab2_answer_noise_unchanged);
  return text + say(l, Text::lab2_answer_noise_changed, changed_list(c, l));
}

std::string file_of(const Lab2Table& t) {
  for (const Lab2Run* r : t.runs) {
    if (r != nullptr && !r->input.file_name.empty()) return r->input.file_name;
  }
  return "";
}

}  // namespace

Lab2Closing lab2_closing(std::span<const Lab2Table> tables) {
  Lab2Closing out;
  if (tables.empty()) return out;
  const Language l = tables.front().language;
  std::vector<const Lab2Table*> with_constant;
  for (const Lab2Table& t : tables) {
    if (t.runs[0]) with_constant.push_back(&t);
  }
  std::optional<GyroValues> widest;  // the quantity the gyros differ most in
  if (with_constant.size() >= 2) {
    const Lab2Table& a = *with_constant[0];
    const Lab2Table& b = *with_constant[1];
    const model::AnalysisResult& ra = a.runs[0]->result;
    const model::AnalysisResult& rb = b.runs[0]->result;
    out.heading = say(l, Text::lab2_gyros_heading, a.gyro, b.gyro);
    std::vector<GyroValues> pairs;
    if (auto n = fitted_pair(Text::lab2_white_noise_fit, Text::unit_deg_h_sqrt_hz, ra.noise.N,
                             rb.noise.N)) {
      pairs.push_back(*n);
    }
    pairs.push_back(bias_instability_pair(ra, rb));
    if (ra.noise.random_bias_process == rb.noise.random_bias_process) {
      if (auto k = fitted_pair(Text::lab2_q_k, Text::unit_deg_h_sqrt_s, ra.noise.K, rb.noise.K)) {
        pairs.push_back(*k);
      }
      if (auto s = fitted_pair(Text::lab2_q_gm_sigma, Text::unit_deg_h, ra.noise.gm_sigma,
                               rb.noise.gm_sigma)) {
        pairs.push_back(*s);
      }
    }
    for (const GyroValues& v : pairs) {
      out.comparison.push_back(gyro_value_sentence(v, a.gyro, b.gyro, l));
      const double spread = std::fabs(std::log(v.values.after / v.values.before));
      if (std::isfinite(spread) &&
          (!widest || spread > std::fabs(std::log(widest->values.after / widest->values.before)))) {
        widest = v;
      }
    }
    out.comparison.push_back(say(l, Text::lab2_gyros_process,
                                 process_name(ra.noise.random_bias_process, l), a.gyro,
                                 process_name(rb.noise.random_bias_process, l), b.gyro));
    out.comparison.push_back(say(l, Text::lab2_gyros_class, a.gyro,
                                 class_name(ra.verdict.accuracy_class, l), b.gyro,
                                 class_name(rb.verdict.accuracy_class, l)));
  }

  for (const Lab2Table& t : tables) {
    const std::string answer = temperature_answer(t, l);
    if (answer.empty()) continue;
    out.temperature_answer += (out.temperature_answer.empty() ? "" : " ") + answer;
  }
  if (!out.temperature_answer.empty()) {
    out.temperature_question = say(l, Text::lab2_question_18);
    out.temperature_answer += " " + say(l, Text::lab2_answer_general);
  }

  for (const Lab2Table& t : tables) out.conclusions.push_back(t.class_sentence + ".");
  if (widest && with_constant.size() >= 2) {
    const std::string& a = with_constant[0]->gyro;
    const std::string& b = with_constant[1]->gyro;
    out.conclusions.push_back(say(l, Text::lab2_conclusion_widest, a, b, say(l, widest->what),
                                  widest->values.after / widest->values.before, b, a));
  }
  if (with_constant.size() >= 2) {
    const auto [ca, sa] = ramp_slope(*with_constant[0]);
    const auto [cb, sb] = ramp_slope(*with_constant[1]);
    if (std::isfinite(ca) && std::isfinite(cb)) {
      const bool first = std::fabs(ca) > std::fabs(cb);
      out.conclusions.push_back(say(l, Text::lab2_conclusion_temperature,
                                    with_constant[first ? 0 : 1]->gyro,
                                    g(std::fabs(first ? ca : cb)), g(std::fabs(first ? cb : ca)),
                                    with_constant[first ? 1 : 0]->gyro));
    }
  }
  return out;
}

std::string_view to_string(Lab2Condition condition) {
  return text(Language::en, condition == Lab2Condition::constant ? Text::lab2_constant_temperature
                                                                 : Text::lab2_temperature_ramp);
}

std::string lab2_run_title(std::string_view gyro, Lab2Condition condition, std::string_view file,
                           std::string_view channel, Language language) {
  const Text name = condition == Lab2Condition::constant ? Text::lab2_constant_temperature
                                                         : Text::lab2_temperature_ramp;
  return say(language, Text::lab2_run_title, gyro, say(language, name), file, channel);
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

std::vector<Lab2Table> lab2_tables(std::span<const Lab2Run> runs, Language language) {
  std::vector<Lab2Table> tables;
  for (const Lab2Run& run : runs) {
    auto it = std::find_if(tables.begin(), tables.end(),
                           [&](const Lab2Table& t) { return t.gyro == run.gyro; });
    if (it == tables.end()) {
      tables.push_back({});
      tables.back().gyro = run.gyro;
      tables.back().language = language;
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
    if (t.runs[0] && t.runs[1]) t.comparison = compare_runs(*t.runs[0], *t.runs[1], language);
  }
  return tables;
}

std::string lab2_tables_markdown(std::span<const Lab2Table> tables) {
  std::string md;
  for (const Lab2Table& t : tables) {
    const Language l = t.language;
    const std::string file = file_of(t);
    md += fmt::format("## {}{}\n\n", t.gyro, file.empty() ? "" : " (" + file + ")");
    md += fmt::format("| {} | {} | {} | {} |", say(l, Text::lab2_col_quantity),
                      say(l, Text::lab2_col_method), say(l, Text::lab2_constant_temperature),
                      say(l, Text::lab2_temperature_ramp));
    if (t.has_truth) md += " " + say(l, Text::lab2_col_answer_key) + " |";
    md += " " + say(l, Text::unit) +
          (t.has_truth ? " |\n|---|---|---|---|---|---|\n" : " |\n|---|---|---|---|---|\n");
    for (const Lab2Row& row : t.rows) {
      md += fmt::format("| {} | {} | {} | {} |", row.quantity, row.method, row.runs[0].text,
                        row.runs[1].text);
      if (t.has_truth) md += " " + (row.truth.empty() ? std::string("-") : row.truth) + " |";
      md += " " + row.unit + " |\n";
    }
    md += "\n**" + say(l, Text::lab2_accuracy_class_line, t.class_sentence) + "**\n\n" +
          say(l, Text::lab2_scale_factor_note) + "\n\n";
    if (const std::string k = k_convention(t); !k.empty()) md += k + "\n\n";
    if (!t.comparison.empty()) {
      md += say(l, Text::lab2_ramp_changed) + ":\n\n";
      for (const std::string& s : t.comparison) md += "- " + s + "\n";
      md += "\n";
    }
  }
  const Lab2Closing closing = lab2_closing(tables);
  if (!closing.heading.empty()) {
    md += "## " + closing.heading + "\n\n";
    for (const std::string& s : closing.comparison) md += "- " + s + "\n";
    md += "\n";
  }
  if (!closing.temperature_question.empty()) {
    md += "### " + closing.temperature_question + "\n\n" + closing.temperature_answer + "\n\n";
  }
  if (!closing.conclusions.empty()) {
    md += "## " + say(tables.front().language, Text::lab2_conclusions) + "\n\n";
    for (const std::string& s : closing.conclusions) md += "- " + s + "\n";
    md += "\n";
  }
  return md;
}

std::string lab2_tables_html(std::span<const Lab2Table> tables) {
  std::string h;
  for (const Lab2Table& t : tables) {
    const Language l = t.language;
    const std::string file = file_of(t);
    h += "<section>\n<h2>" +
         say(l, Text::lab2_table_heading, html_escape(t.gyro),
             file.empty() ? "" : " <small>(" + html_escape(file) + ")</small>") +
         "</h2>\n";
    h += "<table class=\"lab2\">\n<tr>" + th(say(l, Text::lab2_col_quantity)) +
         th(say(l, Text::lab2_col_method)) + th(say(l, Text::lab2_constant_temperature)) +
         th(say(l, Text::lab2_temperature_ramp));
    if (t.has_truth) h += th(say(l, Text::lab2_col_answer_key));
    h += th(say(l, Text::unit)) + "</tr>\n";
    for (const Lab2Row& row : t.rows) {
      h += "<tr>" + td(row.quantity) + td(row.method) + td(row.runs[0].text) + td(row.runs[1].text);
      if (t.has_truth) h += "<td class=\"truth\">" + html_escape(row.truth) + "</td>";
      h += td(row.unit) + "</tr>\n";
    }
    h += "</table>\n<p class=\"verdict\">" +
         html_escape(say(l, Text::lab2_accuracy_class_line, t.class_sentence)) +
         "</p>\n<p class=\"note\">" + html_escape(say(l, Text::lab2_scale_factor_note)) + "</p>\n";
    if (const std::string k = k_convention(t); !k.empty()) {
      h += "<p class=\"note\">" + html_escape(k) + "</p>\n";
    }
    if (!t.comparison.empty()) {
      h += "<h3>" + html_escape(say(l, Text::lab2_ramp_changed)) + "</h3>\n<ul>\n";
      for (const std::string& s : t.comparison) h += "<li>" + html_escape(s) + "</li>\n";
      h += "</ul>\n";
    }
    h += "</section>\n";
  }
  const Lab2Closing closing = lab2_closing(tables);
  auto list = [](const std::vector<std::string>& items) {
    std::string u = "<ul>\n";
    for (const std::string& s : items) u += "<li>" + html_escape(s) + "</li>\n";
    return u + "</ul>\n";
  };
  if (!closing.heading.empty()) {
    h += "<section id=\"comparison\">\n<h2>" + html_escape(closing.heading) + "</h2>\n" +
         list(closing.comparison) + "</section>\n";
  }
  if (!closing.temperature_question.empty()) {
    h += "<section id=\"temperature-question\">\n<h3>" + html_escape(closing.temperature_question) +
         "</h3>\n<p>" + html_escape(closing.temperature_answer) + "</p>\n</section>\n";
  }
  if (!closing.conclusions.empty()) {
    h += "<section id=\"conclusions\">\n<h2>" +
         html_escape(say(tables.front().language, Text::lab2_conclusions)) + "</h2>\n" +
         list(closing.conclusions) + "</section>\n";
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
  out.tables = lab2_tables(runs, options.language);

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

  std::string preface = title_block_html(options.title_block, options.language) + "<p>" +
                        html_escape(intro) + "</p>\n";
  if (out.plots_skipped) preface += "<p class=\"warn\">" + html_escape(out.plots_note) + "</p>\n";
  preface += lab2_tables_html(out.tables);
  out.html = html_document(out.runs, title, preface, options.language);

  out.markdown_summary =
      fmt::format("# {}\n\n{}{}\n\n", title,
                  title_block_markdown(options.title_block, options.language), intro) +
      lab2_tables_markdown(out.tables);
  if (out.plots_skipped) out.markdown_summary += out.plots_note + "\n\n";
  out.markdown = out.markdown_summary;
  for (const Report& r : out.runs) out.markdown += r.markdown + "\n";
  // The CSV is for programs: its words stay English whatever the page's language.
  out.csv = options.language == Language::en ? lab2_tables_csv(out.tables)
                                             : lab2_tables_csv(lab2_tables(runs, Language::en));
  return out;
}

}  // namespace foglab::report
