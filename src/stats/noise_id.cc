#include "foglab/stats/noise_id.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "foglab/core/numeric.h"
#include "foglab/core/units.h"
#include "foglab/stats/allan.h"

namespace foglab::stats {
namespace {

constexpr std::int64_t kMinLag1Points = 30;  // Riley & Greenhall 2004: N >= 30
constexpr int kMaxD = 3;

// Raw sums of the d-times differenced, detrended series z^(d), d = 0..3.
struct DiffSums {
  std::array<double, kMaxD + 1> sum{};      // sum z_k
  std::array<double, kMaxD + 1> sum_sq{};   // sum z_k^2
  std::array<double, kMaxD + 1> sum_lag{};  // sum z_k z_{k+1}
};

// One factor of the lag-1 method: the decimated angle points p_k = x_{k m},
// k = 0 .. K-1, detrended by a least-squares quadratic written in the
// Legendre basis 1, u, (3u^2 - 1)/2 of u = 2k/(K-1) - 1 (for conditioning).
struct Lag1Factor {
  std::int64_t m = 1;
  std::int64_t K = 0;
  double scale = 0.0;  // u = k * scale - 1
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;  // quadratic in u
  double residual(const double* x, std::int64_t k) const {
    const double u = static_cast<double>(k) * scale - 1.0;
    return x[k * m] - (c0 + u * (c1 + u * c2));
  }
  // Decimated points whose angle index lies in [i0, i1).
  std::int64_t first_in(std::int64_t i0) const { return (i0 + m - 1) / m; }
  std::int64_t end_in(std::int64_t i1) const { return std::min(K, (i1 + m - 1) / m); }
};

struct Moments {
  std::array<double, 5> u_pow{};  // sum u^p, p = 0..4
  std::array<double, 3> data{};   // sum u^p p_k, p = 0..2
};

Moments chunk_moments(const double* x, const Lag1Factor& f, std::int64_t k0, std::int64_t k1) {
  double g0 = 0, g1 = 0, g2 = 0, g3 = 0, g4 = 0, d0 = 0, d1 = 0, d2 = 0;
  const std::int64_t m = f.m;
#pragma omp simd reduction(+ : g0, g1, g2, g3, g4, d0, d1, d2)
  for (std::int64_t k = k0; k < k1; ++k) {
    const double u = static_cast<double>(k) * f.scale - 1.0;
    const double u2 = u * u;
    const double v = x[k * m];
    g0 += 1.0;
    g1 += u;
    g2 += u2;
    g3 += u2 * u;
    g4 += u2 * u2;
    d0 += v;
    d1 += u * v;
    d2 += u2 * v;
  }
  return {{g0, g1, g2, g3, g4}, {d0, d1, d2}};
}

void fit_quadratic(const std::vector<Moments>& parts, Lag1Factor& f) {
  std::array<CompensatedSum, 5> g;
  std::array<CompensatedSum, 3> d;
  for (const auto& p : parts) {
    for (int i = 0; i < 5; ++i) g[i].add(p.u_pow[i]);
    for (int i = 0; i < 3; ++i) d[i].add(p.data[i]);
  }
  // Gram matrix of P0 = 1, P1 = u, P2 = 1.5 u^2 - 0.5 from the power sums.
  const double S0 = g[0].value(), S1 = g[1].value(), S2 = g[2].value(), S3 = g[3].value(),
               S4 = g[4].value();
  Eigen::Matrix3d gram;
  gram(0, 0) = S0;
  gram(0, 1) = gram(1, 0) = S1;
  gram(0, 2) = gram(2, 0) = 1.5 * S2 - 0.5 * S0;
  gram(1, 1) = S2;
  gram(1, 2) = gram(2, 1) = 1.5 * S3 - 0.5 * S1;
  gram(2, 2) = 2.25 * S4 - 1.5 * S2 + 0.25 * S0;
  const Eigen::Vector3d rhs(d[0].value(), d[1].value(), 1.5 * d[2].value() - 0.5 * d[0].value());
  const Eigen::Vector3d coef = gram.ldlt().solve(rhs);
  f.c0 = coef(0) - 0.5 * coef(2);
  f.c1 = coef(1);
  f.c2 = 1.5 * coef(2);
}

// Raw sums over k in [k0, k1) of the d-times differenced residual, every
// order d <= d_max at once. The buffer holds the residual from d_max + 1
// points before k0 and is differenced in place: after d steps
// b[k] = (backward d-th difference ending at k) = z^(d)_{k-d}.
DiffSums chunk_diff_sums(const double* x, const Lag1Factor& f, std::int64_t k0, std::int64_t k1,
                         int d_max, std::vector<double>& buffer) {
  const std::int64_t lo = std::max<std::int64_t>(0, k0 - d_max - 1);
  buffer.resize(static_cast<std::size_t>(k1 - lo));
  double* b = buffer.data() - lo;  // b[k] for k in [lo, k1)
  for (std::int64_t k = lo; k < k1; ++k) b[k] = f.residual(x, k);
  DiffSums sums;
  for (int order = 0; order <= d_max; ++order) {
    if (order > 0) {
      for (std::int64_t k = k1 - 1; k > lo + order - 1; --k) b[k] -= b[k - 1];
    }
    double s1 = 0.0, s2 = 0.0, sl = 0.0;
    const std::int64_t first = std::max<std::int64_t>(k0, order);
#pragma omp simd reduction(+ : s1, s2)
    for (std::int64_t k = first; k < k1; ++k) {
      s1 += b[k];
      s2 += b[k] * b[k];
    }
    const std::int64_t first_lag = std::max<std::int64_t>(k0, order + 1);
#pragma omp simd reduction(+ : sl)
    for (std::int64_t k = first_lag; k < k1; ++k) sl += b[k] * b[k - 1];
    sums.sum[order] = s1;
    sums.sum_sq[order] = s2;
    sums.sum_lag[order] = sl;
  }
  return sums;
}

NoiseId decide(const double* x, const Lag1Factor& f, const std::vector<DiffSums>& parts,
               int d_max) {
  // End values z^(d)_0 and z^(d)_{L-1} for centring (K >= 30 points).
  std::array<double, kMaxD + 2> head{}, tail{};
  for (int i = 0; i <= kMaxD + 1; ++i) {
    head[i] = f.residual(x, i);
    tail[i] = f.residual(x, f.K - (kMaxD + 2) + i);
  }
  NoiseId id;
  id.method = NoiseIdMethod::lag1_acf;
  for (int order = 0; order <= d_max; ++order) {
    CompensatedSum s1, s2, sl;
    for (const auto& p : parts) {
      s1.add(p.sum[order]);
      s2.add(p.sum_sq[order]);
      sl.add(p.sum_lag[order]);
    }
    const double length = static_cast<double>(f.K - order);
    const double mu = s1.value() / length;
    std::array<double, kMaxD + 2> h = head, t = tail;
    for (int j = 0; j < order; ++j) {
      for (int i = 0; i + 1 <= kMaxD + 1 - j; ++i) {
        h[i] = h[i + 1] - h[i];
        t[i] = t[i + 1] - t[i];
      }
    }
    const double first = h[0];
    const double last = t[kMaxD + 1 - order];
    // sum_j (z_j - mu)(z_{j+1} - mu) and sum_j (z_j - mu)^2 from the raw sums.
    const double num = sl.value() - mu * (s1.value() - last) - mu * (s1.value() - first) +
                       (length - 1.0) * mu * mu;
    const double den = s2.value() - length * mu * mu;
    const double r1 = den > 0.0 ? num / den : 0.0;
    const double rho = r1 / (1.0 + r1);
    if (rho < 0.25 || order == d_max) {
      id.rho = rho;
      id.differences = order;
      id.alpha = 2 - 2 * order - static_cast<int>(std::nearbyint(2.0 * rho));
      return id;
    }
  }
  return id;
}

// The lag-1 method for several factors in two passes over the angle record,
// whatever their number: the record is walked in chunks that stay in cache
// while every factor takes its decimated points from them.
std::vector<NoiseId> lag1_identify(std::span<const double> phase,
                                   std::span<const std::int64_t> factors, int d_max) {
  const auto n = static_cast<std::int64_t>(phase.size());
  const double* x = phase.data();
  const auto q_count = static_cast<std::int64_t>(factors.size());
  std::vector<Lag1Factor> fs(factors.size());
  for (std::int64_t q = 0; q < q_count; ++q) {
    fs[q].m = factors[q];
    fs[q].K = (n - 1) / factors[q] + 1;
    fs[q].scale = 2.0 / static_cast<double>(fs[q].K - 1);
  }
  const auto chunk = static_cast<std::int64_t>(kChunkSamples);
  const std::int64_t chunks = (n + chunk - 1) / chunk;

  std::vector<Moments> moments(static_cast<std::size_t>(chunks * q_count));
#pragma omp parallel for schedule(dynamic, 4) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t i0 = c * chunk, i1 = std::min(n, i0 + chunk);
    for (std::int64_t q = 0; q < q_count; ++q) {
      const std::int64_t k0 = fs[q].first_in(i0), k1 = fs[q].end_in(i1);
      if (k0 < k1) moments[c * q_count + q] = chunk_moments(x, fs[q], k0, k1);
    }
  }
  std::vector<Moments> parts1(static_cast<std::size_t>(chunks));
  for (std::int64_t q = 0; q < q_count; ++q) {
    for (std::int64_t c = 0; c < chunks; ++c) parts1[c] = moments[c * q_count + q];
    fit_quadratic(parts1, fs[q]);
  }

