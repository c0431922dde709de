#include "foglab/model/noise_fit.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <utility>

#include "allan_covariance.h"
#include "foglab/core/error.h"
#include "foglab/stats/edf.h"

namespace foglab::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFlickerFactor = 2.0 * std::numbers::ln2 / std::numbers::pi;
// One-sided 95 % point of chi-square with one degree of freedom (1.645^2)
// and the two-sided 95 % normal quantile.
constexpr double kOneSided95 = 2.705543454095404;
constexpr double kZ95 = 1.959963984540054;

constexpr std::array<NoiseTerm, kNoiseTerms> kTerms = {NoiseTerm::N, NoiseTerm::B, NoiseTerm::K,
                                                       NoiseTerm::R, NoiseTerm::Q, NoiseTerm::gm};

int bit(NoiseTerm t) { return 1 << static_cast<int>(t); }

// (Tc/tau)^2 (2 tau/Tc - 3 + 4 e^(-tau/Tc) - e^(-2 tau/Tc)): the Gauss-Markov
// Allan variance per unit sigma^2; a series below x = 1e-2 avoids the
// cancellation (f(x)/x^2 = 2x/3 - x^2/2 + 7x^3/30 - ...).
double gm_shape(double tau_s, double tc_s) {
  const double x = tau_s / tc_s;
  if (x < 1e-2) return x * (2.0 / 3.0 - x * (0.5 - x * 7.0 / 30.0));
  return (2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x)) / (x * x);
}

// The Allan variance of a linear term per unit squared coefficient.
double basis(NoiseTerm t, double tau_s, double tc_s) {
  switch (t) {
    case NoiseTerm::N:
      return 1.0 / tau_s;
    case NoiseTerm::B:
      return kFlickerFactor;
    case NoiseTerm::K:
      return tau_s / 3.0;
    case NoiseTerm::R:
      return tau_s * tau_s / 2.0;
    case NoiseTerm::Q:
      return 3.0 / (tau_s * tau_s);
    case NoiseTerm::gm:
      return gm_shape(tau_s, tc_s);
  }
  return 0.0;
}

double coefficient(const NoiseModel& m, NoiseTerm t) {
  switch (t) {
    case NoiseTerm::N:
      return m.N;
    case NoiseTerm::B:
      return m.B;
    case NoiseTerm::K:
      return m.K;
    case NoiseTerm::R:
      return m.R;
    case NoiseTerm::Q:
      return m.Q;
    case NoiseTerm::gm:
      return m.gm_sigma;
  }
  return 0.0;
}

void set_coefficient(NoiseModel& m, NoiseTerm t, double value) {
  switch (t) {
    case NoiseTerm::N:
      m.N = value;
      break;
    case NoiseTerm::B:
      m.B = value;
      break;
    case NoiseTerm::K:
      m.K = value;
      break;
    case NoiseTerm::R:
      m.R = value;
      break;
    case NoiseTerm::Q:
      m.Q = value;
      break;
    case NoiseTerm::gm:
      m.gm_sigma = value;
      break;
  }
}

std::string subset_name(int mask) {
  std::string name;
  for (NoiseTerm t : kTerms) {
    if (mask & bit(t)) {
      if (!name.empty()) name += "+";
      name += std::string(to_string(t));
    }
  }
  return name.empty() ? "none" : name;
}

// The data of one fit: Allan variances y with degrees of freedom v, and the
// detrending factors of their tau points (none: 1).
struct Points {
  std::vector<double> tau, y, v;
  std::vector<std::size_t> index;  // into the caller's tau points
  const DetrendFactors* detrend = nullptr;
  // Greenhall's OADEV edf of each point for the noise types alpha = -2
  // (random walk), -1 (flicker), 0 (white) and +2 (white phase); empty when
  // the averaging factors are unknown (the data's own edf is used then).
  std::vector<std::array<double, 4>> edf_by_alpha;
  // The averaging factors of the points and the record's angle samples
  // (empty and 0 when unknown: no correlation across tau can be modelled).
  std::vector<std::int64_t> factors;
  std::int64_t phase_points = 0;

  // The expected Allan variance of term t per unit squared coefficient.
  double basis_at(NoiseTerm t, std::size_t i, double tc) const {
    const double b = basis(t, tau[i], tc);
    return detrend ? b * detrend->factor(t, index[i], tc) : b;
  }
};

double deviance(const Points& p, const std::vector<double>& mu) {
  double d = 0.0;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    const double r = p.y[i] / mu[i];
    d += p.v[i] * (r - 1.0 - std::log(r));
  }
  return d;
}

