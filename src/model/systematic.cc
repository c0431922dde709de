#include "foglab/model/systematic.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxDegree = 3;

void check_inputs(std::span<const double> rate, std::span<const double> temperature,
                  double sample_rate_hz) {
  if (rate.size() != temperature.size()) {
    throw UsageError(fmt::format(
        "temperature fit: the rate has {} samples but the temperature {}; they must pair "
        "sample by sample",
        rate.size(), temperature.size()));
  }
  if (rate.size() < 8) {
    throw UsageError(
        fmt::format("temperature fit: {} samples; at least 8 are needed", rate.size()));
  }
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(
        fmt::format("temperature fit: sample rate {} Hz must be positive", sample_rate_hz));
  }
  for (std::size_t k = 0; k < temperature.size(); ++k) {
    if (!std::isfinite(temperature[k])) {
      throw DataError(fmt::format("temperature sample {} is {}; temperatures must be finite", k + 1,
                                  temperature[k]));
    }
  }
}

// Block means of `values` over `blocks` equal blocks of floor(n / blocks)
// samples (the last few samples, fewer than a block, are left out).
std::vector<double> block_means(std::span<const double> values, int blocks) {
  const std::size_t m = std::min<std::size_t>(static_cast<std::size_t>(blocks), values.size());
  const std::size_t length = values.size() / m;
  std::vector<double> means(m);
  for (std::size_t a = 0; a < m; ++a) {
    means[a] = compensated_mean(values.subspan(a * length, length));
  }
  return means;
}

// Sums over the record of u^p (p = 0..6) and (y - y0) u^j (j = 0..3) with
// u = (T - t_ref) / scale, accumulated per chunk for accuracy.
struct Moments {
  std::array<double, 2 * kMaxDegree + 1> u{};
  std::array<double, kMaxDegree + 1> yu{};
  double yy = 0.0;  // sum of (y - y0)^2
  double y0 = 0.0;
  double t_ref = 0.0, scale = 1.0;
  std::size_t n = 0;
};

Moments moments(std::span<const double> rate, std::span<const double> temperature, double t_ref,
                double scale) {
  Moments m;
  m.n = temperature.size();
  m.t_ref = t_ref;
  m.scale = scale;
  m.y0 = rate.empty() ? 0.0 : compensated_mean(rate);  // empty: the Gram matrix only
  for (std::size_t begin = 0; begin < m.n; begin += kChunkSamples) {
    const std::size_t end = std::min(m.n, begin + kChunkSamples);
    std::array<double, 2 * kMaxDegree + 1> u{};
    std::array<double, kMaxDegree + 1> yu{};
    double yy = 0.0;
    for (std::size_t k = begin; k < end; ++k) {
      const double x = (temperature[k] - t_ref) / scale;
      const double y = rate.empty() ? 0.0 : rate[k] - m.y0;
      yy += y * y;
      double power = 1.0;
      for (int p = 0; p <= 2 * kMaxDegree; ++p) {
        u[p] += power;
        if (p <= kMaxDegree) yu[p] += y * power;
        power *= x;
      }
    }
    for (int p = 0; p <= 2 * kMaxDegree; ++p) m.u[p] += u[p];
    for (int p = 0; p <= kMaxDegree; ++p) m.yu[p] += yu[p];
    m.yy += yy;
  }
  return m;
}

Eigen::MatrixXd gram(const Moments& m, int degree) {
  Eigen::MatrixXd g(degree + 1, degree + 1);
  for (int i = 0; i <= degree; ++i) {
    for (int j = 0; j <= degree; ++j) g(i, j) = m.u[i + j];
  }
  return g;
}

// Least-squares coefficients in the scaled variable u (beta_0 includes y0).
Eigen::VectorXd solve_scaled(const Moments& m, int degree) {
  Eigen::VectorXd rhs(degree + 1);
  for (int j = 0; j <= degree; ++j) rhs(j) = m.yu[j];
  Eigen::VectorXd beta = gram(m, degree).colPivHouseholderQr().solve(rhs);
  beta(0) += m.y0;
  return beta;
}

// Coefficients of (T - t_ref)^j from those of u^j.
std::vector<double> unscale(const Eigen::VectorXd& beta, double scale) {
  std::vector<double> c(static_cast<std::size_t>(beta.size()));
  for (Eigen::Index j = 0; j < beta.size(); ++j) c[j] = beta(j) / std::pow(scale, double(j));
  return c;
}

