// foglab — the random error model and its theory (noise_model.h).
#include "foglab/core/noise_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "foglab/core/error.h"

namespace foglab {
namespace {

constexpr std::array<std::string_view, kNoiseTerms.size()> kSymbols = {"N", "B", "K",
                                                                       "R", "Q", "GM"};

// ARW [deg/sqrt(h)] per N [deg/h/sqrt(Hz)]: N deg/h sqrt(s) = N/60 deg/sqrt(h).
constexpr double kSqrtSecondsPerHour = 60.0;

// The Gauss-Markov Allan variance per sigma^2 as a function of x = tau/Tc,
// f(x) = (2x - 3 + 4 e^-x - e^-2x) / x^2 = sum_{n>=3} (-1)^n (4 - 2^n) x^(n-2) / n!.
// Below x = 1/4 the closed form loses digits to cancellation and the series
// is used: its terms fall by about x/n each, so 18 terms reach 1e-17 there.
constexpr double kGaussMarkovSeriesBelow = 0.25;
constexpr int kGaussMarkovSeriesTerms = 18;

constexpr std::array<double, kGaussMarkovSeriesTerms> gauss_markov_series() {
  // Coefficient of x^k, k = 1..terms: (-1)^(k+2) (4 - 2^(k+2)) / (k+2)!.
  std::array<double, kGaussMarkovSeriesTerms> a{};
  double factorial = 2.0;  // 2!
  double power = 4.0;      // 2^2
  for (int k = 1; k <= kGaussMarkovSeriesTerms; ++k) {
    factorial *= k + 2;
    power *= 2.0;
    a[static_cast<std::size_t>(k - 1)] = (k % 2 == 0 ? 1.0 : -1.0) * (4.0 - power) / factorial;
  }
  return a;
}
constexpr std::array<double, kGaussMarkovSeriesTerms> kGaussMarkovSeries = gauss_markov_series();

void check_tau_range(std::string_view function, double tau_min_s, double tau_max_s) {
  if (!(tau_min_s > 0.0) || !(tau_max_s >= tau_min_s)) {
    throw UsageError(
        fmt::format("{}: invalid tau range [{}, {}] s", function, tau_min_s, tau_max_s));
  }
}

}  // namespace

std::string_view to_string(NoiseTerm term) { return kSymbols[static_cast<std::size_t>(term)]; }

NoiseTerm noise_term_from_string(std::string_view text) {
  for (NoiseTerm t : kNoiseTerms) {
    if (text == to_string(t)) return t;
  }
  throw UsageError(fmt::format("noise term: expected N, B, K, R, Q or GM, got '{}'", text));
}

std::string_view describe(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::white:
      return "white rate noise";
    case NoiseTerm::flicker:
      return "flicker (bias instability)";
    case NoiseTerm::random_walk:
      return "rate random walk";
    case NoiseTerm::ramp:
      return "rate ramp";
    case NoiseTerm::quantisation:
      return "angle quantisation";
    case NoiseTerm::gauss_markov:
      return "first-order Gauss-Markov random bias";
  }
  return "?";
}

std::string to_string(NoiseTermSet terms) {
  std::string name;
  for (NoiseTerm t : kNoiseTerms) {
    if (!terms.contains(t)) continue;
    if (!name.empty()) name += '+';
    name += to_string(t);
  }
  return name.empty() ? "none" : name;
}

NoiseTermSet noise_term_set_from_string(std::string_view text) {
  NoiseTermSet set;
  if (text == "none") return set;
  while (true) {
    const auto plus = text.find('+');
    const NoiseTerm t = noise_term_from_string(text.substr(0, plus));
    if (set.contains(t)) {
      throw UsageError(fmt::format("noise terms: '{}' is named twice", to_string(t)));
    }
    set = set.with(t);
    if (plus == std::string_view::npos) return set;
    text.remove_prefix(plus + 1);
  }
}

double NoiseModel::coefficient(NoiseTerm term) const {
  switch (term) {
    case NoiseTerm::white:
      return N;
    case NoiseTerm::flicker:
      return B;
    case NoiseTerm::random_walk:
      return K;
    case NoiseTerm::ramp:
      return R;
    case NoiseTerm::quantisation:
      return Q;
    case NoiseTerm::gauss_markov:
      return gm_sigma;
  }
  return 0.0;
}

