// foglab — noise-model fit, steps 4 and 6: the 95 % intervals of the chosen
// terms, and their widening over the candidates the criterion can hardly
// tell from the chosen one (noise_fit_internal.h; the method in
// include/foglab/model/noise_fit.h).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "allan_covariance.h"
#include "foglab/core/numeric.h"
#include "noise_fit_internal.h"

namespace foglab::model::detail {
namespace {

// The chi-square(1) 95 % point (kZ95 squared; core/numeric.h).
constexpr double kChi2_95 = 3.841458820694124;

// How closely a near candidate must pin a random-bias coefficient (its 95 %
// interval within this factor of the value either way) for its interval to
// bound the process the chosen model leaves out.
constexpr double kClosedRatio = 10.0;

// The columns of A that carry information: a coefficient fitted at
// practically zero (a candidate that is really its subset) has a column of
// zeros, and would make the whole information singular.
std::vector<Eigen::Index> informed_columns(const Eigen::MatrixXd& a) {
  const Eigen::VectorXd norm = a.colwise().norm();
  const double largest = norm.size() > 0 ? norm.maxCoeff() : 0.0;
  std::vector<Eigen::Index> informed;
  for (Eigen::Index j = 0; j < norm.size(); ++j) {
    if (norm(j) > 1e-8 * largest) informed.push_back(j);
  }
  return informed;
}

// The inverse of the information A'A over the informed columns; a direction
// the data do not inform has no finite variance (not zero).
Eigen::MatrixXd inverse_information(const Eigen::MatrixXd& a) {
  const Eigen::Index k = a.cols();
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Constant(k, k, kInf);
  const std::vector<Eigen::Index> informed = informed_columns(a);
  if (informed.empty()) return inverse;
  const Eigen::MatrixXd sub = a(Eigen::all, informed);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(sub.transpose() * sub);
  if (!lu.isInvertible()) return inverse;
  inverse(informed, informed) = lu.inverse();
  return inverse;
}

// Profile-likelihood 95 % intervals of the Gauss-Markov pair. When the hump
// of the Allan variance is only partly inside the record the likelihood of
// (sigma, Tc) is far from quadratic (a long ridge along sigma^2/Tc = K^2/2
// towards the random walk), and the Fisher interval is too short. Tc's
// interval is the set where the deviance profiled over the other
// parameters stays within chi2(1, 0.95) * scale of its minimum; sigma's is
// the union, over the Tc in that set, of its conditional interval (the
// projection of the joint confidence region). An end that the data do not
// close (the process indistinguishable from a random walk) is infinite.
struct GaussMarkovIntervals {
  double sigma_low = kNaN, sigma_high = kNaN, tc_low = kNaN, tc_high = kNaN;
};

GaussMarkovIntervals gauss_markov_intervals(const Points& p, const SubsetFit& chosen,
                                            double tc_scale, double sigma_scale) {
  const double tc_allowed = kChi2_95 * tc_scale, sigma_allowed = kChi2_95 * sigma_scale;
  // Twelve points per decade from well below the shortest tau to far beyond
  // the longest, and the optimum itself.
  const double lo = std::log(std::min(p.tau.front() * 0.1, chosen.tc));
  const double hi = std::log(std::max(p.tau.back() * 1000.0, chosen.tc));
  const int steps = static_cast<int>(std::ceil((hi - lo) / std::log(10.0) * 12.0));
  std::vector<double> ln_tc;
  for (int s = 0; s <= steps; ++s) ln_tc.push_back(lo + (hi - lo) * s / steps);
  ln_tc.push_back(std::log(chosen.tc));
  std::sort(ln_tc.begin(), ln_tc.end());
  std::vector<double> rise(ln_tc.size());  // profile deviance above the minimum
  GaussMarkovIntervals r;
  r.sigma_low = std::sqrt(chosen.squared(NoiseTerm::gauss_markov));
  r.sigma_high = r.sigma_low;
  for (std::size_t s = 0; s < ln_tc.size(); ++s) {
    const SubsetFit f = fit_subset(p, chosen.terms, std::exp(ln_tc[s]));
    rise[s] = f.feasible ? f.deviance - chosen.deviance : kInf;
    if (!(rise[s] <= sigma_allowed)) continue;
    // Conditional interval of ln sigma^2 at this Tc: the quadratic
    // deviance reaches the threshold at +-sqrt((allowed - rise) * variance).
    std::vector<NoiseTerm> order;
    const Eigen::MatrixXd cov =
        inverse_information(log_parameter_gradients(p, f, order, TcColumn::without));
    const auto j = static_cast<Eigen::Index>(
        std::find(order.begin(), order.end(), NoiseTerm::gauss_markov) - order.begin());
    const double half = std::sqrt(std::max(0.0, (sigma_allowed - rise[s]) * cov(j, j)));
    const double sigma = std::sqrt(f.squared(NoiseTerm::gauss_markov));
    r.sigma_low = std::min(r.sigma_low, sigma * std::exp(-0.5 * half));
    r.sigma_high = std::max(r.sigma_high, sigma * std::exp(0.5 * half));
  }
  // The ends of the Tc region within `allowed`: where the rise crosses it
  // either side of the optimum (linear in ln Tc between grid points); 0 and
  // infinite when it never does.
  const auto best = static_cast<std::size_t>(
      std::find(ln_tc.begin(), ln_tc.end(), std::log(chosen.tc)) - ln_tc.begin());
  auto ends = [&](double allowed) {
    auto crossing = [&](std::size_t inside, std::size_t outside) {
      const double e0 = rise[inside] - allowed, e1 = rise[outside] - allowed;
      const double w = std::isfinite(e1) ? e0 / (e0 - e1) : 0.0;
      return std::exp(ln_tc[inside] + w * (ln_tc[outside] - ln_tc[inside]));
    };
    std::pair<double, double> e{0.0, kInf};
    for (std::size_t s = best; s > 0; --s) {
      if (!(rise[s - 1] <= allowed)) {
        e.first = crossing(s, s - 1);
        break;
      }
    }
    for (std::size_t s = best; s + 1 < ln_tc.size(); ++s) {
      if (!(rise[s + 1] <= allowed)) {
        e.second = crossing(s, s + 1);
        break;
      }
    }
    return e;
  };
  std::tie(r.tc_low, r.tc_high) = ends(tc_allowed);
  // sigma's region is open where its Tc region is.
  const auto [sigma_tc_low, sigma_tc_high] = ends(sigma_allowed);
  if (!std::isfinite(sigma_tc_high)) r.sigma_high = kInf;
  if (sigma_tc_low == 0.0) r.sigma_low = 0.0;
  return r;
}

// The 95 % intervals of the terms of `f` (in kNoiseTerms order, the Gauss-
// Markov term's for sigma; NaN for terms not in f) and of Tc.
// Neighbouring tau estimates share most of their data, so the information
// of the independent-points likelihood overstates what the points hold:
// each parameter's variance is scaled by its sandwich ratio under the
// points' `covariance` (point_covariance()) and by the fit's `dispersion`.
// Without the averaging factors that covariance is unknown (null) and the
// fixed `inflation` stands in. The Gauss-Markov pair comes from its
// profile, the deviance's allowance scaled the same way (sigma^2's ratio
// for sigma, Tc's for Tc).
struct Intervals {
  std::array<std::pair<double, double>, kNoiseTerms.size()> term;
  std::pair<double, double> tc{kNaN, kNaN};
};

Intervals intervals_of(const Points& p, const SubsetFit& f, const Eigen::MatrixXd* covariance,
                       double dispersion, double inflation) {
  Intervals r;
  r.term.fill({kNaN, kNaN});
  std::vector<NoiseTerm> order;
  const Eigen::MatrixXd gradients = log_parameter_gradients(p, f, order);
  const Eigen::MatrixXd cov = inverse_information(gradients);
  const Eigen::VectorXd ratio = covariance
                                    ? sandwich_ratios(gradients, standardised(*covariance, p, f))
                                    : Eigen::VectorXd::Constant(gradients.cols(), inflation);
  auto scale_of = [&](Eigen::Index j) { return dispersion * ratio(j); };
  for (std::size_t j = 0; j < order.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    const auto t = static_cast<std::size_t>(order[j]);
    if (order[j] == NoiseTerm::gauss_markov) {
      const GaussMarkovIntervals g =
          gauss_markov_intervals(p, f, scale_of(gradients.cols() - 1), scale_of(jj));
      r.term[t] = {g.sigma_low, g.sigma_high};
      r.tc = {g.tc_low, g.tc_high};
      continue;
    }
    const double value = std::sqrt(f.c[t]);
    // ln(coefficient) = ln(c)/2
    const double sd = 0.5 * std::sqrt(std::max(0.0, cov(jj, jj) * scale_of(jj)));
    r.term[t] = {value * std::exp(-kZ95 * sd), value * std::exp(kZ95 * sd)};
  }
  return r;
}

// Whether a term of `f` carries under 1 % of its mean at every point: the
// candidate is then its own subset with a coefficient at the boundary,
// where the log-scale information of the others is meaningless (the
// near-zero term may trade against any of them).
bool holds_a_negligible_term(const Points& p, const SubsetFit& f) {
  for (NoiseTerm t : kNoiseTerms) {
    if (!f.terms.contains(t)) continue;
    double share = 0.0;
    for (std::size_t i = 0; i < p.y.size(); ++i) {
      share = std::max(share, f.squared(t) * p.basis_at(t, i, f.tc) / f.mu[i]);
    }
    if (share < 0.01) return true;
  }
  return false;
}

const Eigen::MatrixXd* covariance_of(const ChosenModel& chosen) {
  return chosen.covariance ? &*chosen.covariance : nullptr;
}

}  // namespace

// The exact covariance for Gaussian noise (allan_covariance.h) of the
// undetrended model (the fit's coefficients are its). Removing a
// polynomial scales each estimate roughly as it scales its mean, so point
// i's row and column are scaled by the ratio of the detrended mean to the
// undetrended one. A rate ramp is deterministic and has no such
// covariance, but a fitted one stands for a slow drift the record cannot
// tell from a ramp: its share of each point gets the variance the fit
// assumes (2 mu_R^2/v) and the correlation of the steepest noise modelled,
// a random walk (cross terms with the other terms left out).
Eigen::MatrixXd point_covariance(const Points& p, const SubsetFit& f) {
  const double tau0 = p.tau.front() / static_cast<double>(p.factors.front());
  NoiseModel model = to_model(f);
  const double ramp = model.R;
  model.R = 0.0;
  Eigen::MatrixXd c = pooled_allan_variance_covariance(model, tau0, p.factors, p.segment_points);
  const auto n = c.rows();
  Eigen::VectorXd scale(n);
  // A point with a share s of the gap-free record's terms: its variance
  // 1/s times theirs, its covariances 1/sqrt(s s').
  if (!p.term_share.empty()) {
    for (Eigen::Index i = 0; i < n; ++i)
      scale(i) = 1.0 / std::sqrt(p.term_share[static_cast<std::size_t>(i)]);
    c = scale.asDiagonal() * c * scale.asDiagonal();
  }
  // A point whose terms spread more than the model's noise says
  // (Points::edf_reduction r): its variance r times the model's.
  if (!p.edf_reduction.empty()) {
    for (Eigen::Index i = 0; i < n; ++i)
      scale(i) = std::sqrt(p.edf_reduction[static_cast<std::size_t>(i)]);
    c = scale.asDiagonal() * c * scale.asDiagonal();
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double undetrended = allan_variance(model, p.tau[k]);
    const double detrended = f.mu[k] - ramp * ramp * p.basis_at(NoiseTerm::ramp, k, f.tc);
    scale(i) = undetrended > 0 ? detrended / undetrended : 1.0;
  }
  c = scale.asDiagonal() * c * scale.asDiagonal();
  if (ramp > 0) {
    const Eigen::MatrixXd walk =
        pooled_allan_variance_covariance({.K = 1.0}, tau0, p.factors, p.segment_points);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double share = ramp * ramp * p.basis_at(NoiseTerm::ramp, k, f.tc);  // mu_R
      scale(i) = std::sqrt(2.0 / p.v[k]) * share / std::sqrt(std::max(walk(i, i), 1e-300));
    }
    c += scale.asDiagonal() * walk * scale.asDiagonal();
  }
  return c;
}