// polyfit(T, Y, 2) in MATLAB order from the quadratic about t_ref.
std::vector<double> raw_quadratic(const std::vector<double>& c, double t_ref) {
  const double c0 = c[0], c1 = c.size() > 1 ? c[1] : 0.0, c2 = c.size() > 2 ? c[2] : 0.0;
  return {c2, c1 - 2.0 * c2 * t_ref, c0 - c1 * t_ref + c2 * t_ref * t_ref};
}

// Phase structure functions D_x(s) = E[(x(t+s) - x(t))^2] of the noise
// terms, x the integrated rate [(deg/h) s], s >= 0. Stationary terms (finite
// variance): white N^2 s, Gauss-Markov 2 sigma^2 Tc^2 (s/Tc - 1 + e^(-s/Tc)),
// quantisation 2 Q^2 (s > 0). Flicker: -2 h s^2 ln s with h = B^2/(2 pi)
// (two-sided PSD h/|f|, up to an s^2 term that every second difference
// cancels). The Wiener term K^2 s^3/3 is written out in block_covariance().
double stationary_structure(const NoiseModel& m, double s) {
  if (s <= 0) return 0.0;
  double d = m.N * m.N * s + 2.0 * m.Q * m.Q;
  if (m.gm_sigma > 0 && m.gm_tc > 0) {
    const double x = s / m.gm_tc;
    const double e = x < 1e-4 ? x * x * (0.5 - x / 6.0) : x - 1.0 + std::exp(-x);
    d += 2.0 * m.gm_sigma * m.gm_sigma * m.gm_tc * m.gm_tc * e;
  }
  return d;
}

double flicker_structure(const NoiseModel& m, double s) {
  if (s <= 0) return 0.0;
  return -2.0 * (m.B * m.B / (2.0 * std::numbers::pi)) * s * s * std::log(s);
}

// Covariance of block means (blocks of tau seconds) at lags 0..lags-1, from
// Cov = Var - E[(ybar_a - ybar_b)^2]/2 and
// E[(ybar_a - ybar_{a+k})^2] = (2 D(tau) + 2 D(k tau) - D((k+1) tau) - D(|k-1| tau)) / tau^2.
// The non-stationary terms (flicker, Wiener) have no variance; they are given
// up to a matrix f(a) + f(b), which changes only the intercept's variance.
// The Wiener rate W has stationary increments itself: block means k >= 1
// apart differ by the average of lag-k tau increments that overlap by
// k tau - |s - u|, so E[(ybar_a - ybar_{a+k})^2] = K^2 (k tau - tau/3).
std::vector<double> block_covariance(const NoiseModel& m, double tau, std::size_t lags,
                                     bool stationary) {
  auto second = [&](auto&& d, double k) {
    return (2.0 * d(tau) + 2.0 * d(k * tau) - d((k + 1.0) * tau) - d(std::fabs(k - 1.0) * tau)) /
           (tau * tau);
  };
  auto s_fn = [&](double s) { return stationary_structure(m, s); };
  auto f_fn = [&](double s) { return flicker_structure(m, s); };
  std::vector<double> c(lags);
  for (std::size_t k = 0; k < lags; ++k) {
    const double kk = static_cast<double>(k);
    if (stationary) {
      c[k] = stationary_structure(m, tau) / (tau * tau) - 0.5 * second(s_fn, kk);
    } else {
      c[k] = -0.5 * second(f_fn, kk) - (k > 0 ? 0.5 * m.K * m.K * tau * (kk - 1.0 / 3.0) : 0.0);
    }
  }
  return c;
}

// Block means of (T - t_ref)^j / scale^j, j = 0..degree, over m blocks of
// `length` samples.
Eigen::MatrixXd block_regressors(std::span<const double> temperature, double t_ref, double scale,
                                 int degree, std::size_t m, std::size_t length) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(m), degree + 1);
  for (std::size_t a = 0; a < m; ++a) {
    std::array<double, kMaxDegree + 1> sums{};
    for (std::size_t k = a * length; k < (a + 1) * length; ++k) {
      const double u = (temperature[k] - t_ref) / scale;
      double power = 1.0;
      for (int j = 0; j <= degree; ++j) {
        sums[j] += power;
        power *= u;
      }
    }
    for (int j = 0; j <= degree; ++j) {
      x(static_cast<Eigen::Index>(a), j) = sums[j] / static_cast<double>(length);
    }
  }
  return x;
}

