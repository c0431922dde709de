#include "foglab/model/systematic.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "block_covariance.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

using detail::block_covariance;
using detail::TermGroup;

constexpr int kMaxDegree = 3;
constexpr double kAbsoluteZeroC = -273.15;  ///< [degC]

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
    if (temperature[k] < kAbsoluteZeroC) {
      throw DataError(fmt::format(
          "temperature sample {} is {} degC, below absolute zero ({} degC): the temperature "
          "channel must be in degC (is it the right channel?)",
          k + 1, temperature[k], kAbsoluteZeroC));
    }
  }
}

// Block means of `values` over `blocks` equal blocks of floor(n / blocks)
// samples (the last few samples, fewer than a block, are left out).
std::vector<double> block_means(std::span<const double> values, int blocks) {
  const std::size_t m = std::min<std::size_t>(static_cast<std::size_t>(blocks), values.size());
  const std::size_t length = values.size() / m;
  std::vector<double> means(m);
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < m; ++a) {
    means[a] = compensated_mean(values.subspan(a * length, length));
  }
  return means;
}

// Sums over the record of u^p (p = 0..6) and (y - y0) u^j (j = 0..3) with
// u = (T - t_ref) / scale, accumulated per chunk for accuracy (the chunks in
// parallel, added in order).
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
  const std::size_t chunks = (m.n + kChunkSamples - 1) / kChunkSamples;
  std::vector<Moments> partial(chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(m.n, begin + kChunkSamples);
    Moments& part = partial[c];
    for (std::size_t k = begin; k < end; ++k) {
      const double x = (temperature[k] - t_ref) / scale;
      const double y = rate.empty() ? 0.0 : rate[k] - m.y0;
      part.yy += y * y;
      double power = 1.0;
      for (int p = 0; p <= 2 * kMaxDegree; ++p) {
        part.u[p] += power;
        if (p <= kMaxDegree) part.yu[p] += y * power;
        power *= x;
      }
    }
  }
  for (const Moments& part : partial) {
    for (int p = 0; p <= 2 * kMaxDegree; ++p) m.u[p] += part.u[p];
    for (int p = 0; p <= kMaxDegree; ++p) m.yu[p] += part.yu[p];
    m.yy += part.yy;
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

// Block means of u^j = (T - t_ref)^j / scale^j, j = 0..3, over `count`
// blocks of floor(n / count) samples (the blocks in parallel). The columns
// of a fit of degree d are the first d + 1.
struct BlockPowers {
  std::size_t count = 0, length = 0;
  Eigen::MatrixXd means;  // count x 4
};

BlockPowers block_powers(std::span<const double> temperature, double t_ref, double scale,
                         std::size_t count) {
  BlockPowers b;
  b.count = count;
  b.length = count > 0 ? temperature.size() / count : 0;
  b.means = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(count), kMaxDegree + 1);
  if (b.length == 0) return b;
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < count; ++a) {
    std::array<double, kMaxDegree + 1> sums{};
    for (std::size_t k = a * b.length; k < (a + 1) * b.length; ++k) {
      const double u = (temperature[k] - t_ref) / scale;
      double power = 1.0;
      for (int j = 0; j <= kMaxDegree; ++j) {
        sums[j] += power;
        power *= u;
      }
    }
    for (int j = 0; j <= kMaxDegree; ++j) {
      b.means(static_cast<Eigen::Index>(a), j) = sums[j] / static_cast<double>(b.length);
    }
  }
  return b;
}

