// foglab — noise-model fit, step 5: the status and one-sided bound of each
// term left out of the chosen model (noise_fit_internal.h).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "noise_fit_internal.h"

namespace foglab::model::detail {
namespace {

// One-sided 95 % point of chi-square with one degree of freedom (1.645^2).
constexpr double kOneSided95 = 2.705543454095404;

// The one-sided 95 % upper bound of a term left out of `chosen`: the
// coefficient at which forcing the term in raises the deviance by
// kOneSided95 * scale. NaN for the Gauss-Markov term (its bound depends on
// Tc without limit).
double upper_bound(const Points& p, const SubsetFit& chosen, NoiseTerm term, double scale) {
  if (term == NoiseTerm::gauss_markov) return kNaN;
  const double target = chosen.deviance + kOneSided95 * scale;
  auto dev = [&](double c) {
    return fit_subset(p, chosen.terms, chosen.tc, FixedTerm{term, c}, NonPositive::drop_term)
        .deviance;
  };
  double hi = 0.0;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    hi = std::max(hi, p.y[i] / p.basis_at(term, i, chosen.tc));
  }
  double lo = hi * 1e-12;
  for (int grow = 0; grow < 20 && dev(hi) < target; ++grow) hi *= 10.0;
  if (dev(hi) < target) return kNaN;
  for (int it = 0; it < 60 && hi / lo > 1.0 + 1e-6; ++it) {
    const double mid = std::sqrt(lo * hi);
    (dev(mid) < target ? lo : hi) = mid;
  }
  return std::sqrt(hi);
}

}  // namespace

// A term left out is `upper_bound` when the data pull it above zero (the
// enlarged model is feasible) and `absent` when they pull it to zero. Its
// bound is where the deviance's allowance, scaled by the term's sandwich
// ratio in the enlarged model at zero (its column d mu/d c beside the
// chosen model's gradients), is used up.
void bound_left_out_terms(const ChosenModel& chosen, const NoiseFitOptions& options,
                          NoiseFitResult& r) {
  const Points& pc = chosen.points;
  const SubsetFit& f = *chosen.fit;
  std::vector<NoiseTerm> order;
  const Eigen::MatrixXd gradients = log_parameter_gradients(pc, f, order);
  const Eigen::MatrixXd chosen_r =
      chosen.covariance ? standardised(*chosen.covariance, pc, f) : Eigen::MatrixXd();
  for (NoiseTerm t : kNoiseTerms) {
    if (f.terms.contains(t)) continue;
    const NoiseTermSet enlarged = f.terms.with(t);
    TermStatus status = TermStatus::absent;
    if (admissible(enlarged, options) &&
        enlarged.parameter_count() < static_cast<int>(pc.y.size())) {
      if (fit_subset_profiled(pc, enlarged).feasible) status = TermStatus::upper_bound;
    }
    double bound_scale = chosen.dispersion * options.correlation_inflation;
    if (chosen.covariance && t != NoiseTerm::gauss_markov) {
      Eigen::MatrixXd a(gradients.rows(), gradients.cols() + 1);
      a.leftCols(gradients.cols()) = gradients;
      for (std::size_t i = 0; i < pc.y.size(); ++i) {
        a(static_cast<Eigen::Index>(i), gradients.cols()) =
            std::sqrt(0.5 * pc.v[i]) * pc.basis_at(t, i, f.tc) / f.mu[i];
      }
      bound_scale = chosen.dispersion * sandwich_ratios(a, chosen_r)(gradients.cols());
    }
    const double ub = upper_bound(pc, f, t, bound_scale);
    // A one-sided interval [0, bound]: the term may be there, this small.
    const bool bounded = std::isfinite(ub);
    const ParameterEstimate e = {status == TermStatus::upper_bound ? ub : kNaN,
                                 bounded ? 0.0 : kNaN, bounded ? ub : kNaN, ub, status};
    if (t == NoiseTerm::gauss_markov) {
      r.gm_sigma = e;
      r.gm_tc = {kNaN, kNaN, kNaN, kNaN, status};
    } else {
      r.estimate(kNoiseParameters[static_cast<std::size_t>(t)]) = e;
    }
  }
}

}  // namespace foglab::model::detail