// Sigma * x for the symmetric Toeplitz matrix of lag covariances c.
Eigen::MatrixXd toeplitz_times(const std::vector<double>& c, const Eigen::MatrixXd& x) {
  const Eigen::Index m = x.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(m, x.cols());
  for (Eigen::Index a = 0; a < m; ++a) {
    for (Eigen::Index b = 0; b < m; ++b) {
      out.row(a) += c[static_cast<std::size_t>(a > b ? a - b : b - a)] * x.row(b);
    }
  }
  return out;
}

// The overlapping Allan quadratic form at lag m on block means: the
// differences d_i = w_{i+m} - w_i of m-block averages w, A z = D'D z/(2 n).
Eigen::MatrixXd allan_form_times(const Eigen::MatrixXd& z, std::size_t m) {
  const std::size_t total = static_cast<std::size_t>(z.rows());
  const std::size_t n = total - 2 * m + 1;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(z.rows(), z.cols());
  for (Eigen::Index col = 0; col < z.cols(); ++col) {
    std::vector<double> cum(total + 1, 0.0);
    for (std::size_t k = 0; k < total; ++k)
      cum[k + 1] = cum[k] + z(static_cast<Eigen::Index>(k), col);
    std::vector<double> mark(total + 1, 0.0);  // difference array of D'd
    const double inv = 1.0 / static_cast<double>(m);
    for (std::size_t i = 0; i < n; ++i) {
      const double d = ((cum[i + 2 * m] - cum[i + m]) - (cum[i + m] - cum[i])) * inv;
      mark[i] -= d * inv;
      mark[i + m] += 2.0 * d * inv;
      mark[i + 2 * m] -= d * inv;
    }
    double run = 0.0;
    for (std::size_t k = 0; k < total; ++k) {
      run += mark[k];
      out(static_cast<Eigen::Index>(k), col) = run / (2.0 * static_cast<double>(n));
    }
  }
  return out;
}

// tr(A_m Sigma) for Toeplitz Sigma: every difference is the same filter h
// (-1/m on m blocks, +1/m on the next m), so the trace is half of
// sum_k r_h(k) c_k over both signs of k.
double allan_trace(const std::vector<double>& r_h, const std::vector<double>& c) {
  double t = r_h[0] * c[0];
  for (std::size_t k = 1; k < r_h.size() && k < c.size(); ++k) t += 2.0 * r_h[k] * c[k];
  return 0.5 * t;
}

std::vector<double> filter_autocorrelation(std::size_t m) {
  std::vector<double> h(2 * m);
  for (std::size_t p = 0; p < 2 * m; ++p) h[p] = (p < m ? -1.0 : 1.0) / static_cast<double>(m);
  std::vector<double> r(2 * m, 0.0);
  for (std::size_t k = 0; k < 2 * m; ++k) {
    for (std::size_t p = 0; p + k < 2 * m; ++p) r[k] += h[p] * h[p + k];
  }
  return r;
}

// X' Sigma X for the scaled columns u^j, j = 0..degree, from block means:
// sum_k x_k y_k ~ L sum_a xbar_a ybar_a; the stationary terms' (first) and the others'.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> middle(std::span<const double> temperature,
                                                   double sample_rate_hz, double t_ref,
                                                   double scale, int degree,
                                                   const NoiseModel& noise, int blocks) {
  const std::size_t m = std::min<std::size_t>(static_cast<std::size_t>(blocks), temperature.size());
  const std::size_t length = temperature.size() / m;
  const double tau = static_cast<double>(length) / sample_rate_hz;
  const Eigen::MatrixXd x = block_regressors(temperature, t_ref, scale, degree, m, length);
  const double l = static_cast<double>(length) *
                   (static_cast<double>(temperature.size()) / static_cast<double>(m * length));
  auto form = [&](bool stationary) -> Eigen::MatrixXd {
    return l * l * (x.transpose() * toeplitz_times(block_covariance(noise, tau, m, stationary), x));
  };
  return {form(true), form(false)};
}

double polynomial(const std::vector<double>& c, double u) {
  double value = 0.0;
  for (auto it = c.rbegin(); it != c.rend(); ++it) value = value * u + *it;
  return value;
}

// RMS of the residual of the degree-d fit from the moments alone (no pass
// over the record): sum (y - Xb)^2 = yy - 2 b'X'y + b'X'X b, b the scaled
// coefficients of y - y0.
double residual_rms(const Moments& mo, int degree) {
  Eigen::VectorXd rhs(degree + 1);
  for (int j = 0; j <= degree; ++j) rhs(j) = mo.yu[j];
  const Eigen::MatrixXd g = gram(mo, degree);
  const Eigen::VectorXd b = g.colPivHouseholderQr().solve(rhs);
  const double ss = mo.yy - 2.0 * b.dot(rhs) + b.dot(g * b);
  return std::sqrt(std::max(0.0, ss) / static_cast<double>(mo.n));
}