// A fitted subset: squared coefficients of its linear terms (in kTerms
// order), Tc, the fitted means and the deviance.
struct SubsetFit {
  int mask = 0;
  double tc = 0.0;
  std::array<double, kNoiseTerms> c{};  // squared coefficients (gm: sigma^2)
  std::vector<double> mu;
  double deviance = kInf;
  bool feasible = false;
  std::vector<double> v;      // the edf the fit used
  double neg2_loglik = kInf;  // -2 ln L of the gamma likelihood with those edf
};

// Maximum gamma likelihood of the terms in `mask` for a fixed Tc, with an
// optional fixed extra term (`offset_term` with squared coefficient
// `offset_c`) for profiling. Iteratively reweighted least squares with the
// weights edf / mu^2 (the score equations of the gamma likelihood with
// identity link); column scaling and a pivoted QR keep tau^2 and 1/tau^2
// columns apart. Coefficients that turn non-positive make the subset
// infeasible, unless `drop_negative`, when the term is left out instead.
SubsetFit fit_subset(const Points& p, int mask, double tc, int offset_term = -1,
                     double offset_c = 0.0, bool drop_negative = false) {
  SubsetFit fit;
  fit.mask = mask;
  fit.tc = tc;
  const std::size_t n = p.y.size();
  std::vector<NoiseTerm> terms;
  for (NoiseTerm t : kTerms) {
    if (mask & bit(t)) terms.push_back(t);
  }
  std::vector<double> offset(n, 0.0);
  if (offset_term >= 0) {
    for (std::size_t i = 0; i < n; ++i) {
      offset[i] = offset_c * p.basis_at(static_cast<NoiseTerm>(offset_term), i, tc);
    }
  }
  std::vector<double> mu = p.y;  // first weights from the data themselves
  std::vector<double> c(terms.size(), 0.0);
  double previous = kInf;
  for (int iteration = 0; iteration < 200; ++iteration) {
    if (terms.empty()) {
      mu = offset;
      break;
    }
    const Eigen::Index k = static_cast<Eigen::Index>(terms.size());
    Eigen::MatrixXd a(static_cast<Eigen::Index>(n), k);
    Eigen::VectorXd b(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const double w = std::sqrt(p.v[i]) / std::max(mu[i], 1e-12 * p.y[i]);
      for (Eigen::Index j = 0; j < k; ++j) {
        a(static_cast<Eigen::Index>(i), j) = w * p.basis_at(terms[j], i, tc);
      }
      b(static_cast<Eigen::Index>(i)) = w * (p.y[i] - offset[i]);
    }
    Eigen::VectorXd scale = a.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < k; ++j) {
      if (!(scale(j) > 0)) scale(j) = 1.0;
      a.col(j) /= scale(j);
    }
    Eigen::VectorXd x = a.colPivHouseholderQr().solve(b);
    for (Eigen::Index j = 0; j < k; ++j) c[j] = x(j) / scale(j);
    if (drop_negative) {
      bool dropped = false;
      for (std::size_t j = 0; j < terms.size();) {
        if (!(c[j] > 0)) {
          terms.erase(terms.begin() + static_cast<std::ptrdiff_t>(j));
          c.erase(c.begin() + static_cast<std::ptrdiff_t>(j));
          dropped = true;
        } else {
          ++j;
        }
      }
      if (dropped) {
        mu = p.y;
        previous = kInf;
        continue;
      }
    }
    double change = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double m = offset[i];
      for (std::size_t j = 0; j < terms.size(); ++j) m += c[j] * p.basis_at(terms[j], i, tc);
      change = std::max(change, std::fabs(m - mu[i]) / std::max(std::fabs(mu[i]), 1e-300));
      mu[i] = m;
    }
    const double d = [&] {
      for (double m : mu) {
        if (!(m > 0)) return kInf;
      }
      return deviance(p, mu);
    }();
    if (change < 1e-10 || std::fabs(previous - d) < 1e-12 * std::max(1.0, d)) break;
    previous = d;
  }
  fit.feasible = true;
  for (double value : c) {
    if (!(value > 0)) fit.feasible = false;
  }
  for (double m : mu) {
    if (!(m > 0)) fit.feasible = false;
  }
  for (std::size_t j = 0; j < terms.size(); ++j) fit.c[static_cast<int>(terms[j])] = c[j];
  fit.mask = 0;
  for (NoiseTerm t : terms) fit.mask |= bit(t);
  if (offset_term >= 0) fit.c[offset_term] = offset_c;
  fit.mu = std::move(mu);
  fit.deviance = fit.feasible ? deviance(p, fit.mu) : kInf;
  return fit;
}