// Sigma * x for the symmetric Toeplitz matrix of lag covariances c (each
// sum in the order of b).
Eigen::MatrixXd toeplitz_times(const std::vector<double>& c, const Eigen::MatrixXd& x) {
  const Eigen::Index m = x.rows();
  Eigen::MatrixXd out(m, x.cols());
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const double* column = x.col(j).data();
    for (Eigen::Index a = 0; a < m; ++a) {
      double sum = 0.0;
      for (Eigen::Index b = 0; b < a; ++b) sum += c[static_cast<std::size_t>(a - b)] * column[b];
      for (Eigen::Index b = a; b < m; ++b) sum += c[static_cast<std::size_t>(b - a)] * column[b];
      out(a, j) = sum;
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
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> middle(const BlockPowers& blocks, std::size_t samples,
                                                   double sample_rate_hz, int degree,
                                                   const NoiseModel& noise) {
  const std::size_t m = blocks.count;
  const std::size_t length = blocks.length;
  const double tau = static_cast<double>(length) / sample_rate_hz;
  const Eigen::MatrixXd x = blocks.means.leftCols(degree + 1);
  const double l = static_cast<double>(length) *
                   (static_cast<double>(samples) / static_cast<double>(m * length));
  auto form = [&](TermGroup group) -> Eigen::MatrixXd {
    return l * l * (x.transpose() * toeplitz_times(block_covariance(noise, tau, m, group), x));
  };
  return {form(TermGroup::stationary), form(TermGroup::non_stationary)};
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

}  // namespace

struct TemperatureRecord::Sums {
  std::size_t samples = 0;
  double sample_rate_hz = 0.0;  // [Hz]
  double t_ref = 0.0, scale = 1.0;
  double block_min = 0.0, block_max = 0.0;  // [degC] of the block-mean temperature
  Moments moments;                          // with the rate (if one was given)
  BlockPowers covariance, detrend;
};

namespace {

using Sums = TemperatureRecord::Sums;

// The sums of a record about `t_ref`; `blocks` and `detrend_blocks` 0 leave
// out the corresponding block means.
Sums summarize(std::span<const double> rate, std::span<const double> temperature,
               double sample_rate_hz, double t_ref, int blocks, int detrend_blocks) {
  Sums s;
  s.samples = temperature.size();
  s.sample_rate_hz = sample_rate_hz;
  s.t_ref = t_ref;
  s.scale = temperature_scale(temperature, t_ref);
  s.moments = moments(rate, temperature, t_ref, s.scale);
  if (blocks > 0) {
    const std::vector<double> means = block_means(temperature, blocks);
    const auto [lo, hi] = std::minmax_element(means.begin(), means.end());
    s.block_min = *lo;
    s.block_max = *hi;
    s.covariance = block_powers(temperature, t_ref, s.scale,
                                std::min<std::size_t>(static_cast<std::size_t>(blocks), s.samples));
  }
  if (detrend_blocks > 0) {
    const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(detrend_blocks),
                                                    std::max<std::size_t>(16, s.samples / 4));
    s.detrend = block_powers(temperature, t_ref, s.scale, count);
  }
  return s;
}

// Covariance of the scaled coefficients: the slopes from every term, the
// intercept from the stationary ones.
Eigen::MatrixXd scaled_covariance(const Sums& s, int degree, const NoiseModel& noise) {
  const Eigen::MatrixXd inv = gram(s.moments, degree).inverse();
  const auto [stationary, walk] = middle(s.covariance, s.samples, s.sample_rate_hz, degree, noise);
  Eigen::MatrixXd cov = inv * (stationary + walk) * inv;
  const Eigen::MatrixXd intercept_only = inv * stationary * inv;
  cov(0, 0) = intercept_only(0, 0);
  return cov;
}

void check_degree(int degree) {
  if (degree < 0 || degree > kMaxDegree) {
    throw UsageError(fmt::format("temperature fit: degree {} must be 0..3", degree));
  }
}

// coefficient_covariance() from the sums.
std::vector<double> covariance_of(const Sums& s, int degree, const NoiseModel& noise) {
  check_degree(degree);
  const Eigen::MatrixXd cov = scaled_covariance(s, degree, noise);
  std::vector<double> out(static_cast<std::size_t>((degree + 1) * (degree + 1)));
  for (int i = 0; i <= degree; ++i) {
    for (int j = 0; j <= degree; ++j) {
      out[static_cast<std::size_t>(i * (degree + 1) + j)] =
          cov(i, j) / (std::pow(s.scale, double(i)) * std::pow(s.scale, double(j)));
    }
  }
  return out;
}

void set_errors(SystematicFit& fit, const Sums& s, const NoiseModel& noise) {
  const std::vector<double> cov = covariance_of(s, fit.degree, noise);
  fit.standard_errors.assign(static_cast<std::size_t>(fit.degree + 1), 0.0);
  for (int j = 0; j <= fit.degree; ++j) {
    fit.standard_errors[static_cast<std::size_t>(j)] =
        std::sqrt(std::max(0.0, cov[static_cast<std::size_t>(j * (fit.degree + 1) + j)]));
  }
}

// detrend_factors() from the sums.
DetrendFactors detrend_of(const Sums& s, int degree, std::span<const double> tau_s) {
  check_degree(degree);
  DetrendFactors f;
  f.tau_s.assign(tau_s.begin(), tau_s.end());
  const std::size_t count = tau_s.size();
  for (auto& v : f.linear) v.assign(count, 1.0);
  if (count == 0) return f;
  const std::size_t m_blocks = s.detrend.count;
  const std::size_t length = s.detrend.length;
  if (length == 0) return f;
  const double tau_b = static_cast<double>(length) / s.sample_rate_hz;
  const Eigen::MatrixXd x = s.detrend.means.leftCols(degree + 1);
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
  const std::pair<NoiseTerm, NoiseModel> units[] = {{NoiseTerm::white, {.N = 1.0}},
                                                    {NoiseTerm::flicker, {.B = 1.0}},
                                                    {NoiseTerm::random_walk, {.K = 1.0}},
                                                    {NoiseTerm::quantisation, {.Q = 1.0}}};
  for (const auto& [term, unit] : units) {
    const TermGroup group = term == NoiseTerm::white || term == NoiseTerm::quantisation
                                ? TermGroup::stationary
                                : TermGroup::non_stationary;
    f.linear[static_cast<int>(term)] = factors_of(block_covariance(unit, tau_b, m_blocks, group));
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
      f.linear[static_cast<int>(NoiseTerm::ramp)][i] = factor;
    }
  }
  // The Gauss-Markov grid: each Tc on its own (in parallel).
  const double lo = std::log(tau_s.front() * 0.5), hi = std::log(tau_s.back() * 30.0);
  const int steps = std::max(2, static_cast<int>(std::ceil((hi - lo) / std::log(10.0) * 8.0)));
  f.gm_tc_s.resize(static_cast<std::size_t>(steps) + 1);
  f.gm.resize(static_cast<std::size_t>(steps) + 1);
#pragma omp parallel for schedule(dynamic)
  for (int step = 0; step <= steps; ++step) {
    const double tc = std::exp(lo + (hi - lo) * step / steps);
    f.gm_tc_s[static_cast<std::size_t>(step)] = tc;
    f.gm[static_cast<std::size_t>(step)] = factors_of(
        block_covariance({.gm_sigma = 1.0, .gm_tc = tc}, tau_b, m_blocks, TermGroup::stationary));
  }
  return f;
}

void check_options(const SystematicOptions& options) {
  if (options.degree < -1 || options.degree > kMaxDegree || options.max_degree < 0 ||
      options.max_degree > kMaxDegree) {
    throw UsageError(fmt::format("temperature fit: degree {} (max {}) must be 0..3 (or auto)",
                                 options.degree, options.max_degree));
  }
}

// fit_temperature() from the sums.
SystematicFit fit_of(const Sums& s, const SystematicOptions& options) {
  check_options(options);
  const Moments& mo = s.moments;
  SystematicFit fit;
  fit.t_ref_c = s.t_ref;
  fit.temperature_min_c = s.block_min;
  fit.temperature_max_c = s.block_max;
  fit.temperature_span_c = s.block_max - s.block_min;

  const Eigen::VectorXd quadratic = solve_scaled(mo, 2);
  fit.lab_polyfit = raw_quadratic(unscale(quadratic, s.scale), fit.t_ref_c);
  fit.lab_constant_term_deg_h = fit.lab_polyfit[2];

  const bool too_flat = fit.temperature_span_c < options.min_span_c;
  if (too_flat) {
    fit.degree = 0;
    fit.constant_fallback = true;
    fit.lab_constant_meaningful = false;
    fit.note =
        Message(Text::temp_too_flat, fit.temperature_span_c, options.min_span_c,
                options.degree > 0 ? Message(Text::temp_degree_asked, options.degree) : Message());
  } else if (options.degree >= 0) {
    fit.degree = options.degree;
    fit.note = Message(Text::temp_as_asked, fit.degree);
  } else {
    fit.degree = options.max_degree;
    fit.degree_chosen = true;
  }
  fit.coefficients = unscale(solve_scaled(mo, fit.degree), s.scale);
  fit.standard_errors.assign(fit.coefficients.size(), kNaN);
  fit.bias_deg_h = fit.coefficients[0];
  fit.residual_rms_deg_h = residual_rms(mo, fit.degree);
  return fit;
}

// The criterion W_d + p d, d = 0..max_degree, of the fit with the highest
// degree under `noise` into fit.criterion, and the degree it chooses from
// `lowest` up into fit.criterion_degree.
void set_criterion(SystematicFit& fit, const Sums& s, const NoiseModel& noise,
                   const SystematicOptions& options, int lowest) {
  const int top = options.max_degree;
  const Eigen::VectorXd beta = solve_scaled(s.moments, top);
  const Eigen::MatrixXd cov = scaled_covariance(s, top, noise);
  const double penalty = options.degree_penalty;
  fit.criterion_penalty = penalty;
  fit.criterion.assign(static_cast<std::size_t>(top + 1), 0.0);
  for (int d = 0; d < top; ++d) {
    const int k = top - d;
    const Eigen::VectorXd b = beta.tail(k);
    const Eigen::MatrixXd v = cov.bottomRightCorner(k, k);
    fit.criterion[static_cast<std::size_t>(d)] = b.dot(v.ldlt().solve(b)) + penalty * d;
  }
  fit.criterion[static_cast<std::size_t>(top)] = penalty * top;
  fit.criterion_degree =
      static_cast<int>(std::min_element(fit.criterion.begin() + lowest, fit.criterion.end()) -
                       fit.criterion.begin());
}

// choose_temperature_degree() from the sums.
SystematicFit choose_of(const SystematicFit& first, const Sums& s, const NoiseModel& noise,
                        const SystematicOptions& options) {
  SystematicFit fit = first;
  const Moments& mo = s.moments;
  if (fit.degree_chosen && !fit.constant_fallback) {
    const int lowest = std::clamp(options.min_degree, 0, options.max_degree);
    set_criterion(fit, s, noise, options, lowest);
    const int best = fit.criterion_degree;
    fit.degree = best;
    fit.note = Message(
        Text::temp_chosen, best, options.degree_penalty,
        fmt::format("{:.4g}", fmt::join(fit.criterion, ", ")), options.max_degree,
        lowest > 0 ? Message(Text::temp_chosen_from, lowest, fit.temperature_span_c) : Message());
  }
  fit.coefficients = unscale(solve_scaled(mo, fit.degree), s.scale);
  fit.bias_deg_h = fit.coefficients[0];
  fit.standard_errors.assign(fit.coefficients.size(), kNaN);
  fit.residual_rms_deg_h = residual_rms(mo, fit.degree);
  return fit;
}

}  // namespace

