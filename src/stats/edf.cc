// Greenhall's general EDF algorithm. Notation and equation numbers follow
// C. A. Greenhall and W. J. Riley, "Uncertainty of stability variances based
// on finite differences", Proc. 35th PTTI Meeting (2003), and W. J. Riley,
// NIST SP 1065 (2008) section 5.3.3.
#include "foglab/stats/edf.h"

#include <array>
#include <cmath>
#include <limits>

#include "foglab/core/numeric.h"

namespace foglab::stats {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kJmax = 100.0;

// sw(t): the generalised autocovariance kernel of the phase for noise alpha (eq. 7).
double sw(double t, int alpha) {
  const double a = std::fabs(t);
  switch (alpha) {
    case 2: return -a;
    case 1: return t == 0.0 ? 0.0 : t * t * std::log(a);
    case 0: return a * a * a;
    case -1: return t == 0.0 ? 0.0 : t * t * t * t * std::log(a);
    case -2: return a * a * a * a * a;
    case -3: return t == 0.0 ? 0.0 : std::pow(t, 6) * std::log(a);
    case -4: return std::pow(a, 7);
    default: return kNaN;
  }
}

// sx(t): the kernel after the averaging filter of length 1/F (eq. 8).
double sx(double t, double F, int alpha) {
  if (std::isinf(F)) return sw(t, alpha + 2);
  const double h = 1.0 / F;
  if (alpha == 1 && h < 1e-3 && std::fabs(t) >= 0.5) {
    // The second difference of t^2 ln|t| with a tiny step cancels
    // catastrophically; use its Taylor expansion instead:
    // F^2 (2 f(t) - f(t-h) - f(t+h)) = -(f'' + h^2 f''''/12) + O(h^4),
    // f'' = 2 ln|t| + 3, f'''' = -2/t^2.
    return -(2.0 * std::log(std::fabs(t)) + 3.0) + h * h / (6.0 * t * t);
  }
  return F * F * (2.0 * sw(t, alpha) - sw(t - h, alpha) - sw(t + h, alpha));
}

// sz(t): the kernel after the d-th difference (eq. 9), binomial weights
// (-1)^k C(2d, d+k), k = -d .. d.
double sz(double t, double F, int alpha, int d) {
  static constexpr std::array<std::array<double, 4>, 4> kWeights = {{
      {1, 0, 0, 0},
      {2, -1, 0, 0},
      {6, -4, 1, 0},
      {20, -15, 6, -1},
  }};
  double sum = kWeights[d][0] * sx(t, F, alpha);
  for (int k = 1; k <= d; ++k) {
    sum += kWeights[d][k] * (sx(t - k, F, alpha) + sx(t + k, F, alpha));
  }
  return sum;
}

// BasicSum (eq. 10).
double basic_sum(double J, double M, double S, double F, int alpha, int d) {
  const double s0 = sz(0.0, F, alpha, d);
  const double sJ = sz(J / S, F, alpha, d);
  double sum = s0 * s0 + (1.0 - J / M) * sJ * sJ;
  const auto j_end = static_cast<std::int64_t>(J);
  for (std::int64_t j = 1; j < j_end; ++j) {
    const double s = sz(static_cast<double>(j) / S, F, alpha, d);
    sum += 2.0 * (1.0 - static_cast<double>(j) / M) * s * s;
  }
  return sum;
}

struct Coefficients {
  double a0;
  double a1;
};

// Table 1 (modified variances, F = 1) and Table 2 (unmodified, F = m),
// rows alpha = +2 .. -4, columns d = 1, 2, 3; NaN where alpha + 2d <= 1.
constexpr double kNa = kNaN;
constexpr std::array<std::array<Coefficients, 3>, 7> kTable1 = {{
    {{{2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}, {22.0 / 25.0, 2.0 / 3.0}}},
    {{{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}}},
    {{{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}}},
    {{{kNa, kNa}, {1.048, 0.534}, {1.180, 0.816}}},
    {{{kNa, kNa}, {1.302, 0.535}, {1.175, 0.777}}},
    {{{kNa, kNa}, {kNa, kNa}, {1.194, 0.703}}},
    {{{kNa, kNa}, {kNa, kNa}, {1.489, 0.702}}},
}};
constexpr std::array<std::array<Coefficients, 3>, 7> kTable2 = {{
    {{{3.0 / 2.0, 1.0 / 2.0}, {35.0 / 18.0, 1.0}, {231.0 / 100.0, 3.0 / 2.0}}},
    {{{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}}},
    {{{2.0 / 3.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}}},
    {{{kNa, kNa}, {0.852, 0.375}, {0.997, 0.617}}},
    {{{kNa, kNa}, {1.079, 0.368}, {1.033, 0.607}}},
    {{{kNa, kNa}, {kNa, kNa}, {1.053, 0.553}}},
    {{{kNa, kNa}, {kNa, kNa}, {1.302, 0.535}}},
}};
// Table 3: b0, b1 of the alpha = +1 normalisation b0 + b1 ln m, d = 1, 2, 3.
constexpr std::array<Coefficients, 3> kTable3 = {{{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}}};

double binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

}  // namespace