double temperature_scale(std::span<const double> temperature, double t_ref) {
  double ss = 0.0;
  for (double t : temperature) ss += (t - t_ref) * (t - t_ref);
  const double sd = std::sqrt(ss / static_cast<double>(temperature.size()));
  return sd > 0 ? sd : 1.0;
}

// Covariance of the scaled coefficients: the slopes from every term, the
// intercept from the stationary ones.
Eigen::MatrixXd scaled_covariance(std::span<const double> temperature, double sample_rate_hz,
                                  const Moments& mo, int degree, const NoiseModel& noise,
                                  int blocks) {
  const Eigen::MatrixXd inv = gram(mo, degree).inverse();
  const auto [stationary, walk] =
      middle(temperature, sample_rate_hz, mo.t_ref, mo.scale, degree, noise, blocks);
  Eigen::MatrixXd cov = inv * (stationary + walk) * inv;
  const Eigen::MatrixXd intercept_only = inv * stationary * inv;
  cov(0, 0) = intercept_only(0, 0);
  return cov;
}

}  // namespace

SystematicFit fit_temperature(std::span<const double> rate_deg_h,
                              std::span<const double> temperature_c, double sample_rate_hz,
                              const SystematicOptions& options) {
  check_inputs(rate_deg_h, temperature_c, sample_rate_hz);
  if (options.degree < -1 || options.degree > kMaxDegree || options.max_degree < 0 ||
      options.max_degree > kMaxDegree) {
    throw UsageError(fmt::format("temperature fit: degree {} (max {}) must be 0..3 (or auto)",
                                 options.degree, options.max_degree));
  }
  SystematicFit fit;
  fit.t_ref_c = compensated_mean(temperature_c);
  const std::vector<double> means = block_means(temperature_c, options.blocks);
  const auto [lo, hi] = std::minmax_element(means.begin(), means.end());
  fit.temperature_min_c = *lo;
  fit.temperature_max_c = *hi;
  fit.temperature_span_c = *hi - *lo;
  const double scale = temperature_scale(temperature_c, fit.t_ref_c);
  const Moments mo = moments(rate_deg_h, temperature_c, fit.t_ref_c, scale);

  const Eigen::VectorXd quadratic = solve_scaled(mo, 2);
  fit.lab_polyfit = raw_quadratic(unscale(quadratic, scale), fit.t_ref_c);
  fit.lab_constant_term_deg_h = fit.lab_polyfit[2];

  const bool too_flat = fit.temperature_span_c < options.min_span_c;
  if (too_flat) {
    fit.degree = 0;
    fit.constant_fallback = true;
    fit.lab_constant_meaningful = false;
    fit.note = fmt::format(
        "the temperature moves by only {:.3g} degC (block means; below {:.3g} degC), too little "
        "to see a temperature dependence: the systematic part is a constant, the mean rate{}",
        fit.temperature_span_c, options.min_span_c,
        options.degree > 0 ? fmt::format(" (degree {} was asked for)", options.degree) : "");
  } else if (options.degree >= 0) {
    fit.degree = options.degree;
    fit.note = fmt::format("polynomial of degree {} in temperature, as asked", fit.degree);
  } else {
    fit.degree = options.max_degree;
    fit.degree_chosen = true;
  }
  fit.coefficients = unscale(solve_scaled(mo, fit.degree), scale);
  fit.standard_errors.assign(fit.coefficients.size(), kNaN);
  fit.bias_deg_h = fit.coefficients[0];
  fit.residual_rms_deg_h = residual_rms(mo, fit.degree);
  return fit;
}

