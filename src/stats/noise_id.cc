#include "foglab/stats/noise_id.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
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

// Lag-1 autocorrelation method on the decimated angle points p_k = x_{k m}.
NoiseId lag1_identify(std::span<const double> phase, std::int64_t m, int d_max) {
  const auto n = static_cast<std::int64_t>(phase.size());
  const std::int64_t K = (n - 1) / m + 1;
  const double* x = phase.data();
  const double scale = 2.0 / static_cast<double>(K - 1);
  auto basis = [scale](std::int64_t k) {
    const double u = static_cast<double>(k) * scale - 1.0;  // in [-1, 1]
    return Eigen::Vector3d(1.0, u, 1.5 * u * u - 0.5);      // Legendre P0..P2
  };

  // Pass 1: least-squares quadratic in a well-conditioned basis.
  const auto chunk = static_cast<std::int64_t>(kChunkSamples);
  const std::int64_t chunks = (K + chunk - 1) / chunk;
  std::vector<Eigen::Matrix3d> gram(static_cast<std::size_t>(chunks));
  std::vector<Eigen::Vector3d> rhs(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    const std::int64_t end = std::min(K, (c + 1) * chunk);
    for (std::int64_t k = c * chunk; k < end; ++k) {
      const Eigen::Vector3d p = basis(k);
      g.noalias() += p * p.transpose();
      b += p * x[k * m];
    }
    gram[c] = g;
    rhs[c] = b;
  }
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::int64_t c = 0; c < chunks; ++c) {
    g += gram[c];
    b += rhs[c];
  }
  const Eigen::Vector3d coef = g.ldlt().solve(b);
  auto residual = [&](std::int64_t k) { return x[k * m] - coef.dot(basis(k)); };

  // Pass 2: raw sums for every difference order at once.
  std::vector<DiffSums> partial(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t begin = c * chunk;
    const std::int64_t end = std::min(K, begin + chunk);
    const std::int64_t buf_end = std::min(K, end + kMaxD + 1);
    std::vector<double> z(static_cast<std::size_t>(buf_end - begin));
    for (std::int64_t k = begin; k < buf_end; ++k) z[k - begin] = residual(k);
    DiffSums s;
    for (int d = 0; d <= d_max; ++d) {
      if (d > 0) {  // difference in place; the last d entries become stale
        for (std::size_t i = 0; i + 1 < z.size(); ++i) z[i] = z[i + 1] - z[i];
      }
      const std::int64_t length = K - d;  // z^(d)_k exists for k < K - d
      double s1 = 0.0, s2 = 0.0, sl = 0.0;
      const std::int64_t stop = std::min(end, length);
      for (std::int64_t k = begin; k < stop; ++k) {
        const double v = z[k - begin];
        s1 += v;
        s2 += v * v;
        if (k + 1 < length) sl += v * z[k + 1 - begin];
      }
      s.sum[d] = s1;
      s.sum_sq[d] = s2;
      s.sum_lag[d] = sl;
    }
    partial[c] = s;
  }

  // End values z^(d)_0 and z^(d)_{L-1} for centring.
  std::array<double, kMaxD + 2> head{}, tail{};
  for (int i = 0; i <= kMaxD + 1; ++i) {  // K >= 30 points
    head[i] = residual(i);
    tail[i] = residual(K - (kMaxD + 2) + i);
  }
  NoiseId id;
  id.method = "lag1_acf";
  for (int d = 0; d <= d_max; ++d) {
    CompensatedSum s1, s2, sl;
    for (const auto& p : partial) {
      s1.add(p.sum[d]);
      s2.add(p.sum_sq[d]);
      sl.add(p.sum_lag[d]);
    }
    const double length = static_cast<double>(K - d);
    const double mu = s1.value() / length;
    // z^(d)_0 from the head, z^(d)_{L-1} from the tail (d-th differences).
    std::array<double, kMaxD + 2> h = head, t = tail;
    for (int j = 0; j < d; ++j) {
      for (int i = 0; i + 1 <= kMaxD + 1 - j; ++i) {
        h[i] = h[i + 1] - h[i];
        t[i] = t[i + 1] - t[i];
      }
    }
    const double first = h[0];
    const double last = t[kMaxD + 1 - d];
    const double num = sl.value() - mu * (s1.value() - last) - mu * (s1.value() - first) +
                       (length - 1.0) * mu * mu;
    const double den = s2.value() - length * mu * mu;
    const double r1 = den > 0.0 ? num / den : 0.0;
    const double rho = r1 / (1.0 + r1);
    if (rho < 0.25 || d == d_max) {
      id.rho = rho;
      id.differences = d;
      id.alpha = 2 - 2 * d - static_cast<int>(std::nearbyint(2.0 * rho));
      return id;
    }
  }
  return id;
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
    id.method = "none";
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
  id.method = "b1";
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
  const double adev = deviations_from_phase(phase, AllanKind::adev, factor)[0];
  const double mdev = deviations_from_phase(phase, AllanKind::mdev, factor)[0];
  const double rn = adev > 0.0 ? (mdev * mdev) / (adev * adev) : 0.5;
  const double md = static_cast<double>(m);
  const double rn_white_pm = 1.0 / md;
  const double rn_flicker_pm =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(kPi * md)));
  const double rn_white_fm = 0.5;
  id.method = "b1_rn";
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

NoiseId identify_noise(std::span<const double> phase, std::int64_t m, int d_max) {
  d_max = std::clamp(d_max, 1, kMaxD);
  const auto n = static_cast<std::int64_t>(phase.size());
  const std::int64_t points = n > 0 ? (n - 1) / m + 1 : 0;
  NoiseId id = points >= kMinLag1Points ? lag1_identify(phase, m, d_max)
                                        : b1_identify(phase, m, d_max);
  const int lowest = d_max >= 3 ? -4 : -2;
  id.alpha = std::clamp(id.alpha, lowest, 2);
  return id;
}

}  // namespace foglab::stats
