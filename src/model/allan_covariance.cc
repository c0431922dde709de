#include "allan_covariance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace foglab::model::detail {
namespace {

// Greenhall's generalised structure function D(s) of the model's angle
// (core/noise_model.h): the covariance of two combinations sum_a w_a x(t_a)
// and sum_b u_b x(s_b) whose weights cancel constants and straight lines
// (second differences, the Allan variance's) is -1/2 sum_ab w_a u_b
// D(|t_a - s_b|).
// The rate ramp, deterministic, has none.
double structure(const NoiseModel& m, double s) {
  double d = 0.0;
  for (NoiseTerm t : {NoiseTerm::white, NoiseTerm::quantisation, NoiseTerm::flicker,
                      NoiseTerm::random_walk, NoiseTerm::gauss_markov}) {
    d += angle_structure_function(m, t, s);
  }
  return d;
}

// Eight-point Gauss-Legendre rule on [-1, 1].
constexpr std::array<double, 8> kNodes = {
    -0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
    0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights = {
    0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
    0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// Below this sum of the two averaging factors the lag sum is done term by
// term; above it, the summand is smooth between its break points on the
// scale of the factors and the sum is an integral (Euler-Maclaurin: the
// error is of relative order 1/m^2).
constexpr std::int64_t kExactLagSum = 64;

// The second-difference weights of the Allan variance.
constexpr std::array<double, 3> kW = {1.0, -2.0, 1.0};

// Two averaging factors p, q of a record of angle samples, with the numbers
// of second differences np, nq at each; pairs(l) counts the pairs of them
// at lag l.
struct FactorPair {
  std::int64_t p, q, np, nq;
  double pd, qd, npd, nqd;
  FactorPair(std::int64_t p_, std::int64_t q_, std::int64_t phase_points)
      : p(p_),
        q(q_),
        np(phase_points - 2 * p_),
        nq(phase_points - 2 * q_),
        pd(static_cast<double>(p_)),
        qd(static_cast<double>(q_)),
        npd(static_cast<double>(np)),
        nqd(static_cast<double>(nq)) {}
  double pairs(double l) const { return std::max(0.0, std::min(npd, nqd - l) - std::max(0.0, -l)); }
};

// sum_l count(l) C(l)^2 term by term, from D at whole lags (`table`).
double lag_sum_exact(const FactorPair& f, const std::vector<double>& table, bool tails) {
  const std::int64_t tail = tails ? 16 * (f.p + f.q) : 0;
  const std::int64_t lo = std::max(-f.np + 1, -2 * f.q - tail);
  const std::int64_t hi = std::min(f.nq - 1, 2 * f.p + tail);
  double sum = 0.0;
  for (std::int64_t l = lo; l <= hi; ++l) {
    double c = 0.0;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const std::int64_t s = l + b * f.q - a * f.p;
        c += kW[a] * kW[b] * table[static_cast<std::size_t>(s < 0 ? -s : s)];
      }
    }
    c *= -0.5;
    sum += f.pairs(static_cast<double>(l)) * c * c;
  }
  return sum;
}

// The same sum as an integral over l: Gauss-Legendre between the break
// points of C, the tails in doubling steps; quantisation separately.
double lag_sum_integral(const FactorPair& f, const NoiseModel& model, double tau0_s, bool tails) {
  const double pd = f.pd, qd = f.qd;
  auto covariance_at = [&](double l) {
    double c = 0.0;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        c += kW[a] * kW[b] * structure(model, std::fabs(l + b * qd - a * pd) * tau0_s);
      }
    }
    return -0.5 * c;
  };
  // Break points, tails in doubling steps, all inside the lags that have
  // pairs at all.
  std::vector<double> edges;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) edges.push_back(a * pd - b * qd);
  }
  if (tails) {
    const double step = 0.5 * (pd + qd);
    for (int k = 1; k <= 7; ++k) {
      edges.push_back(2.0 * pd + step * (std::exp2(k) - 1.0));
      edges.push_back(-2.0 * qd - step * (std::exp2(k) - 1.0));
    }
  }
  for (double& e : edges) e = std::clamp(e, -f.npd, f.nqd);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double sum = 0.0;
  for (std::size_t s = 0; s + 1 < edges.size(); ++s) {
    const double mid = 0.5 * (edges[s] + edges[s + 1]);
    const double half = 0.5 * (edges[s + 1] - edges[s]);
    for (std::size_t g = 0; g < kNodes.size(); ++g) {
      const double l = mid + half * kNodes[g];
      const double c = covariance_at(l);
      sum += half * kWeights[g] * f.pairs(l) * c * c;
    }
  }
  // Quantisation (white angle) correlates only at the break points, where
  // it adds Q^2 sum w_a w_b over the coinciding samples.
  if (model.Q > 0) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const double l = a * pd - b * qd;
        double weight = 0.0;
        bool first = true;
        for (int a2 = 0; a2 < 3; ++a2) {
          for (int b2 = 0; b2 < 3; ++b2) {
            if (a2 * pd - b2 * qd != l) continue;
            first = first && a2 * 3 + b2 >= a * 3 + b;
            weight += kW[a2] * kW[b2];
          }
        }
        if (!first) continue;  // that lag is counted once
        const double c = covariance_at(l), cq = model.Q * model.Q * weight;
        sum += f.pairs(l) * (c * c - (c - cq) * (c - cq));
      }
    }
  }
  return sum;
}

}  // namespace