TemperatureRecord::TemperatureRecord(std::span<const double> rate_deg_h,
                                     std::span<const double> temperature_c, double sample_rate_hz,
                                     int blocks, int detrend_blocks) {
  check_inputs(rate_deg_h, temperature_c, sample_rate_hz);
  if (blocks < 1 || detrend_blocks < 1) {
    throw UsageError(fmt::format("temperature fit: {} and {} blocks; at least 1 is needed", blocks,
                                 detrend_blocks));
  }
  sums_ = std::make_shared<const Sums>(summarize(rate_deg_h, temperature_c, sample_rate_hz,
                                                 compensated_mean(temperature_c), blocks,
                                                 detrend_blocks));
}

double TemperatureRecord::t_ref_c() const { return sums_->t_ref; }

SystematicFit fit_temperature(std::span<const double> rate_deg_h,
                              std::span<const double> temperature_c, double sample_rate_hz,
                              const SystematicOptions& options) {
  check_inputs(rate_deg_h, temperature_c, sample_rate_hz);
  check_options(options);
  return fit_of(summarize(rate_deg_h, temperature_c, sample_rate_hz,
                          compensated_mean(temperature_c), options.blocks, 0),
                options);
}

SystematicFit fit_temperature(const TemperatureRecord& record, const SystematicOptions& options) {
  return fit_of(record.sums(), options);
}