double greenhall_edf(int alpha, std::int64_t m, std::int64_t n_phase,
                     const DifferenceVariance& variance) {
  const int d = variance.order;
  const bool overlapping = variance.stride == Stride::overlapping;
  const bool modified = variance.filter == Filter::modified;
  if (d < 1 || d > 3 || alpha > 2 || alpha < -4 || alpha + 2 * d <= 1 || m < 1) return kNaN;
  const double md = static_cast<double>(m);
  const double F = modified ? 1.0 : md;  // filter factor
  const double S = overlapping ? md : 1.0;  // stride factor
  const double L = md / F + md * d;  // length of the filter applied to the phase
  const double M = 1.0 + std::floor(S * (static_cast<double>(n_phase) - L) / md);
  if (M < 1.0) return kNaN;
  const double J = std::min(M, (d + 1) * S);
  const double r = M / S;
  const std::size_t row = static_cast<std::size_t>(2 - alpha);
  const std::size_t col = static_cast<std::size_t>(d - 1);

  double inv_edf = kNaN;
  if (modified) {  // case 1: modified variances, every alpha
    if (J <= kJmax) {
      const double s0 = sz(0.0, 1.0, alpha, d);
      inv_edf = basic_sum(J, M, S, 1.0, alpha, d) / (s0 * s0 * M);
    } else if (r > d + 1) {
      const auto [a0, a1] = kTable1[row][col];
      inv_edf = (a0 - a1 / r) / r;
    } else {
      const double s0 = sz(0.0, 1.0, alpha, d);
      inv_edf = basic_sum(kJmax, kJmax, kJmax / r, 1.0, alpha, d) / (s0 * s0 * kJmax);
    }
  } else if (alpha <= 0) {  // case 2: unmodified, alpha <= 0
    if (J <= kJmax) {
      const double Fp = md * (d + 1) <= kJmax ? md : kInf;
      const double s0 = sz(0.0, Fp, alpha, d);
      inv_edf = basic_sum(J, M, S, Fp, alpha, d) / (s0 * s0 * M);
    } else if (r > d + 1) {
      const auto [a0, a1] = kTable2[row][col];
      inv_edf = (a0 - a1 / r) / r;
    } else {
      const double s0 = sz(0.0, kInf, alpha, d);
      inv_edf = basic_sum(kJmax, kJmax, kJmax / r, kInf, alpha, d) / (s0 * s0 * kJmax);
    }
  } else if (alpha == 1) {  // case 3: unmodified, flicker PM
    if (J <= kJmax) {
      const double s0 = sz(0.0, md, alpha, d);
      inv_edf = basic_sum(J, M, S, md, alpha, d) / (s0 * s0 * M);
    } else {
      const auto [b0, b1] = kTable3[col];
      const double norm = b0 + b1 * std::log(md);
      if (r > d + 1) {
        const auto [a0, a1] = kTable2[row][col];
        inv_edf = (a0 - a1 / r) / (norm * norm * r);
      } else {
        const double mp = kJmax / r;
        inv_edf = basic_sum(kJmax, kJmax, mp, mp, alpha, d) / (norm * norm * kJmax);
      }
    }
  } else {  // case 4: unmodified, white PM
    const double a0 = binomial(4 * d, 2 * d) / (binomial(2 * d, d) * binomial(2 * d, d));
    const double a1 = d / 2.0;
    if (std::ceil(r) > d || M > 1e6) {
      inv_edf = (a0 - a1 / r) / M;
    } else {
      // Few terms: evaluate the exact sum (eq. 10) with J = M.
      const double s0 = sz(0.0, md, alpha, d);
      inv_edf = basic_sum(M, M, S, md, alpha, d) / (s0 * s0 * M);
    }
  }
  if (!(inv_edf > 0.0) || !std::isfinite(inv_edf)) return kNaN;
  return 1.0 / inv_edf;
}

