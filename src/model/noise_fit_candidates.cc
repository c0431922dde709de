// foglab — noise-model fit, step 2: every admissible subset of terms, fitted
// by maximum gamma likelihood and ranked by the criterion
// (noise_fit_internal.h).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "noise_fit_internal.h"

namespace foglab::model::detail {
namespace {

// The noise type that dominates the fitted model at each point decides its
// edf (the Allan variance's uncertainty at the model, not at the noisy
// data's apparent type): white N -> alpha 0, flicker B -> -1, random walk K
// and ramp R -> -2, quantisation Q -> +2, Gauss-Markov -> -2 below Tc, 0 above.
// The index is into Points::edf_by_alpha (alpha -2, -1, 0, +2).
std::size_t edf_alpha_index(NoiseTerm t, double tau_s, double tc_s) {
  switch (t) {
    case NoiseTerm::white:
      return 2;
    case NoiseTerm::flicker:
      return 1;
    case NoiseTerm::random_walk:
    case NoiseTerm::ramp:
      return 0;
    case NoiseTerm::quantisation:
      return 3;
    case NoiseTerm::gauss_markov:
      return tau_s < tc_s ? 0 : 2;
  }
  return 2;
}

std::vector<double> model_edf(const Points& p, const SubsetFit& f) {
  std::vector<double> v = p.v;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    double best = -1.0;
    std::size_t alpha_index = 2;
    for (NoiseTerm t : kNoiseTerms) {
      if (!f.terms.contains(t)) continue;
      const double share = f.squared(t) * p.basis_at(t, i, f.tc);
      if (share <= best) continue;
      best = share;
      alpha_index = edf_alpha_index(t, p.tau[i], f.tc);
    }
    const double e = p.edf_by_alpha[i][alpha_index];
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
SubsetFit fit_subset_final(const Points& p, NoiseTermSet terms) {
  SubsetFit f = fit_subset_profiled(p, terms);
  f.v = p.v;
  if (!p.edf_by_alpha.empty()) {
    for (int round = 0; round < 3 && f.feasible; ++round) {
      Points q = p;
      q.v = model_edf(p, f);
      if (q.v == f.v) break;
      SubsetFit g = fit_subset_profiled(q, terms);
      if (!g.feasible) break;
      g.v = std::move(q.v);
      f = std::move(g);
    }
  }
  if (f.feasible) f.neg2_loglik = neg2_loglik(p, f.v, f.mu);
  return f;
}

}  // namespace

double deviance(const Points& p, const std::vector<double>& mu) {
  double d = 0.0;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    const double r = p.y[i] / mu[i];
    d += p.v[i] * (r - 1.0 - std::log(r));
  }
  return d;
}

// Iteratively reweighted least squares with the weights edf / mu^2 (the
// score equations of the gamma likelihood with identity link); column
// scaling and a pivoted QR keep tau^2 and 1/tau^2 columns apart. It stops
// when no mean changes by more than the tolerance (relative) or the
// deviance by less than 1e-12 of itself, or after max_iterations (the
// status says which). Once a step has started from positive means, no step
// leaves them or raises the deviance: such a step is halved (below).
//
// With NonPositive::drop_term the fit is a non-negative one: a term whose
// coefficient comes out non-positive is left out, and at convergence a term
// left out comes back while the deviance's slope along it says adding it
// lowers the deviance (its predicted drop g^2 / 2H above kWorthReturning):
// the first steps are weighted by the data themselves, so an Allan point far
// below the model's line (a few edf at the longest tau, where a chi-square
// draw can be a tenth of its mean) weighs a hundred times its due there, and
// had pushed the random walk and the ramp negative together. Both left out
// for good, the reference of the bandwidth search missed the long taus by a
// deviance of 77, 64 of which a 111-sample moving average on 5 % of N^2 then
// made up (white noise with flicker and a random walk, 2 h with three
// gaps: docs/validation.md). The fit returned is the converged one with the
// least deviance, so a term's return never makes it worse.
SubsetFit fit_subset(const Points& p, NoiseTermSet terms, double tc, std::optional<FixedTerm> fixed,
                     NonPositive non_positive) {
  constexpr double kWorthReturning = 1e-3;  // deviance
  constexpr int kMaxHalvings = 30;
  const std::size_t n = p.y.size();
  std::vector<NoiseTerm> fitted;
  for (NoiseTerm t : kNoiseTerms) {
    if (terms.contains(t)) fitted.push_back(t);
  }
  std::vector<double> offset = p.fixed_avar;
  offset.resize(n, 0.0);
  if (fixed) {
    for (std::size_t i = 0; i < n; ++i) {
      offset[i] += fixed->squared_coefficient * p.basis_at(fixed->term, i, tc);
    }
  }
  // The basis of each term at every point, by term: fixed over the
  // iterations (only the weights change), so computed once.
  std::array<std::vector<double>, kNoiseTerms.size()> bases;
  for (NoiseTerm t : fitted) {
    std::vector<double>& b = bases[static_cast<std::size_t>(t)];
    for (std::size_t i = 0; i < n; ++i) b.push_back(p.basis_at(t, i, tc));
  }
  const auto basis = [&bases](NoiseTerm t) -> const std::vector<double>& {
    return bases[static_cast<std::size_t>(t)];
  };
  std::vector<NoiseTerm> left_out;  // drop_term: the terms left out
  int returns_left = static_cast<int>(fitted.size());
  std::vector<double> mu = p.y;  // first weights from the data themselves
  std::vector<double> c(fitted.size(), 0.0);
  std::vector<double> start = c;  // the coefficients at the step's start
  double previous = kInf;         // their deviance (kInf: no start to go back to)
  // The means of coefficients `coef` of the fitted terms.
  const auto means = [&](const std::vector<double>& coef) {
    std::vector<double> m = offset;
    for (std::size_t j = 0; j < fitted.size(); ++j) {
      const std::vector<double>& b = basis(fitted[j]);
      for (std::size_t i = 0; i < n; ++i) m[i] += coef[j] * b[i];
    }
    return m;
  };
  const auto deviance_or_inf = [&](const std::vector<double>& m) {
    for (double value : m) {
      if (!(value > 0)) return kInf;
    }
    return deviance(p, m);
  };
  int iterations = 0;

  // The fit as it stands.
  const auto settle = [&](FitStatus status) {
    SubsetFit fit;
    fit.tc = tc;
    fit.status = status;
    fit.iterations = iterations;
    fit.feasible = true;
    for (double value : c) {
      if (!(value > 0)) fit.feasible = false;
    }
    for (double m : mu) {
      if (!(m > 0)) fit.feasible = false;
    }
    for (std::size_t j = 0; j < fitted.size(); ++j) {
      fit.c[static_cast<std::size_t>(fitted[j])] = c[j];
      fit.terms = fit.terms.with(fitted[j]);
    }
    if (fixed) fit.c[static_cast<std::size_t>(fixed->term)] = fixed->squared_coefficient;
    fit.mu = mu;
    fit.deviance = fit.feasible ? deviance(p, fit.mu) : kInf;
    return fit;
  };
  // The term left out whose return lowers the deviance most, if worth it.
  const auto term_to_return = [&]() -> std::optional<std::size_t> {
    std::optional<std::size_t> best;
    double best_drop = kWorthReturning;
    for (std::size_t j = 0; j < left_out.size(); ++j) {
      double slope = 0.0, curvature = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const double b = basis(left_out[j])[i];
        slope += p.v[i] * b * (mu[i] - p.y[i]) / (mu[i] * mu[i]);
        curvature += p.v[i] * b * b / (mu[i] * mu[i]);
      }
      if (!(slope < 0.0) || !(curvature > 0.0)) continue;
      if (const double drop = slope * slope / (2.0 * curvature); drop > best_drop) {
        best = j, best_drop = drop;
      }
    }
    return best;
  };