  std::vector<DiffSums> sums(static_cast<std::size_t>(chunks * q_count));
#pragma omp parallel if (chunks > 1)
  {
    std::vector<double> buffer;
#pragma omp for schedule(dynamic, 4)
    for (std::int64_t c = 0; c < chunks; ++c) {
      const std::int64_t i0 = c * chunk, i1 = std::min(n, i0 + chunk);
      for (std::int64_t q = 0; q < q_count; ++q) {
        const std::int64_t k0 = fs[q].first_in(i0), k1 = fs[q].end_in(i1);
        if (k0 < k1) sums[c * q_count + q] = chunk_diff_sums(x, fs[q], k0, k1, d_max, buffer);
      }
    }
  }
  std::vector<NoiseId> ids(factors.size());
  std::vector<DiffSums> parts2(static_cast<std::size_t>(chunks));
  for (std::int64_t q = 0; q < q_count; ++q) {
    for (std::int64_t c = 0; c < chunks; ++c) parts2[c] = sums[c * q_count + q];
    ids[q] = decide(x, fs[q], parts2, d_max);
  }
  return ids;
}

// Theoretical B1 ratio for N averages and ADEV exponent mu (SP1065 eq. 73).
double b1_theory(double count, int mu) {
  if (mu == 0) return count * std::log(count) / (2.0 * (count - 1.0) * std::log(2.0));
  const double p = static_cast<double>(mu);
  return count * (1.0 - std::pow(count, p)) / (2.0 * (count - 1.0) * (1.0 - std::pow(2.0, p)));
}

NoiseId b1_identify(std::span<const double> phase, std::int64_t m, int d_max) {
  const auto n = static_cast<std::int64_t>(phase.size());
  const std::int64_t count = (n - 1) / m;  // number of m-sample averages
  NoiseId id;
  if (count < 3) {
    id.method = NoiseIdMethod::none;
    return id;
  }
  std::vector<double> avg(static_cast<std::size_t>(count));
  for (std::int64_t j = 0; j < count; ++j) {
    avg[j] = (phase[(j + 1) * m] - phase[j * m]) / static_cast<double>(m);
  }
  double mean = 0.0;
  for (const double v : avg) mean += v;
  mean /= static_cast<double>(count);
  double var = 0.0, avar = 0.0;
  for (std::int64_t j = 0; j < count; ++j) {
    var += (avg[j] - mean) * (avg[j] - mean);
    if (j + 1 < count) avar += (avg[j + 1] - avg[j]) * (avg[j + 1] - avg[j]);
  }
  var /= static_cast<double>(count - 1);
  avar /= 2.0 * static_cast<double>(count - 1);
  const double b1 = avar > 0.0 ? var / avar : 1.0;
  const double nb = static_cast<double>(count);
  const int mu_top = d_max >= 3 ? 3 : 1;
  int mu = -2;
  for (int hi = mu_top; hi > -2; --hi) {
    const double boundary = std::sqrt(b1_theory(nb, hi) * b1_theory(nb, hi - 1));
    if (b1 > boundary) {
      mu = hi;
      break;
    }
  }
  id.method = NoiseIdMethod::b1;
  if (mu >= -1) {
    id.alpha = -mu - 1;
    return id;
  }
  // White or flicker PM: the same ADEV slope; R(n) = MVAR/AVAR tells them
  // apart (SP1065 section 5.6.2). With few averages B1 also mistakes white FM
  // for PM, so white FM (R = 1/2) is the third candidate; the nearest theory
  // on a log scale wins (boundaries at geometric means).
  if (3 * m > n) {
    id.alpha = 0;
    return id;
  }
  const std::array<std::int64_t, 1> factor = {m};
  const double adev = detail::deviations_from_phase(phase, AllanKind::adev, factor)[0];
  const double mdev = detail::deviations_from_phase(phase, AllanKind::mdev, factor)[0];
  const double rn = adev > 0.0 ? (mdev * mdev) / (adev * adev) : 0.5;
  const double md = static_cast<double>(m);
  const double rn_white_pm = 1.0 / md;
  const double rn_flicker_pm =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  const double rn_white_fm = 0.5;
  id.method = NoiseIdMethod::b1_rn;
  if (rn < std::sqrt(rn_white_pm * rn_flicker_pm)) {
    id.alpha = 2;
  } else if (rn < std::sqrt(rn_flicker_pm * rn_white_fm)) {
    id.alpha = 1;
  } else {
    id.alpha = 0;
  }
  return id;
}

}  // namespace