DetrendFactors detrend_factors(std::span<const double> temperature_c, double sample_rate_hz,
                               double t_ref_c, int degree, std::span<const double> tau_s,
                               int blocks) {
  if (degree < 0 || degree > kMaxDegree) {
    throw UsageError(fmt::format("temperature fit: degree {} must be 0..3", degree));
  }
  DetrendFactors f;
  f.tau_s.assign(tau_s.begin(), tau_s.end());
  const std::size_t count = tau_s.size();
  for (auto& v : f.linear) v.assign(count, 1.0);
  if (count == 0) return f;
  const std::size_t m_blocks = std::min<std::size_t>(
      static_cast<std::size_t>(blocks), std::max<std::size_t>(16, temperature_c.size() / 4));
  const std::size_t length = temperature_c.size() / m_blocks;
  if (length == 0) return f;
  const double tau_b = static_cast<double>(length) / sample_rate_hz;
  const double scale = temperature_scale(temperature_c, t_ref_c);
  const Eigen::MatrixXd x =
      block_regressors(temperature_c, t_ref_c, scale, degree, m_blocks, length);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(x).householderQ() *
                            Eigen::MatrixXd::Identity(x.rows(), x.cols());

  // Block lag of each tau (at least 1, at most what the blocks hold), and
  // the Allan form applied to Q at each distinct lag.
  const std::size_t max_lag = (m_blocks - 1) / 2;
  std::vector<std::size_t> lag(count);
  std::map<std::size_t, std::pair<std::vector<double>, Eigen::MatrixXd>> forms;
  for (std::size_t i = 0; i < count; ++i) {
    lag[i] = std::clamp<std::size_t>(static_cast<std::size_t>(std::llround(tau_s[i] / tau_b)), 1,
                                     max_lag);
    if (!forms.count(lag[i])) {
      forms[lag[i]] = {filter_autocorrelation(lag[i]), allan_form_times(q, lag[i])};
    }
  }
  // The factor of one covariance (lag covariances c) at every tau.
  auto factors_of = [&](const std::vector<double>& c) {
    const Eigen::MatrixXd sq = toeplitz_times(c, q);
    const Eigen::MatrixXd qsq = q.transpose() * sq;
    std::vector<double> out(count, 1.0);
    for (std::size_t i = 0; i < count; ++i) {
      const auto& [r_h, aq] = forms.at(lag[i]);
      const double tr_as = allan_trace(r_h, c);
      const double tr_aps = (sq.array() * aq.array()).sum();
      const double tr_paps = ((q.transpose() * aq) * qsq).trace();
      double factor = tr_as > 0 ? (tr_as - 2.0 * tr_aps + tr_paps) / tr_as : 1.0;
      factor = std::clamp(factor, 1e-3, 1.0);
      const double ratio = tau_s[i] / tau_b;
      if (ratio < 1.0) factor = 1.0 - (1.0 - factor) * ratio;
      out[i] = factor;
    }
    return out;
  };
  const std::pair<NoiseTerm, NoiseModel> units[] = {{NoiseTerm::N, {.N = 1.0}},
                                                    {NoiseTerm::B, {.B = 1.0}},
                                                    {NoiseTerm::K, {.K = 1.0}},
                                                    {NoiseTerm::Q, {.Q = 1.0}}};
  for (const auto& [term, unit] : units) {
    const bool stationary = term == NoiseTerm::N || term == NoiseTerm::Q;
    f.linear[static_cast<int>(term)] =
        factors_of(block_covariance(unit, tau_b, m_blocks, stationary));
  }
  // The rate ramp is deterministic: the residual's Allan variance over the ramp's.
  {
    Eigen::MatrixXd ramp(static_cast<Eigen::Index>(m_blocks), 1);
    for (std::size_t a = 0; a < m_blocks; ++a) {
      ramp(static_cast<Eigen::Index>(a), 0) = (static_cast<double>(a) + 0.5) * tau_b;
    }
    const Eigen::MatrixXd residual = ramp - q * (q.transpose() * ramp);
    for (std::size_t i = 0; i < count; ++i) {
      const double before = (ramp.transpose() * allan_form_times(ramp, lag[i]))(0, 0);
      const double after = (residual.transpose() * allan_form_times(residual, lag[i]))(0, 0);
      double factor = std::clamp(before > 0 ? after / before : 1.0, 1e-3, 1.0);
      const double ratio = tau_s[i] / tau_b;
      if (ratio < 1.0) factor = 1.0 - (1.0 - factor) * ratio;
      f.linear[static_cast<int>(NoiseTerm::R)][i] = factor;
    }
  }
  const double lo = std::log(tau_s.front() * 0.5), hi = std::log(tau_s.back() * 30.0);
  const int steps = std::max(2, static_cast<int>(std::ceil((hi - lo) / std::log(10.0) * 8.0)));
  for (int s = 0; s <= steps; ++s) {
    const double tc = std::exp(lo + (hi - lo) * s / steps);
    f.gm_tc_s.push_back(tc);
    f.gm.push_back(
        factors_of(block_covariance({.gm_sigma = 1.0, .gm_tc = tc}, tau_b, m_blocks, true)));
  }
  return f;
}