// The correlation times tried for a Gauss-Markov term: from the shortest tau
// to well beyond the longest (where the process looks like a random walk),
// six per decade, then golden-section refinement around the best.
SubsetFit fit_subset_profiled(const Points& p, int mask) {
  if (!(mask & bit(NoiseTerm::gm))) return fit_subset(p, mask, 1.0);
  const double lo = std::log(p.tau.front() * 0.5);
  const double hi = std::log(p.tau.back() * 30.0);
  const int steps = std::max(8, static_cast<int>(std::ceil((hi - lo) / std::log(10.0) * 6.0)));
  std::vector<SubsetFit> grid;
  grid.reserve(static_cast<std::size_t>(steps) + 1);
  for (int s = 0; s <= steps; ++s) {
    grid.push_back(fit_subset(p, mask, std::exp(lo + (hi - lo) * s / steps)));
  }
  std::size_t best = 0;
  for (std::size_t s = 1; s < grid.size(); ++s) {
    if (grid[s].deviance < grid[best].deviance) best = s;
  }
  if (!grid[best].feasible) return grid[best];
  // Golden section on ln Tc between the neighbours of the best grid point.
  double a = std::log(grid[best > 0 ? best - 1 : 0].tc);
  double b = std::log(grid[std::min(best + 1, grid.size() - 1)].tc);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  SubsetFit result = grid[best];
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  SubsetFit f1 = fit_subset(p, mask, std::exp(x1)), f2 = fit_subset(p, mask, std::exp(x2));
  for (int it = 0; it < 40 && b - a > 1e-6; ++it) {
    if (f1.deviance < f2.deviance) {
      b = x2;
      x2 = x1;
      f2 = std::move(f1);
      x1 = b - g * (b - a);
      f1 = fit_subset(p, mask, std::exp(x1));
    } else {
      a = x1;
      x1 = x2;
      f1 = std::move(f2);
      x2 = a + g * (b - a);
      f2 = fit_subset(p, mask, std::exp(x2));
    }
  }
  for (SubsetFit* f : {&f1, &f2}) {
    if (f->deviance < result.deviance) result = *f;
  }
  return result;
}

// The noise type that dominates the fitted model at each point decides its
// edf (the Allan variance's uncertainty at the model, not at the noisy
// data's apparent type): white N -> alpha 0, flicker B -> -1, random walk K
// and ramp R -> -2, quantisation Q -> +2, Gauss-Markov -> -2 below Tc, 0 above.
std::vector<double> model_edf(const Points& p, const SubsetFit& f) {
  std::vector<double> v = p.v;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    double best = -1.0;
    int alpha_index = 2;
    for (NoiseTerm t : kTerms) {
      if (!(f.mask & bit(t))) continue;
      const double share = f.c[static_cast<int>(t)] * p.basis_at(t, i, f.tc);
      if (share <= best) continue;
      best = share;
      switch (t) {
        case NoiseTerm::N:
          alpha_index = 2;
          break;
        case NoiseTerm::B:
          alpha_index = 1;
          break;
        case NoiseTerm::K:
        case NoiseTerm::R:
          alpha_index = 0;
          break;
        case NoiseTerm::Q:
          alpha_index = 3;
          break;
        case NoiseTerm::gm:
          alpha_index = p.tau[i] < f.tc ? 0 : 2;
          break;
      }
    }
    const double e = p.edf_by_alpha[i][static_cast<std::size_t>(alpha_index)];
    if (std::isfinite(e) && e > 0) v[i] = e;
  }
  return v;
}

double neg2_loglik(const Points& p, const std::vector<double>& v, const std::vector<double>& mu) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    const double k = 0.5 * v[i];
    sum += -2.0 * (k * std::log(k) - std::lgamma(k) + (k - 1.0) * std::log(p.y[i]) -
                   k * std::log(mu[i]) - k * p.y[i] / mu[i]);
  }
  return sum;
}

// The profiled fit of a subset with the edf of its own model (a few
// alternations of fit and edf), and its likelihood.
SubsetFit fit_subset_final(const Points& p, int mask) {
  SubsetFit f = fit_subset_profiled(p, mask);
  f.v = p.v;
  if (!p.edf_by_alpha.empty()) {
    for (int round = 0; round < 3 && f.feasible; ++round) {
      Points q = p;
      q.v = model_edf(p, f);
      if (q.v == f.v) break;
      SubsetFit g = fit_subset_profiled(q, mask);
      if (!g.feasible) break;
      g.v = std::move(q.v);
      f = std::move(g);
    }
  }
  if (f.feasible) f.neg2_loglik = neg2_loglik(p, f.v, f.mu);
  return f;
}