  std::optional<SubsetFit> best_converged;
  for (; iterations < p.control.max_iterations;) {
    ++iterations;
    if (fitted.empty()) {
      mu = offset;
      best_converged = settle(FitStatus::converged);
      break;
    }
    const Eigen::Index k = static_cast<Eigen::Index>(fitted.size());
    Eigen::MatrixXd a(static_cast<Eigen::Index>(n), k);
    Eigen::VectorXd b(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const double w = std::sqrt(p.v[i]) / std::max(mu[i], 1e-12 * p.y[i]);
      for (Eigen::Index j = 0; j < k; ++j) {
        a(static_cast<Eigen::Index>(i), j) = w * basis(fitted[static_cast<std::size_t>(j)])[i];
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
    if (non_positive == NonPositive::drop_term) {
      bool dropped = false;
      for (std::size_t j = 0; j < fitted.size();) {
        if (!(c[j] > 0)) {
          left_out.push_back(fitted[j]);
          fitted.erase(fitted.begin() + static_cast<std::ptrdiff_t>(j));
          c.erase(c.begin() + static_cast<std::ptrdiff_t>(j));
          dropped = true;
        } else {
          ++j;
        }
      }
      if (dropped) {
        mu = p.y;
        previous = kInf;
        start = c;
        continue;
      }
    }
    std::vector<double> next = means(c);
    double d = deviance_or_inf(next);
    // Step halving (as glm2 does: I. C. Marschner, "glm2: fitting
    // generalized linear models with convergence problems", The R Journal
    // 3(2), 2011): from a start whose means are all positive, a step that
    // leaves that domain or raises the deviance is halved back towards the
    // start until it does neither. Without it, fits far from the data (a
    // subset without the white term, a profile's term held far off its
    // optimum) swung between two states, or in and out of the domain, for
    // all max_iterations: 1,147 of the 10,030 fits of one analyze of an
    // ADIS16405 channel, more than half of its reweighting steps.
    if (previous < kInf) {
      for (int halving = 0; !(d <= previous); ++halving) {
        if (halving == kMaxHalvings) {
          c = start;  // no descent along the step: stay at the start
          next = mu;  // the start's means
          d = previous;
          break;
        }
        for (std::size_t j = 0; j < c.size(); ++j) c[j] = 0.5 * (c[j] + start[j]);
        next = means(c);
        d = deviance_or_inf(next);
      }
    }
    double change = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      change = std::max(change, std::fabs(next[i] - mu[i]) / std::max(std::fabs(mu[i]), 1e-300));
    }
    mu = std::move(next);
    if (change < p.control.tolerance || std::fabs(previous - d) < 1e-12 * std::max(1.0, d)) {
      SubsetFit now = settle(FitStatus::converged);
      if (!best_converged || now.deviance < best_converged->deviance) best_converged = now;
      const std::optional<std::size_t> back =
          now.feasible && returns_left > 0 ? term_to_return() : std::nullopt;
      if (!back) break;
      // Back in, the next step weighted by this fit's means.
      --returns_left;
      fitted.push_back(left_out[*back]);
      c.push_back(0.0);
      left_out.erase(left_out.begin() + static_cast<std::ptrdiff_t>(*back));
      start = c;
      previous = now.deviance;
      continue;
    }
    start = c;
    previous = d;
  }
  if (best_converged) return *std::move(best_converged);
  return settle(FitStatus::iteration_limit);
}

namespace {

// The shortest Gauss-Markov correlation time tried: half the shortest tau
// (the shortest, when the sensor bandwidth is modelled: a shorter
// correlation is the bandwidth's).
double shortest_tc(const Points& p) { return p.tau.front() * (p.white_shape.empty() ? 0.5 : 1.0); }

}  // namespace

// The correlation times tried for a Gauss-Markov term: from shortest_tc()
// to well beyond the longest tau (where the process looks like a random
// walk), six per decade, then golden-section refinement around the best.
SubsetFit fit_subset_profiled(const Points& p, NoiseTermSet terms) {
  if (!terms.contains(NoiseTerm::gauss_markov)) return fit_subset(p, terms, 1.0);
  const double lo = std::log(shortest_tc(p));
  const double hi = std::log(p.tau.back() * 30.0);
  const int steps = std::max(8, static_cast<int>(std::ceil((hi - lo) / std::log(10.0) * 6.0)));
  std::vector<SubsetFit> grid;
  grid.reserve(static_cast<std::size_t>(steps) + 1);
  for (int s = 0; s <= steps; ++s) {
    grid.push_back(fit_subset(p, terms, std::exp(lo + (hi - lo) * s / steps)));
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
  SubsetFit f1 = fit_subset(p, terms, std::exp(x1)), f2 = fit_subset(p, terms, std::exp(x2));
  for (int it = 0; it < 40 && b - a > 1e-6; ++it) {
    if (f1.deviance < f2.deviance) {
      b = x2;
      x2 = x1;
      f2 = std::move(f1);
      x1 = b - g * (b - a);
      f1 = fit_subset(p, terms, std::exp(x1));
    } else {
      a = x1;
      x1 = x2;
      f1 = std::move(f2);
      x2 = a + g * (b - a);
      f2 = fit_subset(p, terms, std::exp(x2));
    }
  }
  for (SubsetFit* f : {&f1, &f2}) {
    if (f->deviance < result.deviance) result = *f;
  }
  return result;
}

bool admissible(NoiseTermSet terms, const NoiseFitOptions& options) {
  if (terms.empty()) return false;
  const bool gm = terms.contains(NoiseTerm::gauss_markov);
  if (gm && !options.allow_gauss_markov) return false;
  if (gm && terms.contains(NoiseTerm::random_walk) && !options.allow_wiener_with_gauss_markov) {
    return false;
  }
  return true;
}

std::vector<SubsetFit> fit_candidates(const Points& p, const NoiseFitOptions& options) {
  std::vector<SubsetFit> fits;
  for (unsigned mask = 1; mask < (1u << kNoiseTerms.size()); ++mask) {
    const NoiseTermSet terms = NoiseTermSet::from_mask(mask);
    if (!admissible(terms, options)) continue;
    // A subset with more parameters than points minus one cannot be judged.
    if (terms.parameter_count() >= static_cast<int>(p.y.size())) continue;
    SubsetFit f = fit_subset_final(p, terms);
    // A Gauss-Markov term that wants its Tc at the shortest tried (below
    // the first tau), or within the reach of an output filter (up to
    // kFilterReach samples), is no random bias: a correlation that short is
    // the white level's and the bandwidth's (for tau >> Tc it adds 2
    // sigma^2 Tc to N^2), and its sigma and Tc would be reported at a search
    // bound. The subset is left out. (On a 3-sample moving average behind a
    // first-order low-pass, N+GM with Tc = 2.5 samples had carried half the
    // white level: N 27 % low.)
    constexpr double kAtBound = 1.01;
    constexpr double kFilterReach = 8.0;  // samples
    const double filter_reach = kFilterReach * p.sample_interval_s();
    if (terms.contains(NoiseTerm::gauss_markov) &&
        (f.tc <= kAtBound * shortest_tc(p) || f.tc <= filter_reach)) {
      continue;
    }
    if (f.feasible) fits.push_back(std::move(f));
  }
  std::sort(fits.begin(), fits.end(), [&](const SubsetFit& a, const SubsetFit& b) {
    return criterion(a, options.penalty) < criterion(b, options.penalty);
  });
  return fits;
}

double criterion(const SubsetFit& f, double penalty) {
  return f.neg2_loglik + penalty * f.terms.parameter_count();
}

NoiseModel to_model(const SubsetFit& f) {
  NoiseModel m;
  for (NoiseTerm t : kNoiseTerms) {
    if (f.terms.contains(t)) m.set_coefficient(t, std::sqrt(f.squared(t)));
  }
  if (f.terms.contains(NoiseTerm::gauss_markov)) m.gm_tc = f.tc;
  return m;
}

CandidateModel candidate(const SubsetFit& f, double penalty) {
  CandidateModel c;
  c.terms = f.terms;
  c.model = to_model(f);
  c.deviance = f.deviance;
  c.parameters = f.terms.parameter_count();
  c.criterion = criterion(f, penalty);
  c.status = f.status;
  c.iterations = f.iterations;
  return c;
}

}  // namespace foglab::model::detail
