#include "total_kernel.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"

namespace foglab::stats::detail {
namespace {

// Up to this factor the direct method (about 26 m operations per
// subsequence) is faster than the blocked one, whose blocks of 2m
// subsequences are then too short to pay for their setup (measured at
// L = 10^5 and 10^6: direct wins at m <= 4, blocked at m >= 8).
constexpr std::int64_t kDirectMaxFactor = 5;

// Coefficients of the third difference -P(j) + 3 P(j+m) - 3 P(j+2m) + P(j+3m).
constexpr std::array<double, 4> kThirdDifference = {-1.0, 3.0, -3.0, 1.0};

void require_factor(std::size_t length, std::int64_t m) {
  if (m < 1 || 3 * m > static_cast<std::int64_t>(length)) {
    throw UsageError("total_modified_sum: averaging factor m = " + std::to_string(m) +
                     " needs 1 <= m and 3m <= the record length " + std::to_string(length));
  }
}

// ---------------------------------------------------------------------------
// Direct method.

// T(i) of one subsequence w[0 .. 3m-1]; `star` holds 9m values, `prefix`
// 9m + 1. The window is referred to its middle sample and its slope is
// removed about its centre (both leave T unchanged) so that no large level
// enters the sums.
double subsequence_total(const double* w, std::int64_t m, double* star, double* prefix) {
  const std::int64_t n = 3 * m, h1 = n / 2, h2 = n - h1;
  const double level = w[h1];
  double first_half = 0.0, second_half = 0.0;
  for (std::int64_t k = 0; k < h1; ++k) first_half += w[k] - level;
  for (std::int64_t k = h2; k < n; ++k) second_half += w[k] - level;
  // (mean2 - mean1) / dist with both halves h1 long and dist = h2.
  const double slope = (second_half - first_half) / (static_cast<double>(h1) * h2);
  const double centre = 0.5 * static_cast<double>(n - 1);
  for (std::int64_t k = 0; k < n; ++k) {
    const double v = (w[k] - level) - slope * (static_cast<double>(k) - centre);
    star[n - 1 - k] = v;
    star[n + k] = v;
    star[3 * n - 1 - k] = v;
  }
  prefix[0] = 0.0;
  for (std::int64_t t = 0; t < 3 * n; ++t) prefix[t + 1] = prefix[t] + star[t];
  double sum = 0.0;
  for (std::int64_t j = 0; j < 2 * n; ++j) {
    const double d = -prefix[j] + 3.0 * prefix[j + m] - 3.0 * prefix[j + 2 * m] + prefix[j + 3 * m];
    sum += d * d;
  }
  return sum;
}

// z minus its least-squares line (compensated sums, referred to the middle
// sample): a ramp leaves every T(i) unchanged, and without it a large slope
// makes each window's own slope removal lose digits.
std::vector<double> detrended(std::span<const double> z) {
  const auto length = static_cast<std::int64_t>(z.size());
  const double level = z[static_cast<std::size_t>(length / 2)];
  const double centre = 0.5 * static_cast<double>(length - 1);
  CompensatedSum sum;
  for (const double v : z) sum.add(v - level);
  const double mean = sum.value() / static_cast<double>(length);
  CompensatedSum moment;
  for (std::int64_t k = 0; k < length; ++k) {
    moment.add((static_cast<double>(k) - centre) * ((z[k] - level) - mean));
  }
  const auto l = static_cast<double>(length);
  const double slope = length > 1 ? moment.value() * 12.0 / (l * (l * l - 1.0)) : 0.0;
  // The line is evaluated in extended precision: rounding slope * k to double
  // would leave a sawtooth error of up to half an ulp of the trend, an
  // error with a systematic slope that the long windows amplify.
  const long double offset = static_cast<long double>(level) + mean;
  std::vector<double> y(z.size());
  for (std::int64_t k = 0; k < length; ++k) {
    y[k] = static_cast<double>((static_cast<long double>(z[k]) - offset) -
                               static_cast<long double>(slope) * (k - 0.5L * (length - 1)));
  }
  return y;
}

double direct_sum(std::span<const double> record, std::int64_t m) {
  const std::vector<double> z = detrended(record);
  const auto length = static_cast<std::int64_t>(z.size());
  const std::int64_t subsequences = length - 3 * m + 1;
  // Fixed chunks (independent of the thread count), summed in order.
  const std::int64_t chunk = std::max<std::int64_t>(1, (std::int64_t{1} << 16) / m);
  const std::int64_t chunks = (subsequences + chunk - 1) / chunk;
  std::vector<double> partial(static_cast<std::size_t>(chunks), 0.0);
#pragma omp parallel if (chunks > 1)
  {
    std::vector<double> star(static_cast<std::size_t>(9 * m));
    std::vector<double> prefix(static_cast<std::size_t>(9 * m + 1));
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < chunks; ++c) {
      const std::int64_t end = std::min(subsequences, (c + 1) * chunk);
      double s = 0.0;
      for (std::int64_t i = c * chunk; i < end; ++i) {
        s += subsequence_total(z.data() + i, m, star.data(), prefix.data());
      }
      partial[static_cast<std::size_t>(c)] = s;
    }
  }
  CompensatedSum total;
  for (const double s : partial) total.add(s);
  return total.value();
}

// ---------------------------------------------------------------------------
// Blocked O(L) method.

// One of the six pieces j = q m + r, r in [0, m), of the start points. With
// Z the prefix sums of z (Z(k) = z_0 + ... + z_{k-1}) and s_i the slope of
// subsequence i, its term is
//   U(i + r) + V(i - r) + end Z(i + 3m) + start Z(i) - s_i g(r),
//   U(u) = sum_e u_coef[e] Z(u + e m),  V(v) = sum_e v_coef[e] Z(v + (e + 1) m),  e = 0, 1, 2,
// and g, the response to the ramp k = 0 .. 3m-1, is the quadratic
// h0 + h1 rho + h2 rho^2 in rho = r - (m - 1) / 2.
struct Piece {
  std::array<double, 3> u_coef{};
  std::array<double, 3> v_coef{};
  double end = 0.0;
  double start = 0.0;
  double h0 = 0.0, h1 = 0.0, h2 = 0.0;
  double g_sum = 0.0;         // sum over r of g(r)
  double g_square_sum = 0.0;  // sum over r of g(r)^2
};

std::array<Piece, 6> make_pieces(std::int64_t m) {
  const long double n = 3.0L * static_cast<long double>(m);
  // Prefix sums of the reflected ramp, block by block (quadratics in t).
  auto ramp_prefix = [n](std::int64_t block, long double t) -> long double {
    if (block == 0) return ((2.0L * n - 1.0L) * t - t * t) / 2.0L;
    if (block == 1) return n * n - (2.0L * n + 1.0L) * t / 2.0L + t * t / 2.0L;
    return -3.0L * n * n + (6.0L * n - 1.0L) * t / 2.0L - t * t / 2.0L;
  };
  std::array<Piece, 6> pieces{};
  for (std::int64_t q = 0; q < 6; ++q) {
    Piece& p = pieces[static_cast<std::size_t>(q)];
    for (std::int64_t c = 0; c < 4; ++c) {
      const std::int64_t point = q + c;  // the point j + c m lies at point * m + r
      const double k = kThirdDifference[static_cast<std::size_t>(c)];
      switch (point / 3) {
        case 0:  // Sigma - p(3m - t) = Z(i + 3m) - Z(i - r + (3 - point) m)
          p.v_coef[static_cast<std::size_t>(2 - point)] -= k;
          p.end += k;
          break;
        case 1:  // Sigma + p(t - 3m) = Z(i + 3m) + Z(i + r + (point - 3) m) - 2 Z(i)
          p.u_coef[static_cast<std::size_t>(point - 3)] += k;
          p.end += k;
          p.start -= 2.0 * k;
          break;
        default:  // 3 Sigma - p(9m - t) = 3 Z(i + 3m) - 2 Z(i) - Z(i - r + (9 - point) m)
          p.v_coef[static_cast<std::size_t>(8 - point)] -= k;
          p.end += 3.0 * k;
          p.start -= 2.0 * k;
          break;
      }
    }
    auto g = [&](long double r) {
      long double sum = 0.0L;
      for (std::int64_t c = 0; c < 4; ++c) {
        const long double t = static_cast<long double>((q + c) * m) + r;
        sum += kThirdDifference[static_cast<std::size_t>(c)] * ramp_prefix((q + c) / 3, t);
      }
      return sum;
    };
    const long double centre = static_cast<long double>(m - 1) / 2.0L;
    const long double g0 = g(centre), g_plus = g(centre + 1.0L), g_minus = g(centre - 1.0L);
    p.h0 = static_cast<double>(g0);
    p.h1 = static_cast<double>((g_plus - g_minus) / 2.0L);
    p.h2 = static_cast<double>((g_plus + g_minus - 2.0L * g0) / 2.0L);
    long double g_sum = 0.0L, g_square_sum = 0.0L;
    for (std::int64_t r = 0; r < m; ++r) {
      const long double v = g(static_cast<long double>(r));
      g_sum += v;
      g_square_sum += v * v;
    }
    p.g_sum = static_cast<double>(g_sum);
    p.g_square_sum = static_cast<double>(g_square_sum);
  }
  return pieces;
}

// Scratch arrays of one thread.
struct Workspace {
  std::vector<double> prefix;                    // Z of the locally detrended block data
  std::vector<double> slope;                     // s_i
  std::vector<double> u_values;                  // U(u)
  std::vector<double> v_stride;                  // stride-2 prefix sums of V
  std::array<std::vector<double>, 3> u_moments;  // prefix sums of y^k U, y = u - centre
  std::array<std::vector<double>, 3> v_moments;
};

// Sum of T(i) over i in [i0, i0 + count): all six pieces, each square
// expanded and summed over (i, r) with O(1) work per sample. Every array is
// local to the block: the data are referred to their own least-squares line
// over the block's span (a ramp leaves each T(i) unchanged), so prefix sums
// only grow like the span times the local scatter.
double block_sum(const double* z, std::int64_t i0, std::int64_t count, std::int64_t m,
                 const std::array<Piece, 6>& pieces, Workspace& ws) {
  const std::int64_t n = 3 * m, h1 = n / 2, h2 = n - h1;
  const std::int64_t span = count + n - 1;  // samples used by the block
  const double* x = z + i0;

  // Local least-squares line (two passes, referred to the middle sample).
  const double level = x[span / 2];
  const double centre = 0.5 * static_cast<double>(span - 1);
  double mean = 0.0;
  for (std::int64_t k = 0; k < span; ++k) mean += x[k] - level;
  mean /= static_cast<double>(span);
  double moment = 0.0;
  for (std::int64_t k = 0; k < span; ++k) {
    moment += (static_cast<double>(k) - centre) * ((x[k] - level) - mean);
  }
  const double spand = static_cast<double>(span);
  const double line_slope = moment * 12.0 / (spand * (spand * spand - 1.0));
  const long double offset = static_cast<long double>(level) + mean;

  // The line in extended precision (see detrended()).
  std::vector<double>& zp = ws.prefix;
  zp.resize(static_cast<std::size_t>(span + 1));
  zp[0] = 0.0;
  for (std::int64_t k = 0; k < span; ++k) {
    const long double line =
        offset + static_cast<long double>(line_slope) * (k - 0.5L * (span - 1));
    zp[k + 1] = zp[k] + static_cast<double>(static_cast<long double>(x[k]) - line);
  }

  ws.slope.resize(static_cast<std::size_t>(count));
  const double slope_scale = 1.0 / (static_cast<double>(h1) * static_cast<double>(h2));
  for (std::int64_t i = 0; i < count; ++i) {
    ws.slope[i] = ((zp[i + n] - zp[i + h2]) - (zp[i + h1] - zp[i])) * slope_scale;
  }

  const std::int64_t nu = count + m - 1;  // u = i + r in [0, nu); v = i - r + m - 1 likewise
  const double u_centre = 0.5 * static_cast<double>(nu - 1);
  ws.u_values.resize(static_cast<std::size_t>(nu));
  ws.v_stride.resize(static_cast<std::size_t>(nu + 2));
  for (auto& a : ws.u_moments) a.resize(static_cast<std::size_t>(nu + 1));
  for (auto& a : ws.v_moments) a.resize(static_cast<std::size_t>(nu + 1));
  double* uv = ws.u_values.data();
  double* qv = ws.v_stride.data();
  double* pu0 = ws.u_moments[0].data();
  double* pu1 = ws.u_moments[1].data();
  double* pu2 = ws.u_moments[2].data();
  double* pv0 = ws.v_moments[0].data();
  double* pv1 = ws.v_moments[1].data();
  double* pv2 = ws.v_moments[2].data();
  const double* sl = ws.slope.data();
  const double md = static_cast<double>(m);
  const double window_centre = 0.5 * static_cast<double>(m - 1);

  double block_total = 0.0;
  for (const Piece& p : pieces) {
    const double a0 = p.u_coef[0], a1 = p.u_coef[1], a2 = p.u_coef[2];
    const double b0 = p.v_coef[0], b1 = p.v_coef[1], b2 = p.v_coef[2];
    const double* z0 = zp.data();
    const double* zm = zp.data() + m;
    const double* z2m = zp.data() + 2 * m;

    // Squares of U and V with their trapezoid multiplicities, and the
    // prefix sums used below.
    double uu = 0.0, vv = 0.0;
    pu0[0] = pu1[0] = pu2[0] = pv0[0] = pv1[0] = pv2[0] = 0.0;
    qv[0] = qv[1] = 0.0;
    for (std::int64_t u = 0; u < nu; ++u) {
      const double uval = a0 * z0[u] + a1 * zm[u] + a2 * z2m[u];
      const double vval = b0 * z0[u + 1] + b1 * zm[u + 1] + b2 * z2m[u + 1];
      const auto multiplicity =
          static_cast<double>(std::min(u, count - 1) - std::max<std::int64_t>(0, u - m + 1) + 1);
      uu += multiplicity * uval * uval;
      vv += multiplicity * vval * vval;
      const double y = static_cast<double>(u) - u_centre;
      uv[u] = uval;
      pu0[u + 1] = pu0[u] + uval;
      pu1[u + 1] = pu1[u] + y * uval;
      pu2[u + 1] = pu2[u] + y * y * uval;
      pv0[u + 1] = pv0[u] + vval;
      pv1[u + 1] = pv1[u] + y * vval;
      pv2[u + 1] = pv2[u] + y * y * vval;
      qv[u + 2] = qv[u] + vval;
    }

    // Cross term sum_{i,r} U(i + r) V(i - r): for u = i + r, the partners
    // v = u - 2r form a run of one parity.
    double cross = 0.0;
    for (std::int64_t u = 0; u < nu; ++u) {
      const std::int64_t r1 = std::max<std::int64_t>(0, u - count + 1);
      const std::int64_t r2 = std::min(m - 1, u);
      const std::int64_t k_high = u - 2 * r1 + m - 1;
      const std::int64_t k_low = u - 2 * r2 + m - 1;
      cross += uv[u] * (qv[k_high + 2] - qv[k_low]);
    }

    // Terms with the i-only part R(i, r) = W(i) - s_i g(r).
    double ur = 0.0, vr = 0.0, rr = 0.0;
    for (std::int64_t i = 0; i < count; ++i) {
      const double w = p.end * zp[i + n] + p.start * zp[i];
      const double s = sl[i];
      const double d = static_cast<double>(i) + window_centre - u_centre;
      const std::int64_t e = i + m;
      const double au0 = pu0[e] - pu0[i], au1 = pu1[e] - pu1[i], au2 = pu2[e] - pu2[i];
      const double av0 = pv0[e] - pv0[i], av1 = pv1[e] - pv1[i], av2 = pv2[e] - pv2[i];
      // Moments about the window centre; for V the offset r runs backwards.
      const double mu1 = au1 - d * au0, mu2 = au2 - d * (2.0 * au1 - d * au0);
      const double mv1 = av1 - d * av0, mv2 = av2 - d * (2.0 * av1 - d * av0);
      const double gu = p.h0 * au0 + p.h1 * mu1 + p.h2 * mu2;
      const double gv = p.h0 * av0 - p.h1 * mv1 + p.h2 * mv2;
      ur += w * au0 - s * gu;
      vr += w * av0 - s * gv;
      rr += md * w * w - s * (2.0 * w * p.g_sum - s * p.g_square_sum);
    }
    block_total += uu + vv + rr + 2.0 * (cross + ur + vr);
  }
  return block_total;
}

}  // namespace

double total_modified_sum_blocked(std::span<const double> z, std::int64_t m) {
  require_factor(z.size(), m);
  const auto length = static_cast<std::int64_t>(z.size());
  const std::int64_t subsequences = length - 3 * m + 1;
  const std::int64_t block = 2 * m;
  const std::int64_t blocks = (subsequences + block - 1) / block;
  const std::array<Piece, 6> pieces = make_pieces(m);
  std::vector<double> partial(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel if (blocks > 1)
  {
    Workspace ws;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::int64_t i0 = b * block;
      const std::int64_t count = std::min(block, subsequences - i0);
      partial[static_cast<std::size_t>(b)] = block_sum(z.data(), i0, count, m, pieces, ws);
    }
  }
  CompensatedSum total;
  for (const double s : partial) total.add(s);
  return total.value();
}

double total_modified_sum_direct(std::span<const double> z, std::int64_t m) {
  require_factor(z.size(), m);
  return direct_sum(z, m);
}

double total_modified_sum(std::span<const double> z, std::int64_t m) {
  require_factor(z.size(), m);
  return m <= kDirectMaxFactor ? direct_sum(z, m) : total_modified_sum_blocked(z, m);
}

}  // namespace foglab::stats::detail