// For Gaussian data the overlapping estimate at factor m,
//   A_m = sum_k d_k^2 / (2 m^2 tau0^2 n_m),  d_k = x_{k+2m} - 2 x_{k+m} + x_k,
// n_m = N - 2 m terms, has Cov(A_p, A_q) = 2 sum_{k,l} C(l - k)^2 / (4 p^2 q^2
// tau0^4 n_p n_q) (Isserlis), C(l) = Cov(d^p_k, d^q_{k+l}) from D above; the
// double sum is sum_l count(l) C(l)^2 with count(l) the pairs at lag l.
// C(l) bends where l + b q - a p = 0 (a, b = 0, 1, 2) and, for white,
// quantisation and Wiener noise, vanishes outside [-2q, 2p] (the two second
// differences see disjoint increments or one sits inside a linear part of
// the other); flicker and Gauss-Markov terms leave tails (flicker C ~ l^-2,
// so C^2 ~ l^-4), summed out to 16 (p + q) past that interval term by term
// and to about 64 (p + q) in the integral (the rest is of relative order
// 1/16^3 and 1/64^3).
Eigen::MatrixXd allan_variance_covariance(const NoiseModel& model, double tau0_s,
                                          std::span<const std::int64_t> m,
                                          std::int64_t phase_points) {
  const auto count = static_cast<Eigen::Index>(m.size());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(count, count);
  const bool tails = model.B > 0 || model.gm_sigma > 0;
  // D at whole lags, for the term-by-term sums (the largest lag they reach).
  const std::int64_t max_lag = kExactLagSum * (tails ? 18 : 2);
  std::vector<double> table(static_cast<std::size_t>(max_lag) + 1);
  for (std::size_t k = 0; k < table.size(); ++k) {
    table[k] = structure(model, static_cast<double>(k) * tau0_s);
  }
  const double tau0_4 = tau0_s * tau0_s * tau0_s * tau0_s;
  for (Eigen::Index i = 0; i < count; ++i) {
    for (Eigen::Index j = i; j < count; ++j) {
      const FactorPair f(m[static_cast<std::size_t>(i)], m[static_cast<std::size_t>(j)],
                         phase_points);
      if (f.np <= 0 || f.nq <= 0) continue;
      const double sum = f.p + f.q <= kExactLagSum ? lag_sum_exact(f, table, tails)
                                                   : lag_sum_integral(f, model, tau0_s, tails);
      cov(i, j) = 2.0 * sum / (4.0 * f.pd * f.pd * f.qd * f.qd * tau0_4 * f.npd * f.nqd);
      cov(j, i) = cov(i, j);
    }
  }
  return cov;
}

Eigen::MatrixXd pooled_allan_variance_covariance(const NoiseModel& model, double tau0_s,
                                                 std::span<const std::int64_t> m,
                                                 std::span<const std::int64_t> segment_points) {
  if (segment_points.size() == 1) {
    return allan_variance_covariance(model, tau0_s, m, segment_points.front());
  }
  const auto count = static_cast<Eigen::Index>(m.size());
  auto terms = [&](std::int64_t points) {
    Eigen::VectorXd n(count);
    for (Eigen::Index i = 0; i < count; ++i) {
      n(i) = static_cast<double>(
          std::max<std::int64_t>(0, points - 2 * m[static_cast<std::size_t>(i)]));
    }
    return n;
  };
  Eigen::VectorXd total = Eigen::VectorXd::Zero(count);
  for (const std::int64_t points : segment_points) total += terms(points);
  std::vector<std::int64_t> lengths(segment_points.begin(), segment_points.end());
  std::sort(lengths.begin(), lengths.end());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(count, count);
  for (std::size_t k = 0; k < lengths.size();) {
    std::size_t same = k;
    while (same < lengths.size() && lengths[same] == lengths[k]) ++same;
    const Eigen::VectorXd w = terms(lengths[k]).cwiseQuotient(total.cwiseMax(1.0));
    if (w.maxCoeff() > 0.0) {
      cov += static_cast<double>(same - k) * w.asDiagonal() *
             allan_variance_covariance(model, tau0_s, m, lengths[k]) * w.asDiagonal();
    }
    k = same;
  }
  return cov;
}

}  // namespace foglab::model::detail