void NoiseModel::set_coefficient(NoiseTerm term, double value) {
  switch (term) {
    case NoiseTerm::white:
      N = value;
      break;
    case NoiseTerm::flicker:
      B = value;
      break;
    case NoiseTerm::random_walk:
      K = value;
      break;
    case NoiseTerm::ramp:
      R = value;
      break;
    case NoiseTerm::quantisation:
      Q = value;
      break;
    case NoiseTerm::gauss_markov:
      gm_sigma = value;
      break;
  }
}

NoiseTermSet NoiseModel::terms() const {
  NoiseTermSet set;
  for (NoiseTerm t : kNoiseTerms) {
    if (coefficient(t) > 0.0) set = set.with(t);
  }
  return set;
}

std::string_view to_string(RandomBiasProcess process) {
  switch (process) {
    case RandomBiasProcess::none:
      return "none";
    case RandomBiasProcess::wiener:
      return "wiener";
    case RandomBiasProcess::gauss_markov:
      return "gauss_markov";
  }
  return "?";
}

double flicker_floor_deg_h(double b_deg_h) { return std::sqrt(kFlickerAllanFactor) * b_deg_h; }

double flicker_coefficient_deg_h(double floor_deg_h) {
  return floor_deg_h / std::sqrt(kFlickerAllanFactor);
}

double arw_deg_sqrt_h(double n_deg_h_sqrt_hz) { return n_deg_h_sqrt_hz / kSqrtSecondsPerHour; }

double white_noise_of_arw(double arw_deg_sqrt_h) { return arw_deg_sqrt_h * kSqrtSecondsPerHour; }

double gauss_markov_allan_shape(double tau_s, double tc_s) {
  const double x = tau_s / tc_s;
  if (x < kGaussMarkovSeriesBelow) {
    double sum = 0.0;
    for (auto a = kGaussMarkovSeries.rbegin(); a != kGaussMarkovSeries.rend(); ++a) {
      sum = (sum + *a) * x;
    }
    return sum;
  }
  return (2.0 * x + 4.0 * std::expm1(-x) - std::expm1(-2.0 * x)) / (x * x);
}

double unit_allan_variance(NoiseTerm term, double tau_s, double tc_s) {
  switch (term) {
    case NoiseTerm::white:
      return 1.0 / tau_s;
    case NoiseTerm::flicker:
      return kFlickerAllanFactor;
    case NoiseTerm::random_walk:
      return tau_s / 3.0;
    case NoiseTerm::ramp:
      return tau_s * tau_s / 2.0;
    case NoiseTerm::quantisation:
      return 3.0 / (tau_s * tau_s);
    case NoiseTerm::gauss_markov:
      return gauss_markov_allan_shape(tau_s, tc_s);
  }
  return 0.0;
}

double allan_variance(const NoiseModel& model, NoiseTerm term, double tau_s) {
  const double c = model.coefficient(term);
  if (c == 0.0) return 0.0;
  if (term == NoiseTerm::gauss_markov && !(model.gm_tc > 0.0)) return 0.0;
  return c * c * unit_allan_variance(term, tau_s, model.gm_tc);
}

double allan_variance(const NoiseModel& model, double tau_s) {
  double sum = 0.0;
  for (NoiseTerm t : kNoiseTerms) sum += allan_variance(model, t, tau_s);
  return sum;
}

double rate_psd(const NoiseModel& model, NoiseTerm term, double frequency_hz,
                double sample_interval_s) {
  const double w = 2.0 * std::numbers::pi * frequency_hz;  // [rad/s]
  const double c = model.coefficient(term);
  switch (term) {
    case NoiseTerm::white:
      return c * c;
    case NoiseTerm::flicker:
      return c * c / w;
    case NoiseTerm::random_walk:
      return c * c / (w * w);
    case NoiseTerm::ramp:
      return c * c / (w * w * w);
    case NoiseTerm::quantisation:
      return w * w * sample_interval_s * c * c;
    case NoiseTerm::gauss_markov: {
      const double wt = w * model.gm_tc;
      return 2.0 * c * c * model.gm_tc / (1.0 + wt * wt);
    }
  }
  return 0.0;
}