DetrendFactors detrend_factors(std::span<const double> temperature_c, double sample_rate_hz,
                               double t_ref_c, int degree, std::span<const double> tau_s,
                               int blocks) {
  check_degree(degree);
  return detrend_of(summarize({}, temperature_c, sample_rate_hz, t_ref_c, 0, blocks), degree,
                    tau_s);
}

DetrendFactors detrend_factors(const TemperatureRecord& record, int degree,
                               std::span<const double> tau_s) {
  return detrend_of(record.sums(), degree, tau_s);
}

std::vector<double> coefficient_covariance(std::span<const double> temperature_c,
                                           double sample_rate_hz, double t_ref_c, int degree,
                                           const NoiseModel& noise, int blocks) {
  check_degree(degree);
  return covariance_of(summarize({}, temperature_c, sample_rate_hz, t_ref_c, blocks, 0), degree,
                       noise);
}

SystematicFit finish_temperature_fit(const SystematicFit& first, std::span<const double> rate_deg_h,
                                     std::span<const double> temperature_c, double sample_rate_hz,
                                     const NoiseModel& noise, const SystematicOptions& options) {
  check_inputs(rate_deg_h, temperature_c, sample_rate_hz);
  const Sums s =
      summarize(rate_deg_h, temperature_c, sample_rate_hz, first.t_ref_c, options.blocks, 0);
  SystematicFit fit = choose_of(first, s, noise, options);
  set_errors(fit, s, noise);
  return fit;
}