int parameter_count(int mask) {
  int count = 0;
  for (NoiseTerm t : kTerms) {
    if (mask & bit(t)) count += t == NoiseTerm::gm ? 2 : 1;
  }
  return count;
}

NoiseModel to_model(const SubsetFit& f) {
  NoiseModel m;
  for (NoiseTerm t : kTerms) {
    if (f.mask & bit(t)) set_coefficient(m, t, std::sqrt(f.c[static_cast<int>(t)]));
  }
  if (f.mask & bit(NoiseTerm::gm)) m.gm_tc = f.tc;
  return m;
}

// The scaled gradients a_i = sqrt(v_i/2) d ln mu_i / d theta (rows), theta =
// (ln c_j for the linear terms, then ln sigma^2, ln Tc): the Fisher
// information of the gamma likelihood is A'A, and the score's covariance
// A'RA when the points' standardised errors have correlation R.
// Without `with_tc`, Tc is held at its value (the conditional covariance of
// the others).
Eigen::MatrixXd log_parameter_gradients(const Points& p, const SubsetFit& f,
                                        std::vector<NoiseTerm>& order, bool with_tc = true) {
  order.clear();
  for (NoiseTerm t : kTerms) {
    if (f.mask & bit(t)) order.push_back(t);
  }
  const bool gm = with_tc && (f.mask & bit(NoiseTerm::gm)) != 0;
  const Eigen::Index k = static_cast<Eigen::Index>(order.size()) + (gm ? 1 : 0);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(p.y.size()), k);
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const double w = std::sqrt(0.5 * p.v[i]) / f.mu[i];
    for (std::size_t j = 0; j < order.size(); ++j) {
      const int t = static_cast<int>(order[j]);
      a(row, static_cast<Eigen::Index>(j)) = w * f.c[t] * p.basis_at(order[j], i, f.tc);
    }
    if (gm) {
      const double h = 1e-5;
      const double up = p.basis_at(NoiseTerm::gm, i, f.tc * std::exp(h));
      const double down = p.basis_at(NoiseTerm::gm, i, f.tc * std::exp(-h));
      a(row, k - 1) = w * f.c[static_cast<int>(NoiseTerm::gm)] * (up - down) / (2.0 * h);
    }
  }
  return a;
}

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

// Covariance of the log parameters (log_parameter_gradients) from the
// Fisher information of the gamma likelihood, the points independent.
Eigen::MatrixXd log_parameter_covariance(const Points& p, const SubsetFit& f,
                                         std::vector<NoiseTerm>& order, bool with_tc = true) {
  return inverse_information(log_parameter_gradients(p, f, order, with_tc));
}

// How much the correlation R between the points' errors widens each
// parameter's variance: the sandwich (robust) covariance J^-1 (A'RA) J^-1,
// J = A'A, of the estimator that treats the points as independent
// (White, "Maximum likelihood estimation of misspecified models",
// Econometrica 50, 1982; for the wavelet variance, Guerrier et al., JASA
// 108, 2013), divided by J^-1 on the diagonal, over the informed columns.
// 1 where J is singular.
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

// The covariance [(deg/h)^4] of the points' Allan variance estimates under
// the model `f`: the exact one for Gaussian noise (allan_covariance.h) of
// the undetrended model (the fit's coefficients are its). Removing a
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
  Eigen::MatrixXd c = detail::allan_variance_covariance(model, tau0, p.factors, p.phase_points);
  const auto n = c.rows();
  Eigen::VectorXd scale(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double undetrended = allan_variance(model, p.tau[k]);
    const double detrended = f.mu[k] - ramp * ramp * p.basis_at(NoiseTerm::R, k, f.tc);
    scale(i) = undetrended > 0 ? detrended / undetrended : 1.0;
  }
  c = scale.asDiagonal() * c * scale.asDiagonal();
  if (ramp > 0) {
    const Eigen::MatrixXd walk =
        detail::allan_variance_covariance({.K = 1.0}, tau0, p.factors, p.phase_points);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double share = ramp * ramp * p.basis_at(NoiseTerm::R, k, f.tc);  // mu_R
      scale(i) = std::sqrt(2.0 / p.v[k]) * share / std::sqrt(std::max(walk(i, i), 1e-300));
    }
    c += scale.asDiagonal() * walk * scale.asDiagonal();
  }
  return c;
}