Eigen::MatrixXd log_parameter_gradients(const Points& p, const SubsetFit& f,
                                        std::vector<NoiseTerm>& order, TcColumn tc) {
  order.clear();
  for (NoiseTerm t : kNoiseTerms) {
    if (f.terms.contains(t)) order.push_back(t);
  }
  const bool gm = tc == TcColumn::with && f.terms.contains(NoiseTerm::gauss_markov);
  const Eigen::Index k = static_cast<Eigen::Index>(order.size()) + (gm ? 1 : 0);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(p.y.size()), k);
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const double w = std::sqrt(0.5 * p.v[i]) / f.mu[i];
    for (std::size_t j = 0; j < order.size(); ++j) {
      a(row, static_cast<Eigen::Index>(j)) =
          w * f.squared(order[j]) * p.basis_at(order[j], i, f.tc);
    }
    if (gm) {
      const double h = 1e-5;
      const double up = p.basis_at(NoiseTerm::gauss_markov, i, f.tc * std::exp(h));
      const double down = p.basis_at(NoiseTerm::gauss_markov, i, f.tc * std::exp(-h));
      a(row, k - 1) = w * f.squared(NoiseTerm::gauss_markov) * (up - down) / (2.0 * h);
    }
  }
  return a;
}

// The sandwich (robust) covariance J^-1 (A'RA) J^-1, J = A'A, of the
// estimator that treats the points as independent (White, "Maximum
// likelihood estimation of misspecified models", Econometrica 50, 1982; for
// the wavelet variance, Guerrier et al., JASA 108, 2013), divided by J^-1 on
// the diagonal, over the informed columns. 1 where J is singular.
Eigen::VectorXd sandwich_ratios(const Eigen::MatrixXd& a, const Eigen::MatrixXd& correlation) {
  Eigen::VectorXd ratio = Eigen::VectorXd::Ones(a.cols());
  const std::vector<Eigen::Index> informed = informed_columns(a);
  if (informed.empty()) return ratio;
  const Eigen::MatrixXd sub = a(Eigen::all, informed);
  const Eigen::MatrixXd naive = inverse_information(sub);
  if (!naive.allFinite()) return ratio;
  const Eigen::MatrixXd robust = naive * (sub.transpose() * correlation * sub) * naive;
  for (std::size_t j = 0; j < informed.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    if (naive(jj, jj) > 0) ratio(informed[j]) = robust(jj, jj) / naive(jj, jj);
  }
  return ratio;
}