SystematicFit choose_temperature_degree(const SystematicFit& first, const TemperatureRecord& record,
                                        const NoiseModel& noise, const SystematicOptions& options) {
  return choose_of(first, record.sums(), noise, options);
}

void set_standard_errors(SystematicFit& fit, const TemperatureRecord& record,
                         const NoiseModel& noise) {
  set_errors(fit, record.sums(), noise);
}

void set_criterion_verdict(SystematicFit& fit, const TemperatureRecord& record,
                           const NoiseModel& noise, const SystematicOptions& options) {
  if (fit.constant_fallback || fit.degree_chosen) return;
  set_criterion(fit, record.sums(), noise, options, 0);
}

void subtract_temperature_fit(const SystematicFit& fit, std::span<double> rate_deg_h,
                              std::span<const double> temperature_c) {
  if (rate_deg_h.size() != temperature_c.size()) {
    throw UsageError(fmt::format("temperature fit: {} rate and {} temperature samples",
                                 rate_deg_h.size(), temperature_c.size()));
  }
  const std::size_t n = rate_deg_h.size();
#pragma omp parallel for schedule(static) if (n > kChunkSamples)
  for (std::size_t k = 0; k < n; ++k) {
    rate_deg_h[k] -= polynomial(fit.coefficients, temperature_c[k] - fit.t_ref_c);
  }
}

std::vector<double> temperature_law(const SystematicFit& fit,
                                    std::span<const double> temperature_c) {
  const std::size_t n = temperature_c.size();
  std::vector<double> law = large_vector(n);
#pragma omp parallel for schedule(static) if (n > kChunkSamples)
  for (std::size_t k = 0; k < n; ++k) {
    law[k] = polynomial(fit.coefficients, temperature_c[k] - fit.t_ref_c);
  }
  return law;
}

std::vector<double> temperature_fit_residual(const SystematicFit& fit,
                                             std::span<const double> rate_deg_h,
                                             std::span<const double> temperature_c) {
  if (rate_deg_h.size() != temperature_c.size()) {
    throw UsageError(fmt::format("temperature fit: {} rate and {} temperature samples",
                                 rate_deg_h.size(), temperature_c.size()));
  }
  const std::size_t n = rate_deg_h.size();
  std::vector<double> residual = large_vector(n, 0.0, n + 1);
#pragma omp parallel for schedule(static) if (n > kChunkSamples)
  for (std::size_t k = 0; k < n; ++k) {
    residual[k] = rate_deg_h[k] - polynomial(fit.coefficients, temperature_c[k] - fit.t_ref_c);
  }
  return residual;
}

}  // namespace foglab::model
