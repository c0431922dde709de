// foglab — two analyses of one gyro compared (run_comparison.h).
#include "foglab/model/run_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

// The polynomial's range [deg/h] over the temperatures it was fitted on.
double polynomial_range(const SystematicFit& s) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  constexpr int kSteps = 200;
  for (int k = 0; k <= kSteps; ++k) {
    const double t = s.temperature_min_c + (s.temperature_max_c - s.temperature_min_c) * k / kSteps;
    double v = 0.0, p = 1.0;
    for (std::size_t j = 1; j < s.coefficients.size(); ++j) {
      p *= t - s.t_ref_c;
      v += s.coefficients[j] * p;
    }
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return hi - lo;
}

SystematicChange systematic_change(const AnalysisResult& a, const AnalysisResult& b) {
  const SystematicFit& sa = *a.systematic;
  const SystematicFit& sb = *b.systematic;
  SystematicChange c;
  c.span_before_c = sa.temperature_span_c;
  c.span_after_c = sb.temperature_span_c;
  c.degree_after = sb.degree;
  if (sb.coefficients.size() > 1) {
    c.polynomial_range_deg_h = polynomial_range(sb);
    c.range_over_bias_instability = c.polynomial_range_deg_h / b.bias_instability_deg_h;
  }
  c.bias_before_deg_h = sa.bias_deg_h;
  c.bias_after_deg_h = sb.bias_deg_h;
  c.t_ref_before_c = sa.t_ref_c;
  c.t_ref_after_c = sb.t_ref_c;
  c.bias_difference_deg_h = std::abs(sb.bias_deg_h - sa.bias_deg_h);
  c.wander_deg_h = std::sqrt(allan_variance(b.noise.model, 0.5 * b.duration_s));
  c.lab_constant_meaningful_before = sa.lab_constant_meaningful;
  return c;
}

ValueChange estimates(const ParameterEstimate& a, const ParameterEstimate& b) {
  return compare_values(a.value, a.ci95_low, a.ci95_high, b.value, b.ci95_low, b.ci95_high);
}

ValueChange bias_instability(const AnalysisResult& a, const AnalysisResult& b) {
  const auto [alo, ahi] = adev_interval_at(a.allan, a.bias_instability_tau_s);
  const auto [blo, bhi] = adev_interval_at(b.allan, b.bias_instability_tau_s);
  return compare_values(a.bias_instability_deg_h, alo, ahi, b.bias_instability_deg_h, blo, bhi);
}

}  // namespace

std::string_view to_string(Change change) {
  switch (change) {
    case Change::unchanged:
      return "unchanged";
    case Change::changed:
      return "changed";
    case Change::not_comparable:
      return "not_comparable";
  }
  return "?";
}

ValueChange compare_values(double before, double before_low, double before_high, double after,
                           double after_low, double after_high) {
  ValueChange c{before,    before_low, before_high,          after,
                after_low, after_high, after / before - 1.0, Change::not_comparable};
  if (std::isfinite(before_low) && std::isfinite(before_high) && std::isfinite(after_low) &&
      std::isfinite(after_high)) {
    const bool overlap = std::max(before_low, after_low) <= std::min(before_high, after_high);
    c.verdict = overlap ? Change::unchanged : Change::changed;
  }
  return c;
}

std::pair<double, double> adev_interval_at(const stats::AllanResult& allan, double tau_s) {
  std::size_t best = allan.tau_s.size();
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < allan.tau_s.size(); ++i) {
    const double d = std::abs(std::log(allan.tau_s[i] / tau_s));
    if (d < best_distance) {
      best_distance = d;
      best = i;
    }
  }
  if (best == allan.tau_s.size() || best >= allan.ci95_low.size() ||
      best >= allan.ci95_high.size()) {
    return {kNaN, kNaN};
  }
  return {allan.ci95_low[best], allan.ci95_high[best]};
}

RunComparison compare_runs(const AnalysisResult& a, const AnalysisResult& b) {
  RunComparison r;
  if (a.systematic && b.systematic) r.systematic = systematic_change(a, b);
  if (a.noise.N.status == TermStatus::resolved && b.noise.N.status == TermStatus::resolved) {
    r.white_noise = estimates(a.noise.N, b.noise.N);
    if (r.white_noise->verdict == Change::changed) r.changed.push_back(ChangedItem::white_noise);
  }
  r.bias_instability = bias_instability(a, b);
  if (r.bias_instability.verdict == Change::changed) {
    r.changed.push_back(ChangedItem::bias_instability);
  }
  r.process_before = a.noise.random_bias_process;
  r.process_after = b.noise.random_bias_process;
  if (r.process_before != r.process_after) {
    r.changed.push_back(ChangedItem::random_bias_process);
  } else if (r.process_before == RandomBiasProcess::wiener) {
    r.random_walk = estimates(a.noise.K, b.noise.K);
    if (r.random_walk->verdict == Change::changed) r.changed.push_back(ChangedItem::random_walk);
  } else if (r.process_before == RandomBiasProcess::gauss_markov) {
    r.gm_sigma = estimates(a.noise.gm_sigma, b.noise.gm_sigma);
    r.gm_tc = estimates(a.noise.gm_tc, b.noise.gm_tc);
  }
  for (const NoiseTerm term : {NoiseTerm::ramp, NoiseTerm::quantisation}) {
    const NoiseParameter& p = kNoiseParameters[static_cast<std::size_t>(term)];
    const bool in_a = a.noise.estimate(p).status == TermStatus::resolved;
    const bool in_b = b.noise.estimate(p).status == TermStatus::resolved;
    if (in_a == in_b) continue;
    r.terms_in_one_run.push_back({term, in_b, (in_b ? b : a).noise.estimate(p).value});
    r.changed.push_back(ChangedItem::term);
  }
  r.class_before = a.verdict.accuracy_class;
  r.class_after = b.verdict.accuracy_class;
  return r;
}

}  // namespace foglab::model