namespace {

// The sum of edf_of(points) over the stretches where it is finite (NaN:
// too short a stretch for the factor); NaN when it is nowhere.
template <class EdfOf>
double sum_over_stretches(std::span<const std::int64_t> segment_points, EdfOf edf_of) {
  double total = 0.0;
  bool any = false;
  for (const std::int64_t points : segment_points) {
    const double edf = edf_of(points);
    if (!std::isfinite(edf)) continue;
    total += edf;
    any = true;
  }
  return any ? total : kNaN;
}

}  // namespace

double pooled_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points,
                  const DifferenceVariance& variance) {
  return sum_over_stretches(segment_points, [&](std::int64_t points) {
    return greenhall_edf(alpha, m, points, variance);
  });
}

double pooled_totdev_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points) {
  return sum_over_stretches(segment_points, [&](std::int64_t points) {
    // TOTDEV is defined up to m = (N - 1) / 2 (allan.h's max_factor)
    return 2 * m + 1 <= points ? totdev_edf(alpha, m, points) : kNaN;
  });
}

double totdev_edf(int alpha, std::int64_t m, std::int64_t n_phase) {
  // NIST SP 1065 Table 12: edf = b (T / tau) - c.
  const double ratio = static_cast<double>(n_phase) / static_cast<double>(m);
  switch (alpha) {
    case 0: return 1.50 * ratio;
    case -1: return 1.17 * ratio - 0.22;
    case -2: return 0.93 * ratio - 0.36;
    default:
      return greenhall_edf(alpha, m, n_phase);
  }
}

double mtotdev_edf(int alpha, std::int64_t m, std::int64_t n_phase) {
  // Below m = 10 the fits do not apply: the MDEV edf (as Stable32 does).
  if (m < 10) return greenhall_edf(alpha, m, n_phase, {.filter = Filter::modified});
  // edf = b (T / tau) - c, T / tau = N / m. For white PM, flicker FM and
  // random-walk FM, NIST SP 1065 section 5.2.12 (Table 10). For white FM and
  // flicker PM, Stable32 1.60 uses larger edf than that table's (1.10, 1.20)
  // and (1.20, 1.40); its PHASE.DAT bounds fit b (N / m) - c exactly with
  // the values below (octave table, m = 16 .. 256; its decade table's
  // m = 10 .. 200 agree to 1.2 %, tests/stats/allan_reference_test.cc).
  const double ratio = static_cast<double>(n_phase) / static_cast<double>(m);
  double b = 0.0, c = 0.0;
  switch (alpha) {
    case 2:
      b = 1.90, c = 2.10;
      break;
    case 1:
      b = 1.733, c = 2.99;
      break;
    case 0:
      b = 1.332, c = 1.894;
      break;
    case -1:
      b = 0.85, c = 0.50;
      break;
    case -2:
      b = 0.75, c = 0.31;
      break;
    default:
      return kNaN;
  }
  const double edf = b * ratio - c;
  return edf > 0.0 ? edf : kNaN;
}

