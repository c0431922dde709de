#include "foglab/stats/noise_id.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "../core/simd_clones.h"
#include "foglab/core/numeric.h"
#include "foglab/core/units.h"
#include "foglab/stats/allan.h"

namespace foglab::stats {
namespace {

constexpr std::int64_t kMinLag1Points = 30;  // Riley & Greenhall 2004: N >= 30
// Barnes' B1 ratio needs at least this many m-sample averages: with fewer,
// the previous tau's noise type holds. Stable32 does the same: its
// PHASE.DAT tables (tests/data/stable32-phasedat) identify the noise down to
// seven averages and carry the last type on below that.
constexpr std::int64_t kB1MinAverages = 8;
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

// The data sums over the decimated points that the quadratic fit needs,
// sum u^p p_k for p = 0..2 (the powers of u alone have closed forms).
using Moments = std::array<double, 3>;

// A point's index within one chunk's range as a double, through a 32-bit
// integer: AVX2 converts those four at a time but has no conversion from
// 64-bit integers (the loops below ran at a quarter of their speed). A
// chunk's range holds at most kChunkSamples + kMaxD + 1 points.
FOGLAB_CLONED_INLINE double local_index(std::int64_t offset) {
  return static_cast<double>(static_cast<std::int32_t>(offset));
}

// The decimated points x[k m] are read with a compile-time stride for the
// factors 1, 2 and 4, which hold 7/8 of all the points the method visits:
// the compiler then loads them as vectors and shuffles, instead of one by one.
template <std::int64_t Stride>
FOGLAB_CLONED_INLINE Moments moments_with(const double* x, std::int64_t m, double scale,
                                          std::int64_t k0, std::int64_t k1) {
  const std::int64_t step = Stride > 0 ? Stride : m;
  const double u0 = static_cast<double>(k0) * scale - 1.0;
  double d0 = 0, d1 = 0, d2 = 0;
#pragma omp simd reduction(+ : d0, d1, d2)
  for (std::int64_t k = k0; k < k1; ++k) {
    const double u = u0 + local_index(k - k0) * scale;
    const double v = x[k * step];
    d0 += v;
    d1 += u * v;
    d2 += u * u * v;
  }
  return {d0, d1, d2};
}

FOGLAB_SIMD_CLONES Moments chunk_moments(const double* x, std::int64_t m, double scale,
                                         std::int64_t k0, std::int64_t k1) {
  switch (m) {
    case 1:
      return moments_with<1>(x, m, scale, k0, k1);
    case 2:
      return moments_with<2>(x, m, scale, k0, k1);
    case 4:
      return moments_with<4>(x, m, scale, k0, k1);
    default:
      return moments_with<0>(x, m, scale, k0, k1);
  }
}

Moments chunk_moments(const double* x, const Lag1Factor& f, std::int64_t k0, std::int64_t k1) {
  return chunk_moments(x, f.m, f.scale, k0, k1);
}

void fit_quadratic(const std::vector<Moments>& parts, Lag1Factor& f) {
  std::array<CompensatedSum, 3> d;
  for (const auto& p : parts) {
    for (int i = 0; i < 3; ++i) d[i].add(p[i]);
  }
  // The power sums of u_k = 2k/(K-1) - 1 over k = 0 .. K-1: the odd ones
  // vanish by symmetry, S2 = K(K+1) / (3(K-1)), S4 = K(K+1)(3K^2-7) / (15(K-1)^3).
  const double K = static_cast<double>(f.K);
  const double S0 = K, S1 = 0.0, S2 = K * (K + 1.0) / (3.0 * (K - 1.0)), S3 = 0.0,
               S4 =
                   K * (K + 1.0) * (3.0 * K * K - 7.0) / (15.0 * (K - 1.0) * (K - 1.0) * (K - 1.0));
  // Gram matrix of P0 = 1, P1 = u, P2 = 1.5 u^2 - 0.5 from the power sums.
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

// The residual of the decimated points from the fitted quadratic,
// r_k = p_k - (c0 + u (c1 + u c2)), for k in [k0, k1) into out[k - k0].
template <std::int64_t Stride>
FOGLAB_CLONED_INLINE void residuals_with(const double* x, std::int64_t m, double scale, double c0,
                                         double c1, double c2, std::int64_t k0, std::int64_t k1,
                                         double* out) {
  const std::int64_t step = Stride > 0 ? Stride : m;
  const double u0 = static_cast<double>(k0) * scale - 1.0;
#pragma omp simd
  for (std::int64_t k = k0; k < k1; ++k) {
    const double u = u0 + local_index(k - k0) * scale;
    out[k - k0] = x[k * step] - (c0 + u * (c1 + u * c2));
  }
}

FOGLAB_SIMD_CLONES void residuals(const double* x, std::int64_t m, double scale, double c0,
                                  double c1, double c2, std::int64_t k0, std::int64_t k1,
                                  double* out) {
  switch (m) {
    case 1:
      return residuals_with<1>(x, m, scale, c0, c1, c2, k0, k1, out);
    case 2:
      return residuals_with<2>(x, m, scale, c0, c1, c2, k0, k1, out);
    case 4:
      return residuals_with<4>(x, m, scale, c0, c1, c2, k0, k1, out);
    default:
      return residuals_with<0>(x, m, scale, c0, c1, c2, k0, k1, out);
  }
}

// The raw sums of the orders 0 .. DMax of differences over positions
// [j0, j1) of the residual buffer b, where every order and its lag exist:
// the d-th backward difference ending at j is z^(d)_{j-d}, and its lag
// product is taken with the one ending at j - 1, so b[j - DMax - 1] must
// exist. One loop for all orders, each difference formed in registers.
template <int DMax>
FOGLAB_CLONED_INLINE void difference_sums_to(const double* b, std::int64_t j0, std::int64_t j1,
                                             DiffSums& out) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  double q0 = 0, q1 = 0, q2 = 0, q3 = 0;
  double l0 = 0, l1 = 0, l2 = 0, l3 = 0;
#pragma omp simd reduction(+ : s0, s1, s2, s3, q0, q1, q2, q3, l0, l1, l2, l3)
  for (std::int64_t j = j0; j < j1; ++j) {
    const double a0 = b[j], a1 = b[j - 1], a2 = b[j - 2], a3 = b[j - 3];
    const double e0 = a0 - a1, e1 = a1 - a2, e2 = a2 - a3;  // order 1
    const double f0 = e0 - e1, f1 = e1 - e2;                // order 2
    s0 += a0;
    q0 += a0 * a0;
    l0 += a0 * a1;
    s1 += e0;
    q1 += e0 * e0;
    l1 += e0 * e1;
    s2 += f0;
    q2 += f0 * f0;
    l2 += f0 * f1;
    if constexpr (DMax == 3) {
      const double e3 = a3 - b[j - 4];
      const double f2 = e2 - e3;
      const double g0 = f0 - f1, g1 = f1 - f2;  // order 3
      s3 += g0;
      q3 += g0 * g0;
      l3 += g0 * g1;
    }
  }
  const std::array<double, 4> s = {s0, s1, s2, s3}, q = {q0, q1, q2, q3}, l = {l0, l1, l2, l3};
  for (int order = 0; order <= DMax; ++order) {
    out.sum[order] += s[order];
    out.sum_sq[order] += q[order];
    out.sum_lag[order] += l[order];
  }
}

FOGLAB_SIMD_CLONES void difference_sums(const double* b, std::int64_t j0, std::int64_t j1,
                                        int d_max, DiffSums& out) {
  if (d_max == 3) {
    difference_sums_to<3>(b, j0, j1, out);
  } else {
    difference_sums_to<2>(b, j0, j1, out);
  }
}

// Raw sums over k in [k0, k1) of the d-times differenced residual, every
// order d <= d_max at once: the buffer holds the residual from up to
// kMaxD + 1 points before k0. The first points of the record, where a
// difference or its lag does not exist yet, are summed one by one.
DiffSums chunk_diff_sums(const double* x, const Lag1Factor& f, std::int64_t k0, std::int64_t k1,
                         int d_max, std::vector<double>& buffer) {
  const std::int64_t lo = std::max<std::int64_t>(0, k0 - kMaxD - 1);
  // Grown, never shrunk: a resize that shrinks and grows again would zero the
  // buffer for every factor of every chunk.
  if (buffer.size() < static_cast<std::size_t>(k1 - lo)) {
    buffer.resize(static_cast<std::size_t>(k1 - lo));
  }
  residuals(x, f.m, f.scale, f.c0, f.c1, f.c2, lo, k1, buffer.data());
  const double* b = buffer.data() - lo;  // b[k] for k in [lo, k1)
  DiffSums sums;
  // Positions below kMaxD + 1 lack some order's lag: there each order is
  // differenced and summed on its own.
  const std::int64_t full = std::min(k1, std::max<std::int64_t>(k0, kMaxD + 1));
  for (std::int64_t k = k0; k < full; ++k) {
    std::array<double, kMaxD + 2> z{};  // z[i] = b[k - i], differenced in place
    const std::int64_t depth = std::min<std::int64_t>(k, kMaxD + 1);
    for (std::int64_t i = 0; i <= depth; ++i) z[i] = b[k - i];
    for (int order = 0; order <= d_max; ++order) {
      if (order > 0) {
        for (int i = 0; i + order <= depth; ++i) z[i] -= z[i + 1];
      }
      if (k < order) break;
      sums.sum[order] += z[0];
      sums.sum_sq[order] += z[0] * z[0];
      if (k >= order + 1) sums.sum_lag[order] += z[0] * z[1];
    }
  }
  if (full < k1) difference_sums(b, full, k1, d_max, sums);
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
  // Each pass keeps one partial result per group of consecutive chunks and
  // factor, summed in chunk order within the group, so the result depends on
  // the record's length only, never on the threads. Groups, not chunks: a
  // partial per chunk took a megabyte for 2e7 samples, whose fresh pages cost
  // more than the arithmetic on a virtual machine (issue 19).
  const std::int64_t group = std::clamp<std::int64_t>(chunks / 32, 1, 16);
  const std::int64_t groups = (chunks + group - 1) / group;
  auto for_each_chunk = [&](std::int64_t g, auto&& visit) {
    for (std::int64_t c = g * group; c < std::min(chunks, (g + 1) * group); ++c) {
      const std::int64_t i0 = c * chunk, i1 = std::min(n, i0 + chunk);
      for (std::int64_t q = 0; q < q_count; ++q) {
        const std::int64_t k0 = fs[q].first_in(i0), k1 = fs[q].end_in(i1);
        if (k0 < k1) visit(q, k0, k1);
      }
    }
  };

  std::vector<Moments> moments(static_cast<std::size_t>(groups * q_count));
#pragma omp parallel for schedule(dynamic, 1) if (groups > 1)
  for (std::int64_t g = 0; g < groups; ++g) {
    for_each_chunk(g, [&](std::int64_t q, std::int64_t k0, std::int64_t k1) {
      const Moments part = chunk_moments(x, fs[q], k0, k1);
      Moments& into = moments[g * q_count + q];
      for (int i = 0; i < 3; ++i) into[i] += part[i];
    });
  }
  std::vector<Moments> parts1(static_cast<std::size_t>(groups));
  for (std::int64_t q = 0; q < q_count; ++q) {
    for (std::int64_t g = 0; g < groups; ++g) parts1[g] = moments[g * q_count + q];
    fit_quadratic(parts1, fs[q]);
  }

  std::vector<DiffSums> sums(static_cast<std::size_t>(groups * q_count));
#pragma omp parallel if (groups > 1)
  {
    std::vector<double> buffer;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t g = 0; g < groups; ++g) {
      for_each_chunk(g, [&](std::int64_t q, std::int64_t k0, std::int64_t k1) {
        const DiffSums part = chunk_diff_sums(x, fs[q], k0, k1, d_max, buffer);
        DiffSums& into = sums[g * q_count + q];
        for (int d = 0; d <= kMaxD; ++d) {
          into.sum[d] += part.sum[d];
          into.sum_sq[d] += part.sum_sq[d];
          into.sum_lag[d] += part.sum_lag[d];
        }
      });
    }
  }
  std::vector<NoiseId> ids(factors.size());
  std::vector<DiffSums> parts2(static_cast<std::size_t>(groups));
  for (std::int64_t q = 0; q < q_count; ++q) {
    for (std::int64_t g = 0; g < groups; ++g) parts2[g] = sums[g * q_count + q];
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
  if (count < kB1MinAverages) {
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
  // apart, the boundary at the geometric mean of their theoretical ratios
  // (SP1065 section 5.6.2; the two candidates Stable32 weighs).
  if (3 * m > n) {
    id.alpha = 1;
    return id;
  }
  const std::array<std::int64_t, 1> factor = {m};
  const double adev = detail::deviations_from_phase(phase, AllanKind::adev, factor)[0];
  const double mdev = detail::deviations_from_phase(phase, AllanKind::mdev, factor)[0];
  const double rn = adev > 0.0 ? (mdev * mdev) / (adev * adev) : 1.0;
  const double md = static_cast<double>(m);
  const double rn_white_pm = 1.0 / md;
  const double rn_flicker_pm =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  id.method = NoiseIdMethod::b1_rn;
  id.alpha = rn < std::sqrt(rn_white_pm * rn_flicker_pm) ? 2 : 1;
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
