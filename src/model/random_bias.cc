#include "foglab/model/random_bias.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "block_covariance.h"

namespace foglab::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kChi2_95 = 3.841458820694124;  // chi-square(1) 95 % point
// Log-scale bounds of a variance parameter relative to its natural size:
// the lower one stands for "absent".
constexpr double kLowest = -25.0, kHighest = 25.0;

// Covariance of the differences of consecutive block means at lags
// 0..n-1, from the block means' (generalised) covariance at lags 0..n.
std::vector<double> difference_covariance(const std::vector<double>& c, std::size_t n) {
  std::vector<double> s(n);
  for (std::size_t k = 0; k < n; ++k) {
    s[k] = 2.0 * c[k] - c[k + 1] - c[k == 0 ? 1 : k - 1];
  }
  return s;
}

std::vector<double> unit_covariance(const NoiseModel& m, double tau_b, std::size_t n,
                                    bool stationary) {
  return difference_covariance(detail::block_covariance(m, tau_b, n + 1, stationary), n);
}

// -2 ln L (restricted) of the series y.col(0) with fixed-effect columns
// y.col(1..) and the stationary covariance of lags s[0..n-1], by the
// Durbin-Levinson recursion: the innovations e_t of every column and their
// variances v_t give log|S| = sum ln v_t and a' S^-1 b = sum e_a e_b / v_t.
double neg2_restricted_loglik(const std::vector<double>& s, const Eigen::MatrixXd& y) {
  const Eigen::Index n = y.rows(), m = y.cols();
  std::vector<double> phi(static_cast<std::size_t>(n), 0.0), previous(phi);
  double v = s[0];
  if (!(v > 0)) return kInf;
  double log_det = std::log(v);
  Eigen::MatrixXd gram = y.row(0).transpose() * y.row(0) / v;
  Eigen::VectorXd e(m);
  for (Eigen::Index t = 1; t < n; ++t) {
    double acc = s[static_cast<std::size_t>(t)];
    for (Eigen::Index j = 1; j < t; ++j) {
      acc -= phi[static_cast<std::size_t>(j)] * s[static_cast<std::size_t>(t - j)];
    }
    const double kappa = acc / v;
    std::copy(phi.begin() + 1, phi.begin() + t, previous.begin() + 1);
    for (Eigen::Index j = 1; j < t; ++j) {
      phi[static_cast<std::size_t>(j)] -= kappa * previous[static_cast<std::size_t>(t - j)];
    }
    phi[static_cast<std::size_t>(t)] = kappa;
    v *= 1.0 - kappa * kappa;
    if (!(v > 0)) return kInf;  // not positive definite
    log_det += std::log(v);
    for (Eigen::Index c = 0; c < m; ++c) {
      const double* col = y.col(c).data();
      double x = col[t];
      for (Eigen::Index j = 1; j <= t; ++j) x -= phi[static_cast<std::size_t>(j)] * col[t - j];
      e(c) = x;
    }
    gram += e * e.transpose() / v;
  }
  if (m == 1) return log_det + gram(0, 0);
  const Eigen::MatrixXd a = gram.bottomRightCorner(m - 1, m - 1);
  const Eigen::VectorXd b = gram.col(0).tail(m - 1);
  const Eigen::LLT<Eigen::MatrixXd> llt(a);
  if (llt.info() != Eigen::Success) return kInf;
  const double log_det_a = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  return log_det + log_det_a + gram(0, 0) - b.dot(llt.solve(b));
}