// The matrix R of sandwich_ratios() for the fit `f`: the points'
// covariance divided by the standard deviations the fit's weights assume,
// sqrt(2/v_i) mu_i (its diagonal shows where the edf of the dominant noise
// type misstate a mixture's variance).
Eigen::MatrixXd standardised(const Eigen::MatrixXd& covariance, const Points& p,
                             const SubsetFit& f) {
  Eigen::VectorXd z(covariance.rows());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    z(i) = std::sqrt(0.5 * p.v[k]) / f.mu[k];
  }
  return z.asDiagonal() * covariance * z.asDiagonal();
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
  constexpr double kChi2_95 = 3.841458820694124;
  const int gm = static_cast<int>(NoiseTerm::gm);
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
  r.sigma_low = std::sqrt(chosen.c[gm]);
  r.sigma_high = r.sigma_low;
  for (std::size_t s = 0; s < ln_tc.size(); ++s) {
    const SubsetFit f = fit_subset(p, chosen.mask, std::exp(ln_tc[s]));
    rise[s] = f.feasible ? f.deviance - chosen.deviance : kInf;
    if (!(rise[s] <= sigma_allowed)) continue;
    // Conditional interval of ln sigma^2 at this Tc: the quadratic
    // deviance reaches the threshold at +-sqrt((allowed - rise) * variance).
    std::vector<NoiseTerm> order;
    const Eigen::MatrixXd cov = log_parameter_covariance(p, f, order, /*with_tc=*/false);
    const auto j = static_cast<Eigen::Index>(std::find(order.begin(), order.end(), NoiseTerm::gm) -
                                             order.begin());
    const double half = std::sqrt(std::max(0.0, (sigma_allowed - rise[s]) * cov(j, j)));
    const double sigma = std::sqrt(f.c[gm]);
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

// The one-sided 95 % upper bound of a term left out of `chosen`: the squared
// coefficient at which forcing the term in raises the deviance by
// kOneSided95 * scale. NaN for the Gauss-Markov term (its bound depends on
// Tc without limit).
double upper_bound(const Points& p, const SubsetFit& chosen, NoiseTerm term, double scale) {
  if (term == NoiseTerm::gm) return kNaN;
  const int t = static_cast<int>(term);
  const double target = chosen.deviance + kOneSided95 * scale;
  auto dev = [&](double c) {
    return fit_subset(p, chosen.mask, chosen.tc, t, c, /*drop_negative=*/true).deviance;
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

// The 95 % intervals of the terms of `f` (in kTerms order, the Gauss-
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
  std::array<std::pair<double, double>, kNoiseTerms> term;
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
    if (order[j] == NoiseTerm::gm) {
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
  for (NoiseTerm t : kTerms) {
    if (!(f.mask & bit(t))) continue;
    double share = 0.0;
    for (std::size_t i = 0; i < p.y.size(); ++i) {
      share = std::max(share, f.c[static_cast<int>(t)] * p.basis_at(t, i, f.tc) / f.mu[i]);
    }
    if (share < 0.01) return true;
  }
  return false;
}

bool admissible(int mask, const NoiseFitOptions& options) {
  if (mask == 0) return false;
  const bool gm = (mask & bit(NoiseTerm::gm)) != 0;
  if (gm && !options.allow_gauss_markov) return false;
  if (gm && (mask & bit(NoiseTerm::K)) && !options.allow_wiener_with_gauss_markov) return false;
  return true;
}

CandidateModel candidate(const SubsetFit& f, double penalty) {
  CandidateModel c;
  c.terms = subset_name(f.mask);
  c.model = to_model(f);
  c.deviance = f.deviance;
  c.parameters = parameter_count(f.mask);
  c.criterion = f.neg2_loglik + penalty * c.parameters;
  return c;
}

}  // namespace

std::string_view to_string(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::N:
      return "N";
    case NoiseTerm::B:
      return "B";
    case NoiseTerm::K:
      return "K";
    case NoiseTerm::R:
      return "R";
    case NoiseTerm::Q:
      return "Q";
    case NoiseTerm::gm:
      return "GM";
  }
  return "?";
}

std::string_view to_string(TermStatus status) {
  switch (status) {
    case TermStatus::resolved:
      return "resolved";
    case TermStatus::upper_bound:
      return "upper_bound";
    case TermStatus::absent:
      return "absent";
  }
  return "?";
}

std::string_view to_string(RandomBiasProcess process) {
  switch (process) {
    case RandomBiasProcess::none:
      return "none";
    case RandomBiasProcess::wiener:
      return "wiener";
    case RandomBiasProcess::gauss_markov:
      return "gauss_markov";
  }
  return "?";
}

std::span<const ReportedParameter> reported_parameters() {
  static const ReportedParameter table[] = {
      {"N", "deg/h/sqrt(Hz)", &NoiseFitResult::N, &NoiseModel::N},
      {"B", "deg/h", &NoiseFitResult::B, &NoiseModel::B},
      {"K", "deg/h/sqrt(s)", &NoiseFitResult::K, &NoiseModel::K},
      {"R", "deg/h/s", &NoiseFitResult::R, &NoiseModel::R},
      {"Q", "deg/h*s", &NoiseFitResult::Q, &NoiseModel::Q},
      {"gm_sigma", "deg/h", &NoiseFitResult::gm_sigma, &NoiseModel::gm_sigma},
      {"gm_tc", "s", &NoiseFitResult::gm_tc, &NoiseModel::gm_tc}};
  return table;
}

double allan_variance(const NoiseModel& model, NoiseTerm term, double tau_s) {
  const double c = coefficient(model, term);
  if (c == 0.0) return 0.0;
  return c * c * basis(term, tau_s, model.gm_tc > 0 ? model.gm_tc : 1.0);
}

double allan_variance(const NoiseModel& model, double tau_s) {
  double sum = 0.0;
  for (NoiseTerm t : kTerms) sum += allan_variance(model, t, tau_s);
  return sum;
}

double DetrendFactors::factor(NoiseTerm term, std::size_t index, double tc_s) const {
  if (term != NoiseTerm::gm) return linear[static_cast<int>(term)][index];
  if (gm_tc_s.empty()) return 1.0;
  if (tc_s <= gm_tc_s.front()) return gm.front()[index];
  if (tc_s >= gm_tc_s.back()) return gm.back()[index];
  const auto it = std::upper_bound(gm_tc_s.begin(), gm_tc_s.end(), tc_s);
  const std::size_t k = static_cast<std::size_t>(it - gm_tc_s.begin());
  const double w = std::log(tc_s / gm_tc_s[k - 1]) / std::log(gm_tc_s[k] / gm_tc_s[k - 1]);
  return (1.0 - w) * gm[k - 1][index] + w * gm[k][index];
}

namespace {

// The fit; `factors` and `phase_points` (when known) give each point's edf
// for the candidate models' noise types.
NoiseFitResult fit_impl(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                        std::span<const double> edf, std::span<const std::int64_t> factors,
                        std::int64_t phase_points, const NoiseFitOptions& options,
                        const DetrendFactors* detrend) {
  if (detrend && detrend->tau_s.size() != tau_s.size()) {
    throw UsageError(fmt::format("noise-model fit: {} detrending factors for {} tau points",
                                 detrend->tau_s.size(), tau_s.size()));
  }
  if (tau_s.size() != adev_deg_h.size() || tau_s.size() != edf.size()) {
    throw UsageError(
        fmt::format("noise-model fit: tau, deviation and edf need equal counts, got {}, {} and {}",
                    tau_s.size(), adev_deg_h.size(), edf.size()));
  }
  Points p;
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    if (!(tau_s[i] > 0) || !(adev_deg_h[i] > 0) || !std::isfinite(adev_deg_h[i])) {
      throw UsageError(
          fmt::format("noise-model fit: point {} has tau {} s and deviation {} deg/h; both must be "
                      "positive and finite",
                      i + 1, tau_s[i], adev_deg_h[i]));
    }
    if (!(edf[i] >= options.min_edf)) continue;
    p.tau.push_back(tau_s[i]);
    p.y.push_back(adev_deg_h[i] * adev_deg_h[i]);
    p.v.push_back(edf[i]);
    p.index.push_back(i);
    if (!factors.empty()) {
      std::array<double, 4> e{};
      const int alphas[] = {-2, -1, 0, 2};
      for (int a = 0; a < 4; ++a) {
        e[static_cast<std::size_t>(a)] =
            stats::greenhall_edf(alphas[a], 2, factors[i], phase_points, true, false);
      }
      p.edf_by_alpha.push_back(e);
      p.factors.push_back(factors[i]);
    }
  }
  p.detrend = detrend;
  p.phase_points = phase_points;
  if (p.y.size() < 3) {
    throw UsageError(fmt::format(
        "noise-model fit: {} usable Allan-deviation points (edf >= {}); at least 3 are needed",
        p.y.size(), options.min_edf));
  }

  std::vector<SubsetFit> fits;
  for (int mask = 1; mask < (1 << kNoiseTerms); ++mask) {
    if (!admissible(mask, options)) continue;
    // A subset with more parameters than points minus one cannot be judged.
    if (parameter_count(mask) >= static_cast<int>(p.y.size())) continue;
    SubsetFit f = fit_subset_final(p, mask);
    if (f.feasible) fits.push_back(std::move(f));
  }
  if (fits.empty()) {
    // Cannot happen for positive data (white noise alone always fits), but a
    // status is better than a crash.
    throw DataError("noise-model fit: no candidate model could be fitted to the Allan variance");
  }
  const double penalty = options.penalty;
  auto criterion = [&](const SubsetFit& f) {
    return f.neg2_loglik + penalty * parameter_count(f.mask);
  };
  std::sort(fits.begin(), fits.end(),
            [&](const SubsetFit& a, const SubsetFit& b) { return criterion(a) < criterion(b); });
  const SubsetFit& chosen = fits.front();
  Points pc = p;  // the points with the chosen model's edf
  pc.v = chosen.v;

  NoiseFitResult r;
  r.model = to_model(chosen);
  r.terms = subset_name(chosen.mask);
  r.deviance = chosen.deviance;
  r.points = static_cast<int>(p.y.size());
  r.parameters = parameter_count(chosen.mask);
  r.dispersion = std::max(1.0, chosen.deviance / std::max(1, r.points - r.parameters));
  for (const SubsetFit& f : fits) r.candidates.push_back(candidate(f, penalty));

  // Evidence: the best candidate of each random-bias hypothesis.
  const int k_bit = bit(NoiseTerm::K), gm_bit = bit(NoiseTerm::gm);
  for (const SubsetFit& f : fits) {  // sorted by criterion
    const bool has_k = f.mask & k_bit, has_gm = f.mask & gm_bit;
    if (!has_k && !has_gm && !r.has_candidate_without_random_bias) {
      r.best_without_random_bias = candidate(f, penalty);
      r.has_candidate_without_random_bias = true;
    }
    if (has_k && !has_gm && !r.has_wiener_candidate) {
      r.best_wiener = candidate(f, penalty);
      r.has_wiener_candidate = true;
    }
    if (has_gm && !r.has_gauss_markov_candidate) {
      r.best_gauss_markov = candidate(f, penalty);
      r.has_gauss_markov_candidate = true;
    }
  }
  if (chosen.mask & gm_bit) {
    r.random_bias_process = RandomBiasProcess::gauss_markov;
  } else if (chosen.mask & k_bit) {
    r.random_bias_process = RandomBiasProcess::wiener;
  }

  // Intervals (intervals_of()), under the chosen model's covariance of the
  // points.
  const bool modelled = !pc.factors.empty();
  const Eigen::MatrixXd covariance = modelled ? point_covariance(pc, chosen) : Eigen::MatrixXd();
  const Eigen::MatrixXd* known = modelled ? &covariance : nullptr;
  // The reported parameter of each term (gm: its sigma), in kTerms order.
  auto estimate_for = [&](NoiseTerm t) -> ParameterEstimate& {
    return r.*(reported_parameters()[static_cast<std::size_t>(t)].estimate);
  };
  const Intervals own =
      intervals_of(pc, chosen, known, r.dispersion, options.correlation_inflation);
  for (NoiseTerm t : kTerms) {
    if (!(chosen.mask & bit(t))) continue;
    const auto [low, high] = own.term[static_cast<std::size_t>(t)];
    estimate_for(t) = {coefficient(r.model, t), low, high, kNaN, TermStatus::resolved};
  }
  if (chosen.mask & gm_bit) {
    r.gm_tc = {r.model.gm_tc, own.tc.first, own.tc.second, kNaN, TermStatus::resolved};
  }

  // Terms left out: status and one-sided bound, the deviance's allowance
  // scaled by the term's sandwich ratio in the enlarged model at zero (its
  // column d mu/d c, the chosen model's gradients beside it).
  std::vector<NoiseTerm> order;
  const Eigen::MatrixXd gradients = log_parameter_gradients(pc, chosen, order);
  const Eigen::MatrixXd chosen_r =
      modelled ? standardised(covariance, pc, chosen) : Eigen::MatrixXd();
  for (NoiseTerm t : kTerms) {
    if (chosen.mask & bit(t)) continue;
    const int enlarged = chosen.mask | bit(t);
    TermStatus status = TermStatus::absent;
    if (admissible(enlarged, options) && parameter_count(enlarged) < static_cast<int>(p.y.size())) {
      const SubsetFit bigger = fit_subset_profiled(pc, enlarged);
      if (bigger.feasible) status = TermStatus::upper_bound;
    }
    double bound_scale = r.dispersion * options.correlation_inflation;
    if (modelled && t != NoiseTerm::gm) {
      Eigen::MatrixXd a(gradients.rows(), gradients.cols() + 1);
      a.leftCols(gradients.cols()) = gradients;
      for (std::size_t i = 0; i < pc.y.size(); ++i) {
        a(static_cast<Eigen::Index>(i), gradients.cols()) =
            std::sqrt(0.5 * pc.v[i]) * pc.basis_at(t, i, chosen.tc) / chosen.mu[i];
      }
      bound_scale = r.dispersion * sandwich_ratios(a, chosen_r)(gradients.cols());
    }
    const double ub = upper_bound(pc, chosen, t, bound_scale);
    ParameterEstimate& e = estimate_for(t);
    // A one-sided interval [0, bound]: the term may be there, this small.
    const bool bounded = std::isfinite(ub);
    e = {status == TermStatus::upper_bound ? ub : kNaN, bounded ? 0.0 : kNaN, bounded ? ub : kNaN,
         ub, status};
    if (t == NoiseTerm::gm) {
      r.gm_tc = {kNaN, kNaN, kNaN, kNaN, status};
    }
  }

  // The other candidates the criterion can hardly tell from the chosen one
  // (within `interval_window` of its criterion: the chosen one with a
  // term the data leave undecided, or the other random-bias process) give
  // their intervals too, and each reported interval is the union: an
  // interval conditional on the selected model alone misses the truth
  // whenever the selection dropped a term that shifts the others (a small
  // flicker term left out pulls a Gauss-Markov sigma or a random walk up
  // by 15-30 %; docs/validation.md). A chosen term's interval is the union
  // over the candidates that hold it; a random-bias term left out (K, or
  // the Gauss-Markov pair) gets the largest upper end as its bound (Tc the
  // union of the intervals). The estimates, the statuses and the decision
  // stay those of the chosen model.
  const double best = criterion(chosen);
  for (std::size_t k = 1; k < fits.size(); ++k) {
    const SubsetFit& f = fits[k];
    if (!(criterion(f) - best <= options.interval_window)) break;  // sorted
    if (holds_a_negligible_term(p, f)) continue;
    Points q = p;
    q.v = f.v;
    const Intervals other = intervals_of(q, f, known, r.dispersion, options.correlation_inflation);
    for (NoiseTerm t : kTerms) {
      if (!(f.mask & bit(t))) continue;
      ParameterEstimate& e = estimate_for(t);
      const auto [low, high] = other.term[static_cast<std::size_t>(t)];
      if (t == NoiseTerm::gm) {  // NaN when Tc has no interval yet
        r.gm_tc.ci95_low = std::fmin(r.gm_tc.ci95_low, other.tc.first);
        r.gm_tc.ci95_high = std::fmax(r.gm_tc.ci95_high, other.tc.second);
      }
      if (chosen.mask & bit(t)) {
        e.ci95_low = std::min(e.ci95_low, low);
        e.ci95_high = std::max(e.ci95_high, high);
        continue;
      }
      // A linear term left out keeps its profile bound (a log-scale
      // interval of a coefficient near zero reaches far up); the random
      // bias left out takes the other process's, when finite (a Gauss-
      // Markov sigma whose Tc may be endless, like a random walk's, has
      // none).
      if (t != NoiseTerm::K && t != NoiseTerm::gm) continue;
      if (!std::isfinite(high)) continue;        // no bound from that candidate
      e.upper_95 = std::fmax(e.upper_95, high);  // NaN when it had no bound
      e.ci95_low = 0.0;
      e.ci95_high = e.upper_95;
      if (e.status == TermStatus::upper_bound) e.value = e.upper_95;
    }
  }
  return r;
}

}  // namespace

NoiseFitResult fit_noise_model(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                               std::span<const double> edf, const NoiseFitOptions& options,
                               const DetrendFactors* detrend) {
  return fit_impl(tau_s, adev_deg_h, edf, {}, 0, options, detrend);
}

NoiseFitResult fit_noise_model(const stats::AllanResult& allan, const NoiseFitOptions& options,
                               const DetrendFactors* detrend) {
  if (allan.kind != stats::AllanKind::oadev || allan.m.size() != allan.dev.size()) {
    throw UsageError("noise-model fit: needs an overlapping Allan deviation (oadev) result");
  }
  // Without intervals the edf come from the models alone (white noise's
  // stand in until the first model is fitted).
  std::vector<double> edf = allan.edf;
  edf.resize(allan.dev.size(), kNaN);
  for (std::size_t i = 0; i < edf.size(); ++i) {
    if (!std::isfinite(edf[i])) {
      edf[i] = stats::greenhall_edf(0, 2, allan.m[i], allan.phase_points, true, false);
    }
  }
  return fit_impl(allan.tau_s, allan.dev, edf, allan.m, allan.phase_points, options, detrend);
}

}  // namespace foglab::model