double htotdev_edf(int alpha, std::int64_t m, std::int64_t n_phase) {
  // Howe, Beard, Greenhall and Riley's fits (NIST SP 1065 section 5.2.14):
  // edf = (T / tau) / (b0 + b1 tau / T) for white and flicker FM from m = 16;
  // elsewhere the OHDEV edf, which HTOTDEV's improves on.
  const double ratio = static_cast<double>(n_phase - 1) / static_cast<double>(m);  // rate points
  if (m >= 16 && alpha == 0) return ratio / (0.559 + 1.004 / ratio);
  if (m >= 16 && alpha == -1) return ratio / (0.868 + 1.140 / ratio);
  return greenhall_edf(alpha, m, n_phase, {.order = 3});
}

double theo1_edf(int alpha, std::int64_t m, std::int64_t n_phase) {
  // D. A. Howe and T. K. Peppler, "Estimation of very long-term frequency
  // stability using a special-purpose statistic", Proc. 2003 EFTF/IEEE FCS,
  // as Riley's "Confidence intervals and bias corrections for the Stable32
  // variance functions" lists them, with tau = 0.75 m in units of tau0 and
  // N phase points.
  const double n = static_cast<double>(n_phase);
  const double t = 0.75 * static_cast<double>(m);
  double edf = kNaN;
  switch (alpha) {
    case 2:
      edf = 0.86 * (n + 1.0) * (n - 4.0 * t / 3.0) / (n - t) * (t / (t + 1.14));
      break;
    case 1:
      edf = (4.798 * n * n - 6.374 * n * t + 12.387 * t) / (std::sqrt(t + 36.6) * (n - t)) *
            (t / (t + 0.3));
      break;
    case 0: {
      const double t15 = std::pow(t, 1.5);
      edf = ((4.1 * n + 0.8) / t - (3.1 * n + 6.5) / n) * (t15 / (t15 + 5.2));
      break;
    }
    case -1: {
      const double t3 = t * t * t;
      edf = (2.0 * n * n - 1.3 * n * t - 3.5 * t) / (n * t) * (t3 / (t3 + 2.3));
      break;
    }
    case -2: {
      const double a = 4.4 * n - 1.0;
      edf = (4.4 * n - 2.0) / (2.9 * t) * (a * a - 8.6 * t * a + 11.4 * t * t) /
            ((4.4 * n - 3.0) * (4.4 * n - 3.0));
      break;
    }
    default:
      break;
  }
  // The random-walk fit turns negative beyond m ~ 0.84 N: no interval there.
  return edf > 0.0 ? edf : kNaN;
}

double htotdev_bias(int alpha, std::int64_t m) {
  // W. J. Riley, "Confidence intervals and bias corrections for the Stable32
  // variance functions" (Hamilton Technical Services, 2000): HTOTVAR / HVAR.
  if (m <= 1) return 1.0;
  switch (alpha) {
    case 0:
      return 0.995;
    case -1:
      return 0.851;
    case -2:
      return 0.771;
    case -3:
      return 0.717;
    case -4:
      return 0.679;
    default:
      return 1.0;
  }
}

double pooled_mtotdev_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points) {
  return sum_over_stretches(segment_points, [&](std::int64_t points) {
    return 3 * m <= points ? mtotdev_edf(alpha, m, points) : kNaN;
  });
}

double pooled_theo1_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points) {
  return sum_over_stretches(segment_points, [&](std::int64_t points) {
    return m + 1 <= points ? theo1_edf(alpha, m, points) : kNaN;
  });
}

double pooled_htotdev_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points) {
  return sum_over_stretches(segment_points, [&](std::int64_t points) {
    return 3 * m + 1 <= points ? htotdev_edf(alpha, m, points) : kNaN;
  });
}

}  // namespace foglab::stats