// Nelder-Mead simplex minimisation (Lagarias et al. 1998 coefficients) of f
// over a box, from x0 with initial steps of `step`.
template <typename F>
std::pair<Eigen::VectorXd, double> minimise(F&& f, Eigen::VectorXd x0, double step) {
  const Eigen::Index d = x0.size();
  auto clamped = [&](Eigen::VectorXd x) {
    for (Eigen::Index i = 0; i < d; ++i) x(i) = std::clamp(x(i), kLowest, kHighest);
    return x;
  };
  std::vector<Eigen::VectorXd> p(static_cast<std::size_t>(d + 1), clamped(x0));
  std::vector<double> fp(p.size());
  for (Eigen::Index i = 0; i < d; ++i) {
    Eigen::VectorXd& q = p[static_cast<std::size_t>(i + 1)];
    q(i) += q(i) + step <= kHighest ? step : -step;
  }
  for (std::size_t i = 0; i < p.size(); ++i) fp[i] = f(p[i]);
  for (int iteration = 0; iteration < 100 * static_cast<int>(d + 1); ++iteration) {
    std::vector<std::size_t> order(p.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return fp[a] < fp[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[order.size() - 2];
    double size = 0.0;
    for (const auto& q : p) size = std::max(size, (q - p[best]).cwiseAbs().maxCoeff());
    if (size < 1e-4 && std::fabs(fp[worst] - fp[best]) < 1e-7) break;
    Eigen::VectorXd centre = Eigen::VectorXd::Zero(d);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (i != worst) centre += p[i] / static_cast<double>(d);
    }
    const Eigen::VectorXd r = clamped(centre + (centre - p[worst]));
    const double fr = f(r);
    if (fr < fp[best]) {
      const Eigen::VectorXd e = clamped(centre + 2.0 * (centre - p[worst]));
      const double fe = f(e);
      if (fe < fr) {
        p[worst] = e, fp[worst] = fe;
      } else {
        p[worst] = r, fp[worst] = fr;
      }
    } else if (fr < fp[second]) {
      p[worst] = r, fp[worst] = fr;
    } else {
      const bool outside = fr < fp[worst];
      const Eigen::VectorXd c = outside ? Eigen::VectorXd(centre + 0.5 * (r - centre))
                                        : Eigen::VectorXd(centre + 0.5 * (p[worst] - centre));
      const double fc = f(c);
      if (fc < (outside ? fr : fp[worst])) {
        p[worst] = c, fp[worst] = fc;
      } else {
        for (std::size_t i = 0; i < p.size(); ++i) {
          if (i == best) continue;
          p[i] = p[best] + 0.5 * (p[i] - p[best]);
          fp[i] = f(p[i]);
        }
      }
    }
  }
  const auto best = static_cast<std::size_t>(std::min_element(fp.begin(), fp.end()) - fp.begin());
  return {p[best], fp[best]};
}

// The data of the likelihood: differenced block means and the differenced
// block means of the removed polynomial's columns (the constant drops out).
struct Blocks {
  Eigen::MatrixXd y;  // (blocks - 1) x (1 + degree)
  double tau_b = 0.0;
  double level = 0.0;  // half the mean squared difference: the Allan variance at tau_b
};

Blocks make_blocks(std::span<const double> rate, std::span<const double> temperature, int degree,
                   double t_ref, double fs, int blocks) {
  const std::size_t length = rate.size() / static_cast<std::size_t>(blocks);
  const int columns = temperature.empty() ? 1 : 1 + std::max(0, degree);
  double scale = 0.0;
  if (columns > 1) {
    for (double t : temperature) scale = std::max(scale, std::fabs(t - t_ref));
    if (!(scale > 0)) scale = 1.0;
  }
  Eigen::MatrixXd means(blocks, columns);
  for (int b = 0; b < blocks; ++b) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(columns);
    for (std::size_t i = static_cast<std::size_t>(b) * length; i < (b + 1) * length; ++i) {
      sum(0) += rate[i];
      double power = 1.0;
      for (int j = 1; j < columns; ++j) {
        power *= (temperature[i] - t_ref) / scale;
        sum(j) += power;
      }
    }
    means.row(b) = sum.transpose() / static_cast<double>(length);
  }
  Blocks r;
  r.y = means.bottomRows(blocks - 1) - means.topRows(blocks - 1);
  r.tau_b = static_cast<double>(length) / fs;
  r.level = 0.5 * r.y.col(0).squaredNorm() / static_cast<double>(r.y.rows());
  // Columns of comparable size keep X' S^-1 X well conditioned.
  for (int j = 1; j < columns; ++j) {
    const double norm = r.y.col(j).norm();
    if (norm > 0) r.y.col(j) /= norm;
  }
  return r;
}

}  // namespace