// The covariance divided by the standard deviations the fit's weights
// assume, sqrt(2/v_i) mu_i (its diagonal shows where the edf of the
// dominant noise type misstate a mixture's variance).
Eigen::MatrixXd standardised(const Eigen::MatrixXd& covariance, const Points& p,
                             const SubsetFit& f) {
  Eigen::VectorXd z(covariance.rows());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    z(i) = std::sqrt(0.5 * p.v[k]) / f.mu[k];
  }
  return z.asDiagonal() * covariance * z.asDiagonal();
}

ChosenModel chosen_model(const Points& p, const SubsetFit& chosen, double dispersion) {
  ChosenModel c;
  c.points = p;
  c.points.v = chosen.v;
  c.fit = &chosen;
  c.dispersion = dispersion;
  if (!c.points.factors.empty()) c.covariance = point_covariance(c.points, chosen);
  return c;
}

void set_chosen_intervals(const ChosenModel& chosen, const NoiseFitOptions& options,
                          NoiseFitResult& r) {
  const SubsetFit& f = *chosen.fit;
  const Intervals own = intervals_of(chosen.points, f, covariance_of(chosen), chosen.dispersion,
                                     options.correlation_inflation);
  for (const NoiseParameter& parameter : kNoiseParameters) {
    const NoiseTerm t = parameter.term;
    if (!f.terms.contains(t)) continue;
    const bool tc = parameter.value == &NoiseModel::gm_tc;
    const auto [low, high] = tc ? own.tc : own.term[static_cast<std::size_t>(t)];
    r.estimate(parameter) = {r.model.*parameter.value, low, high, kNaN, TermStatus::resolved};
  }
}

