// foglab — the generator's building blocks (generator_internal.h): the
// normal random numbers (a ziggurat on counter-based words), the exact
// Ornstein-Uhlenbeck step, and the bank of OU components that makes
// flicker noise.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "foglab/core/error.h"
#include "foglab/core/noise_model.h"
#include "foglab/core/numeric.h"
#include "generator_internal.h"

namespace foglab::sim {

// ============================================================================
// detail: random numbers, OU coefficients, flicker design
// ============================================================================
namespace detail {

const Ziggurat& ziggurat() {
  static const Ziggurat table = [] {
    // Marsaglia & Tsang (2000) constants for 256 layers; V is recomputed from
    // R so that the layers have exactly equal areas.
    Ziggurat z{};
    const double r = 3.6541528853610088;
    const double fr = std::exp(-0.5 * r * r);
    const double v = r * fr + std::sqrt(0.5 * std::numbers::pi) * std::erfc(r / std::sqrt(2.0));
    z.r = r;
    z.x[0] = v / fr;
    z.x[1] = r;
    z.x[Ziggurat::kLayers] = 0.0;
    double f = fr;
    for (int i = 2; i < Ziggurat::kLayers; ++i) {
      z.x[i] = std::sqrt(-2.0 * std::log(v / z.x[i - 1] + f));
      f = std::exp(-0.5 * z.x[i] * z.x[i]);
    }
    for (int i = 0; i < Ziggurat::kLayers; ++i) z.ratio[i] = z.x[i + 1] / z.x[i];
    for (int i = 0; i <= Ziggurat::kLayers; ++i) z.f[i] = std::exp(-0.5 * z.x[i] * z.x[i]);
    return z;
  }();
  return table;
}

double normal_slow(const Ziggurat& z, std::uint64_t word) {
  // Further words for this deviate: re-hash the first one with a counter.
  std::uint64_t extra = 0;
  const auto next_word = [&] { return mix64(word ^ (0x5851f42d4c957f2dULL * ++extra)); };
  const auto open_uniform = [](std::uint64_t w) {  // (0, 1)
    return (static_cast<double>(w >> 11) + 0.5) * 0x1.0p-53;
  };
  std::uint64_t w = word;
  for (;;) {
    const unsigned layer = static_cast<unsigned>(w & 0xFFu);
    const double u = static_cast<double>(static_cast<std::int64_t>(w) >> 11) * 0x1.0p-52;
    if (std::fabs(u) < z.ratio[layer]) return u * z.x[layer];
    if (layer == 0) {  // the tail beyond r (Marsaglia 1964)
      double x = 0.0;
      double y = 0.0;
      do {
        x = std::log(open_uniform(next_word())) / z.r;
        y = std::log(open_uniform(next_word()));
      } while (-2.0 * y < x * x);
      return u < 0.0 ? x - z.r : z.r - x;
    }
    const double x = u * z.x[layer];
    // The wedge: accept under the density (one exp; Marsaglia & Tsang's form
    // of Doornik's test f1 + U (f0 - f1) < 1).
    if (z.f[layer + 1] + uniform_of(next_word()) * (z.f[layer] - z.f[layer + 1]) <
        std::exp(-0.5 * x * x)) {
      return x;
    }
    w = next_word();
  }
}

namespace {

// Power series sum_{n >= n0} (-1)^n coef(n) x^(n - shift) / n!, for small x.
template <typename Coef>
double series(double x, int n0, int shift, Coef coef) {
  double factorial = 1.0;
  for (int n = 2; n < n0; ++n) factorial *= n;
  double sum = 0.0;
  for (int n = n0; n < n0 + 30; ++n) {
    factorial *= n;
    sum += ((n % 2 == 0) ? 1.0 : -1.0) * coef(n) * std::pow(x, n - shift) / factorial;
  }
  return sum;
}

constexpr double kSeriesBelow = 0.25;

// g(x) = [x - 2(1 - e^-x) + (1 - e^-2x)/2] / x^3
double ou_g(double x) {
  if (x < kSeriesBelow) {
    return series(x, 3, 3, [](int n) { return 2.0 - std::ldexp(1.0, n - 1); });
  }
  return (x + 2.0 * std::expm1(-x) - 0.5 * std::expm1(-2.0 * x)) / (x * x * x);
}

// c(x) = [(1 - e^-x) - (1 - e^-2x)/2] / x^2
double ou_c(double x) {
  if (x < kSeriesBelow) {
    return series(x, 2, 2, [](int n) { return std::ldexp(1.0, n - 1) - 1.0; });
  }
  return (-std::expm1(-x) + 0.5 * std::expm1(-2.0 * x)) / (x * x);
}

}  // namespace

OuStep ou_step(double tc_s, double h_s) {
  const double x = h_s / tc_s;
  OuStep s;
  s.rho = std::exp(-x);
  s.beta = -std::expm1(-x) / x;
  const double v1 = -std::expm1(-2.0 * x);
  const double v2 = 2.0 * x * ou_g(x);
  const double c = 2.0 * x * ou_c(x);
  s.s_state = std::sqrt(v1);
  s.s_avg_state = c / s.s_state;
  s.s_avg = std::sqrt(std::max(0.0, v2 - c * c / v1));
  return s;
}

FlickerDesign design_flicker(double sample_rate_hz, double duration_s) {
  const double tau0 = 1.0 / sample_rate_hz;
  const double record = std::max(duration_s, tau0);
  FlickerDesign d;
  d.fit_tau_min_s = tau0;
  d.fit_tau_max_s = std::max(record, 10.0 * tau0);
  // Correlation times log-spaced, kFlickerPerDecade per decade, from tau0/2
  // to at least 10 x the record length.
  const double step = std::pow(10.0, 1.0 / kFlickerPerDecade);
  for (double tc = 0.3 * tau0;; tc *= step) {
    FlickerComponent c;
    c.tc_s = tc;
    const double d_max = tc / (kFlickerDecimationRatio * tau0);
    c.level = d_max >= 2.0
                  ? std::min(kFlickerMaxLevel, static_cast<int>(std::floor(std::log2(d_max))))
                  : 0;
    d.components.push_back(c);
    if (tc >= 10.0 * d.fit_tau_max_s) break;
  }
  const auto count = static_cast<Eigen::Index>(d.components.size());
  // Calibration grid: 10 taus per decade over the fit range.
  std::vector<double> taus;
  const double decades = std::log10(d.fit_tau_max_s / d.fit_tau_min_s);
  const int points = std::max(2, static_cast<int>(std::ceil(10.0 * decades)) + 1);
  for (int i = 0; i < points; ++i) {
    taus.push_back(d.fit_tau_min_s * std::pow(10.0, decades * i / (points - 1)));
  }
  // Unknowns z_j = variance_j / w0, w0 = (ln 10 / per_decade) / pi the
  // continuum weight (sum of OU spectra 2 w Tc/(1 + (2 pi f Tc)^2) over
  // log-uniform Tc = B^2/(2 pi f)). Least squares on the relative error of
  // the plateau, plus a small ridge towards z = 1 that fixes the poorly
  // determined components far outside the fit range.
  const double w0 = std::log(10.0) / kFlickerPerDecade / std::numbers::pi;
  const double ridge = 1e-6;
  Eigen::MatrixXd a(static_cast<Eigen::Index>(taus.size()) + count, count);
  Eigen::VectorXd b(a.rows());
  a.setZero();
  for (std::size_t i = 0; i < taus.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    for (Eigen::Index j = 0; j < count; ++j) {
      a(row, j) =
          w0 * gauss_markov_allan_shape(taus[i], d.components[static_cast<std::size_t>(j)].tc_s) /
          kFlickerAllanFactor;
    }
    b(row) = 1.0;
  }
  for (Eigen::Index j = 0; j < count; ++j) {
    a(static_cast<Eigen::Index>(taus.size()) + j, j) = std::sqrt(ridge);
    b(static_cast<Eigen::Index>(taus.size()) + j) = std::sqrt(ridge);
  }
  // Non-negative solution: drop components with a negative weight and refit.
  std::vector<bool> active(static_cast<std::size_t>(count), true);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(count);
  for (int iteration = 0; iteration < 100; ++iteration) {
    Eigen::MatrixXd sub = a;
    for (Eigen::Index j = 0; j < count; ++j) {
      if (!active[static_cast<std::size_t>(j)]) sub.col(j).setZero();
    }
    z = sub.colPivHouseholderQr().solve(b);
    bool changed = false;
    for (Eigen::Index j = 0; j < count; ++j) {
      if (!active[static_cast<std::size_t>(j)]) {
        z(j) = 0.0;
      } else if (z(j) < 0.0) {
        active[static_cast<std::size_t>(j)] = false;
        z(j) = 0.0;
        changed = true;
      }
    }
    if (!changed) break;
  }
  for (Eigen::Index j = 0; j < count; ++j) {
    d.components[static_cast<std::size_t>(j)].variance = w0 * z(j);
  }
  double worst = 0.0;
  for (const double tau : taus) {
    worst =
        std::max(worst, std::fabs(flicker_bank_allan_variance(d, tau) / kFlickerAllanFactor - 1.0));
  }
  d.max_relative_error = worst;
  return d;
}

double flicker_bank_allan_variance(const FlickerDesign& design, double tau_s) {
  double sum = 0.0;
  for (const auto& c : design.components)
    sum += c.variance * gauss_markov_allan_shape(tau_s, c.tc_s);
  return sum;
}

}  // namespace detail

}  // namespace foglab::sim