RandomBiasLikelihood decide_random_bias(std::span<const double> residual_deg_h,
                                        std::span<const double> temperature_c, int degree,
                                        double t_ref_c, double sample_rate_hz,
                                        const NoiseModel& allan_fit,
                                        const RandomBiasOptions& options) {
  RandomBiasLikelihood r;
  const int blocks = static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(options.blocks), residual_deg_h.size() / 4));
  if (blocks < 32 || !(allan_fit.N > 0)) return r;
  const Blocks data =
      make_blocks(residual_deg_h, temperature_c, degree, t_ref_c, sample_rate_hz, blocks);
  if (!(data.level > 0)) return r;
  const auto n = static_cast<std::size_t>(data.y.rows());
  const double tau_b = data.tau_b;
  r.available = true;
  r.blocks = blocks;
  r.block_s = tau_b;

  // The fixed part and the unit covariances; each free variance is written
  // as (its natural size) x e^w, the natural size giving the Allan variance
  // at tau_b the data show.
  const std::vector<double> fixed =
      unit_covariance({.N = allan_fit.N, .Q = allan_fit.Q}, tau_b, n, true);
  const std::vector<double> flicker = unit_covariance({.B = 1.0}, tau_b, n, false);
  const std::vector<double> walk = unit_covariance({.K = 1.0}, tau_b, n, false);
  const double size_b = data.level / (2.0 * std::numbers::ln2 / std::numbers::pi);
  const double size_k = data.level / (tau_b / 3.0);
  auto start = [](double value_squared, double size) {
    return value_squared > 0 ? std::clamp(std::log(value_squared / size), -10.0, 10.0) : -3.0;
  };

  std::vector<double> s(n);
  auto evaluate = [&](const Eigen::VectorXd& w, std::span<const std::vector<double>* const> units,
                      std::span<const double> sizes) {
    s = fixed;
    for (std::size_t u = 0; u < units.size(); ++u) {
      const double a =
          sizes[u] * std::exp(std::clamp(w(static_cast<Eigen::Index>(u)), kLowest, kHighest));
      for (std::size_t k = 0; k < n; ++k) s[k] += a * (*units[u])[k];
    }
    return neg2_restricted_loglik(s, data.y);
  };

  // No random bias: B alone.
  {
    const std::vector<double>* units[] = {&flicker};
    const double sizes[] = {size_b};
    Eigen::VectorXd w0(1);
    w0 << start(allan_fit.B * allan_fit.B, size_b);
    auto [w, f] =
        minimise([&](const Eigen::VectorXd& w) { return evaluate(w, units, sizes); }, w0, 1.0);
    r.none = {true,
              {.N = allan_fit.N, .B = std::sqrt(size_b * std::exp(w(0))), .Q = allan_fit.Q},
              f,
              f,
              0};
  }
  // Wiener: B and K.
  {
    const std::vector<double>* units[] = {&flicker, &walk};
    const double sizes[] = {size_b, size_k};
    Eigen::VectorXd w0(2);
    w0 << start(allan_fit.B * allan_fit.B, size_b), start(allan_fit.K * allan_fit.K, size_k);
    auto [w, f] =
        minimise([&](const Eigen::VectorXd& w) { return evaluate(w, units, sizes); }, w0, 1.0);
    r.wiener = {true,
                {.N = allan_fit.N,
                 .B = std::sqrt(size_b * std::exp(w(0))),
                 .K = std::sqrt(size_k * std::exp(w(1))),
                 .Q = allan_fit.Q},
                f,
                f + options.penalty,
                1};
  }
  // Gauss-Markov: B and sigma at each Tc of a log grid (six per decade, from
  // a quarter block to thirty records), warm-started from the neighbour.
  struct ProfilePoint {
    double ln_tc = 0.0, f = kInf;
    Eigen::VectorXd w;
    double sigma = 0.0, half_width = 0.0;  // ln sigma's conditional 95 % half width
  };
  const double duration = tau_b * blocks;
  std::vector<ProfilePoint> profile;
  {
    const double lo = std::log(tau_b / 4.0), hi = std::log(duration * 30.0);
    const int steps = static_cast<int>(std::ceil((hi - lo) / std::log(10.0) * 6.0));
    Eigen::VectorXd w(2);
    w << start(allan_fit.B * allan_fit.B, size_b), 0.0;
    std::vector<double> gm_unit;
    for (int k = 0; k <= steps; ++k) {
      ProfilePoint point;
      point.ln_tc = lo + (hi - lo) * k / steps;
      const double tc = std::exp(point.ln_tc);
      gm_unit = unit_covariance({.gm_sigma = 1.0, .gm_tc = tc}, tau_b, n, true);
      const std::vector<double>* units[] = {&flicker, &gm_unit};
      const double size_gm =
          data.level / allan_variance({.gm_sigma = 1.0, .gm_tc = tc}, NoiseTerm::gm, tau_b);
      const double sizes[] = {size_b, size_gm};
      auto f = [&](const Eigen::VectorXd& x) { return evaluate(x, units, sizes); };
      auto [best, value] = minimise(f, w, 1.0);
      point.w = best;
      point.f = value;
      point.sigma = std::sqrt(size_gm * std::exp(best(1)));
      // Curvature in (w_B, w_sigma) for sigma's conditional interval.
      const double h = 0.05;
      auto at = [&](double db, double ds) {
        Eigen::VectorXd x = best;
        x(0) += db;
        x(1) += ds;
        return f(x);
      };
      Eigen::Matrix2d hess;
      hess(0, 0) = (at(h, 0) - 2 * value + at(-h, 0)) / (h * h);
      hess(1, 1) = (at(0, h) - 2 * value + at(0, -h)) / (h * h);
      hess(0, 1) = hess(1, 0) = (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4 * h * h);
      double variance = hess(1, 1) > 0 ? 2.0 / hess(1, 1) : kInf;  // of w_sigma, B held
      if (hess.determinant() > 0 && hess(0, 0) > 0) variance = 2.0 * hess.inverse()(1, 1);
      point.half_width = variance;  // stored as a variance until the threshold is known
      profile.push_back(std::move(point));
      w = best;
    }
  }
  const auto best = static_cast<std::size_t>(
      std::min_element(profile.begin(), profile.end(),
                       [](const ProfilePoint& a, const ProfilePoint& b) { return a.f < b.f; }) -
      profile.begin());
  const ProfilePoint& top = profile[best];
  const double tc = std::exp(top.ln_tc);
  r.gauss_markov = {true,
                    {.N = allan_fit.N,
                     .B = std::sqrt(size_b * std::exp(top.w(0))),
                     .Q = allan_fit.Q,
                     .gm_sigma = top.sigma,
                     .gm_tc = tc},
                    top.f,
                    top.f + 2.0 * options.penalty,
                    2};

  // Intervals: Tc where the profile stays within the threshold (linear
  // crossing in ln Tc between grid points), sigma the union of its
  // conditional intervals there.
  const double threshold = top.f + kChi2_95;
  double sigma_low = top.sigma, sigma_high = top.sigma;
  for (const ProfilePoint& p : profile) {
    const double excess = threshold - p.f;
    if (!(excess >= 0)) continue;
    const double half = 0.5 * std::sqrt(excess * p.half_width);  // ln sigma = w/2 + const
    sigma_low = std::min(sigma_low, p.sigma * std::exp(-half));
    sigma_high = std::max(sigma_high, p.sigma * std::exp(half));
  }
  auto crossing = [&](std::size_t inside, std::size_t outside) {
    const double e0 = threshold - profile[inside].f, e1 = threshold - profile[outside].f;
    const double x = std::isfinite(e1) ? e0 / (e0 - e1) : 0.0;
    return std::exp(profile[inside].ln_tc + x * (profile[outside].ln_tc - profile[inside].ln_tc));
  };
  double tc_low = 0.0, tc_high = kInf;
  for (std::size_t k = best; k > 0; --k) {
    if (!(profile[k - 1].f <= threshold)) {
      tc_low = crossing(k, k - 1);
      break;
    }
  }
  for (std::size_t k = best; k + 1 < profile.size(); ++k) {
    if (!(profile[k + 1].f <= threshold)) {
      tc_high = crossing(k, k + 1);
      break;
    }
  }
  if (!std::isfinite(tc_high)) sigma_high = kInf;
  if (tc_low == 0.0) sigma_low = 0.0;
  r.gm_sigma = {top.sigma, sigma_low, sigma_high, kNaN, TermStatus::resolved};
  r.gm_tc = {tc, tc_low, tc_high, kNaN, TermStatus::resolved};

  const RandomBiasHypothesis* chosen = &r.none;
  for (const RandomBiasHypothesis* h : {&r.wiener, &r.gauss_markov}) {
    if (h->criterion < chosen->criterion) chosen = h;
  }
  r.process = chosen == &r.none     ? RandomBiasProcess::none
              : chosen == &r.wiener ? RandomBiasProcess::wiener
                                    : RandomBiasProcess::gauss_markov;
  return r;
}

}  // namespace foglab::model