// Each reported interval becomes the union over the near candidates: an
// interval conditional on the selected model alone misses the truth
// whenever the selection dropped a term that shifts the others (a small
// flicker term left out pulls a Gauss-Markov sigma or a random walk up by
// 15-30 %; docs/validation.md). A chosen term's interval is the union over
// the candidates that hold it; a random-bias term left out (K, or the
// Gauss-Markov pair) gets the largest upper end as its bound (Tc the union
// of the intervals). The estimates, the statuses and the decision stay
// those of the chosen model.
void widen_over_near_candidates(const Points& p, const ChosenModel& chosen,
                                std::span<const SubsetFit> fits, const NoiseFitOptions& options,
                                NoiseFitResult& r) {
  const double best = criterion(*chosen.fit, options.penalty);
  for (std::size_t k = 1; k < fits.size(); ++k) {
    const SubsetFit& f = fits[k];
    if (!(criterion(f, options.penalty) - best <= options.interval_window)) break;  // sorted
    if (holds_a_negligible_term(p, f)) continue;
    Points q = p;
    q.v = f.v;
    const Intervals other =
        intervals_of(q, f, covariance_of(chosen), chosen.dispersion, options.correlation_inflation);
    for (const NoiseParameter& parameter : kNoiseParameters) {
      const NoiseTerm t = parameter.term;
      if (!f.terms.contains(t) || parameter.value == &NoiseModel::gm_tc) continue;
      ParameterEstimate& e = r.estimate(parameter);
      const auto [low, high] = other.term[static_cast<std::size_t>(t)];
      if (t == NoiseTerm::gauss_markov) {  // NaN when Tc has no interval yet
        r.gm_tc.ci95_low = std::fmin(r.gm_tc.ci95_low, other.tc.first);
        r.gm_tc.ci95_high = std::fmax(r.gm_tc.ci95_high, other.tc.second);
      }
      if (chosen.fit->terms.contains(t)) {
        e.ci95_low = std::min(e.ci95_low, low);
        e.ci95_high = std::max(e.ci95_high, high);
        continue;
      }
      // A linear term left out keeps its profile bound (a log-scale
      // interval of a coefficient near zero reaches far up); the random
      // bias left out takes the other process's, when finite (a Gauss-
      // Markov sigma whose Tc may be endless, like a random walk's, has
      // none). A random walk's interval is a log-scale one: it bounds K
      // only when the candidate pins K within a factor of kClosedRatio
      // either way. A candidate that holds it at next to nothing (the
      // chosen model with a negligible random walk) has an interval that
      // says nothing of how large K can be (up to 1e25 deg/h/sqrt(s) on
      // 1 h records, where the profile bound is 1e-3), and the profile
      // bound already speaks for it. (Sigma's comes from its profile.)
      if (t != NoiseTerm::random_walk && t != NoiseTerm::gauss_markov) continue;
      if (!std::isfinite(high)) continue;  // no bound from that candidate
      if (t == NoiseTerm::random_walk &&
          !(low > 0.0 && high / low <= kClosedRatio * kClosedRatio)) {
        continue;
      }
      e.upper_95 = std::fmax(e.upper_95, high);  // NaN when it had no bound
      e.ci95_low = 0.0;
      e.ci95_high = e.upper_95;
      if (e.status == TermStatus::upper_bound) e.value = e.upper_95;
    }
  }
}

}  // namespace foglab::model::detail