std::string_view to_string(NoiseIdMethod method) {
  switch (method) {
    case NoiseIdMethod::off:
      return "";
    case NoiseIdMethod::none:
      return "none";
    case NoiseIdMethod::lag1_acf:
      return "lag1_acf";
    case NoiseIdMethod::b1:
      return "b1";
    case NoiseIdMethod::b1_rn:
      return "b1_rn";
  }
  return "?";
}

std::string to_string(const AlphaMethod& method) {
  std::string text(to_string(method.method));
  if (method.fm_floor) text += ",fm_floor";
  return text;
}

double lag1_autocorrelation(std::span<const double> series) {
  const std::size_t n = series.size();
  if (n < 2) return 0.0;
  double mean = 0.0;
  for (const double v : series) mean += v;
  mean /= static_cast<double>(n);
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = series[i] - mean;
    den += a * a;
    if (i + 1 < n) num += a * (series[i + 1] - mean);
  }
  return den > 0.0 ? num / den : 0.0;
}

std::vector<NoiseId> identify_noise(std::span<const double> phase,
                                    std::span<const std::int64_t> factors, int d_max) {
  d_max = std::clamp(d_max, 1, kMaxD);
  const auto n = static_cast<std::int64_t>(phase.size());
  std::vector<std::int64_t> lag1_factors;
  for (const std::int64_t m : factors) {
    if (n > 0 && (n - 1) / m + 1 >= kMinLag1Points) lag1_factors.push_back(m);
  }
  const std::vector<NoiseId> lag1 = lag1_identify(phase, lag1_factors, d_max);
  std::vector<NoiseId> ids;
  std::size_t next = 0;
  const int lowest = d_max >= 3 ? -4 : -2;
  for (const std::int64_t m : factors) {
    NoiseId id = next < lag1_factors.size() && lag1_factors[next] == m ? lag1[next++]
                                                                      : b1_identify(phase, m, d_max);
    id.alpha = std::clamp(id.alpha, lowest, 2);
    ids.push_back(id);
  }
  return ids;
}

NoiseId identify_noise(std::span<const double> phase, std::int64_t m, int d_max) {
  const std::array<std::int64_t, 1> factor = {m};
  return identify_noise(phase, factor, d_max)[0];
}

}  // namespace foglab::stats