std::vector<double> coefficient_covariance(std::span<const double> temperature_c,
                                           double sample_rate_hz, double t_ref_c, int degree,
                                           const NoiseModel& noise, int blocks) {
  if (degree < 0 || degree > kMaxDegree) {
    throw UsageError(fmt::format("temperature fit: degree {} must be 0..3", degree));
  }
  const double scale = temperature_scale(temperature_c, t_ref_c);
  const Moments mo = moments({}, temperature_c, t_ref_c, scale);
  const Eigen::MatrixXd cov =
      scaled_covariance(temperature_c, sample_rate_hz, mo, degree, noise, blocks);
  std::vector<double> out(static_cast<std::size_t>((degree + 1) * (degree + 1)));
  for (int i = 0; i <= degree; ++i) {
    for (int j = 0; j <= degree; ++j) {
      out[static_cast<std::size_t>(i * (degree + 1) + j)] =
          cov(i, j) / (std::pow(scale, double(i)) * std::pow(scale, double(j)));
    }
  }
  return out;
}

SystematicFit finish_temperature_fit(const SystematicFit& first, std::span<const double> rate_deg_h,
                                     std::span<const double> temperature_c, double sample_rate_hz,
                                     const NoiseModel& noise, const SystematicOptions& options) {
  check_inputs(rate_deg_h, temperature_c, sample_rate_hz);
  SystematicFit fit = first;
  const double scale = temperature_scale(temperature_c, fit.t_ref_c);
  const Moments mo = moments(rate_deg_h, temperature_c, fit.t_ref_c, scale);
  if (fit.degree_chosen && !fit.constant_fallback) {
    const int top = options.max_degree;
    const Eigen::VectorXd beta = solve_scaled(mo, top);
    const Eigen::MatrixXd cov =
        scaled_covariance(temperature_c, sample_rate_hz, mo, top, noise, options.blocks);
    const double penalty = options.degree_penalty;
    fit.criterion.assign(static_cast<std::size_t>(top + 1), 0.0);
    for (int d = 0; d < top; ++d) {
      const int k = top - d;
      const Eigen::VectorXd b = beta.tail(k);
      const Eigen::MatrixXd v = cov.bottomRightCorner(k, k);
      fit.criterion[static_cast<std::size_t>(d)] = b.dot(v.ldlt().solve(b)) + penalty * d;
    }
    fit.criterion[static_cast<std::size_t>(top)] = penalty * top;
    const int best = static_cast<int>(std::min_element(fit.criterion.begin(), fit.criterion.end()) -
                                      fit.criterion.begin());
    fit.degree = best;
    fit.note = fmt::format(
        "degree {} chosen by the criterion W_d + {:.3g} d (Wald statistic of the higher "
        "coefficients with the noise model's covariance) = {:.4g} for d = 0..{}",
        best, penalty, fmt::join(fit.criterion, ", "), top);
  }
  fit.coefficients = unscale(solve_scaled(mo, fit.degree), scale);
  fit.bias_deg_h = fit.coefficients[0];
  set_standard_errors(fit, temperature_c, sample_rate_hz, noise, options.blocks);
  fit.residual_rms_deg_h = residual_rms(mo, fit.degree);
  return fit;
}

void set_standard_errors(SystematicFit& fit, std::span<const double> temperature_c,
                         double sample_rate_hz, const NoiseModel& noise, int blocks) {
  const std::vector<double> cov =
      coefficient_covariance(temperature_c, sample_rate_hz, fit.t_ref_c, fit.degree, noise, blocks);
  fit.standard_errors.assign(static_cast<std::size_t>(fit.degree + 1), 0.0);
  for (int j = 0; j <= fit.degree; ++j) {
    fit.standard_errors[static_cast<std::size_t>(j)] =
        std::sqrt(std::max(0.0, cov[static_cast<std::size_t>(j * (fit.degree + 1) + j)]));
  }
}

void subtract_temperature_fit(const SystematicFit& fit, std::span<double> rate_deg_h,
                              std::span<const double> temperature_c) {
  if (rate_deg_h.size() != temperature_c.size()) {
    throw UsageError(fmt::format("temperature fit: {} rate and {} temperature samples",
                                 rate_deg_h.size(), temperature_c.size()));
  }
  for (std::size_t k = 0; k < rate_deg_h.size(); ++k) {
    rate_deg_h[k] -= polynomial(fit.coefficients, temperature_c[k] - fit.t_ref_c);
  }
}

}  // namespace foglab::model