double angle_structure_function(const NoiseModel& model, NoiseTerm term, double lag_s) {
  const double s = lag_s;
  if (!(s > 0.0)) return 0.0;
  const double c = model.coefficient(term);
  if (c == 0.0) return 0.0;
  switch (term) {
    case NoiseTerm::white:
      return c * c * s;
    case NoiseTerm::quantisation:
      return 2.0 * c * c;  // white angle of variance Q^2
    case NoiseTerm::flicker:
      // Two-sided PSD h / |f| with h = B^2 / (2 pi).
      return -2.0 * (c * c / (2.0 * std::numbers::pi)) * s * s * std::log(s);
    case NoiseTerm::random_walk:
      return -c * c * s * s * s / 6.0;
    case NoiseTerm::ramp:
      return 0.0;
    case NoiseTerm::gauss_markov: {
      if (!(model.gm_tc > 0.0)) return 0.0;
      // e(x) = x - 1 + e^-x: x + expm1(-x) loses 2 eps / x relative to
      // cancellation; below x = 0.1 its series sum_{n>=2} (-x)^n / n!.
      const double x = s / model.gm_tc;
      double e = 0.0;
      if (x < 0.1) {
        double term = 0.5 * x * x;
        for (int n = 3; n <= 14; ++n) {
          e += term;
          term *= -x / n;
        }
      } else {
        e = x + std::expm1(-x);
      }
      return 2.0 * c * c * model.gm_tc * model.gm_tc * e;
    }
  }
  return 0.0;
}

AdevMinimum adev_minimum(const NoiseModel& model, double tau_min_s, double tau_max_s,
                         int points_per_decade) {
  check_tau_range("adev_minimum", tau_min_s, tau_max_s);
  if (points_per_decade < 1) {
    throw UsageError(
        fmt::format("adev_minimum: points_per_decade must be >= 1, got {}", points_per_decade));
  }
  const double lo = std::log10(tau_min_s);
  const double hi = std::log10(tau_max_s);
  const int steps = std::max(1, static_cast<int>(std::ceil((hi - lo) * points_per_decade)));
  auto log_tau = [&](int i) { return lo + (hi - lo) * i / steps; };
  auto f = [&](double lt) { return allan_variance(model, std::pow(10.0, lt)); };
  int best = 0;
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= steps; ++i) {
    const double v = f(log_tau(i));
    if (v < best_value) {
      best_value = v;
      best = i;
    }
  }
  double best_lt = log_tau(best);
  if (best > 0 && best < steps) {
    // Golden-section refinement between the neighbours.
    double a = log_tau(best - 1);
    double b = log_tau(best + 1);
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double c = b - g * (b - a);
    double d = a + g * (b - a);
    double fc = f(c);
    double fd = f(d);
    for (int it = 0; it < 60; ++it) {
      if (fc < fd) {
        b = d;
        d = c;
        fd = fc;
        c = b - g * (b - a);
        fc = f(c);
      } else {
        a = c;
        c = d;
        fc = fd;
        d = a + g * (b - a);
        fd = f(d);
      }
    }
    const double lt = (a + b) / 2.0;
    if (f(lt) <= best_value) {
      best_lt = lt;
      best_value = f(lt);
    }
  }
  AdevMinimum out;
  out.adev_deg_h = std::sqrt(best_value);
  out.tau_s = std::clamp(std::pow(10.0, best_lt), tau_min_s, tau_max_s);
  out.at_range_edge = best == 0 || best == steps;
  return out;
}

double term_dominance_octaves(const NoiseModel& model, NoiseTerm term, double tau_min_s,
                              double tau_max_s) {
  check_tau_range("term_dominance_octaves", tau_min_s, tau_max_s);
  constexpr int kSteps = 400;
  const double step = std::log2(tau_max_s / tau_min_s) / kSteps;
  double best = 0.0;
  int first = -1;  // the grid point where the current stretch began
  for (int s = 0; s <= kSteps; ++s) {
    const double tau = tau_min_s * std::exp2(s * step);
    const double total = allan_variance(model, tau);
    if (total > 0.0 && allan_variance(model, term, tau) >= 0.5 * total) {
      if (first < 0) first = s;
      best = std::max(best, (s - first) * step);
    } else {
      first = -1;
    }
  }
  return best;
}

}  // namespace foglab
