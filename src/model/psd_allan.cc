// foglab — the Allan variance a PSD implies, eq. (17) (psd_allan.h).
#include "foglab/model/psd_allan.h"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>

#include "foglab/core/error.h"
#include "foglab/core/sensor_bandwidth.h"

namespace foglab::model {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPeriod = kPi / 2.0;  // of sin^4 in x = pi f tau: its period is pi
/// Half periods of sin^4 integrated exactly; beyond them sin^4 is replaced by
/// its mean 3/8 (the rest of the integrand changes by ~1/x per period: the
/// error is of order x^-3, below 1e-8 of the integral at 400).
constexpr int kExactHalfPeriods = 400;

/// int_a^b g(e^u) e^u du: smooth on a log scale, from near 0 to the first bump.
template <class G>
double log_integral(const G& g, double a, double b) {
  if (!(a < b)) return 0.0;
  return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
      [&](double u) {
        const double x = std::exp(u);
        return g(x) * x;
      },
      std::log(a), std::log(b), 12, 1e-10);
}

}  // namespace

double fitted_rate_psd(const NoiseFitResult& fit, double frequency_hz, double sample_interval_s) {
  const NoiseModel& m = fit.model;
  const double response = fit.bandwidth.resolved ? power_response(fit.bandwidth.bandwidth,
                                                                  frequency_hz, sample_interval_s)
                                                 : 1.0;
  double s = response * (rate_psd(m, NoiseTerm::white, frequency_hz, sample_interval_s) +
                         rate_psd(m, NoiseTerm::flicker, frequency_hz, sample_interval_s));
  if (m.K > 0.0) s += rate_psd(m, NoiseTerm::random_walk, frequency_hz, sample_interval_s);
  if (m.gm_sigma > 0.0 && m.gm_tc > 0.0) {
    s += rate_psd(m, NoiseTerm::gauss_markov, frequency_hz, sample_interval_s);
  }
  if (m.Q > 0.0) {
    // White angle noise of variance Q^2 per sample, differenced: exact for
    // sampled data (core's rate_psd() has its low-frequency form (2 pi f)^2 Q^2 tau0).
    const double sn = std::sin(kPi * frequency_hz * sample_interval_s);
    s += 4.0 * m.Q * m.Q * sn * sn / sample_interval_s;
  }
  return s + fit.known_white_deg_h_sqrt_hz * fit.known_white_deg_h_sqrt_hz;
}

double allan_variance_from_psd(const std::function<double(double)>& psd, double tau_s,
                               double sample_interval_s, double low_frequency_hz) {
  if (!(tau_s > 0.0) || !(sample_interval_s > 0.0) || !(low_frequency_hz > 0.0)) {
    throw UsageError(fmt::format(
        "Allan variance from a PSD: tau, the sample interval and the lowest frequency must be "
        "positive, got {} s, {} s and {} Hz",
        tau_s, sample_interval_s, low_frequency_hz));
  }
  const double m = std::max(1.0, std::round(tau_s / sample_interval_s));
  const double tau = m * sample_interval_s;
  // x = pi f tau: f = x / (pi tau), df = dx / (pi tau); the m-average's
  // kernel sin^4(x) / (m sin(x / m))^2.
  const double x_low = kPi * low_frequency_hz * tau;
  const double x_high = kPi * m / 2.0;  // the Nyquist frequency
  if (!(x_low < x_high)) return 0.0;
  auto frequency = [tau](double x) { return x / (kPi * tau); };
  auto denominator = [m](double x) {
    const double d = m * std::sin(x / m);
    return d * d;
  };
  auto kernel = [&](double x) {
    const double s = std::sin(x);
    return psd(frequency(x)) * s * s * s * s / denominator(x);
  };
  double sum = log_integral(kernel, x_low, std::min(kHalfPeriod, x_high));
  double x = std::max(x_low, kHalfPeriod);
  for (int k = 0; x < x_high && k < kExactHalfPeriods; ++k) {
    const double next = std::min(x_high, (std::floor(x / kHalfPeriod + 1e-9) + 1.0) * kHalfPeriod);
    sum += boost::math::quadrature::gauss<double, 15>::integrate(kernel, x, next);
    x = next;
  }
  sum += log_integral([&](double xx) { return 0.375 * psd(frequency(xx)) / denominator(xx); }, x,
                      x_high);
  return 4.0 / (kPi * tau) * sum;
}

PsdAllanCheck check_allan_against_psd(const NoiseFitResult& fit, const stats::AllanResult& allan,
                                      double sample_interval_s, double duration_s) {
  PsdAllanCheck c;
  const bool allan_kernel =
      allan.kind == stats::AllanKind::oadev || allan.kind == stats::AllanKind::adev;
  if (fit.status == FitStatus::degenerate || !allan_kernel || allan.input != InputKind::rate ||
      !(sample_interval_s > 0.0) || !(duration_s > sample_interval_s)) {
    return c;
  }
  const auto psd = [&](double f) { return fitted_rate_psd(fit, f, sample_interval_s); };
  // The Allan difference of a record of length T sees the frequencies below
  // 1/T too (its kernel falls as (f tau)^2 there, and every random term's
  // integral converges at 0): the integral starts far below 1/T.
  const double f_low = 1e-6 / duration_s;
  const std::size_t first = static_cast<std::size_t>(std::max(0, fit.first_taus_left_out));
  double worst = -1.0;
  for (std::size_t i = 0; i < allan.tau_s.size(); ++i) {
    const double tau = allan.tau_s[i];
    const double adev =
        std::sqrt(allan_variance_from_psd(psd, tau, sample_interval_s, f_low) +
                  lines_allan_variance(fit, tau) + allan_variance(fit.model, NoiseTerm::ramp, tau));
    c.tau_s.push_back(tau);
    c.adev_deg_h.push_back(adev);
    if (i < first || i >= allan.ci95_low.size() || i >= allan.ci95_high.size()) continue;
    const double measured = allan.dev[i], lo = allan.ci95_low[i], hi = allan.ci95_high[i];
    if (!(measured > 0.0 && lo > 0.0 && hi > measured && lo < measured && adev > 0.0)) continue;
    ++c.compared;
    const double half_width = adev >= measured ? std::log(hi / measured) : std::log(measured / lo);
    const double distance = std::fabs(std::log(adev / measured)) / half_width;
    if (distance <= 1.0) ++c.inside_95;
    if (distance > worst) {
      worst = distance;
      c.worst_tau_s = tau;
      c.worst_ratio = adev / measured;
      c.worst_half_widths = distance;
    }
  }
  return c;
}

}  // namespace foglab::model
