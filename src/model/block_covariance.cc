#include "block_covariance.h"

#include <cmath>

namespace foglab::model::detail {
namespace {

// Phase structure functions D_x(s) = E[(x(t+s) - x(t))^2] of the noise
// terms, x the integrated rate [(deg/h) s], s >= 0 (core/noise_model.h).
// Stationary terms (finite variance): white, Gauss-Markov, quantisation.
// Flicker: Greenhall's generalised form, up to an s^2 term that every second
// difference cancels. The Wiener term K^2 s^3/3 is written out in
// block_covariance().
double stationary_structure(const NoiseModel& m, double s) {
  return angle_structure_function(m, NoiseTerm::white, s) +
         angle_structure_function(m, NoiseTerm::quantisation, s) +
         angle_structure_function(m, NoiseTerm::gauss_markov, s);
}

double flicker_structure(const NoiseModel& m, double s) {
  return angle_structure_function(m, NoiseTerm::flicker, s);
}

}  // namespace

// Covariance of block means (blocks of tau seconds) at lags 0..lags-1, from
// Cov = Var - E[(ybar_a - ybar_b)^2]/2 and
// E[(ybar_a - ybar_{a+k})^2] = (2 D(tau) + 2 D(k tau) - D((k+1) tau) - D(|k-1| tau)) / tau^2.
// The non-stationary terms (flicker, Wiener) have no variance; they are given
// up to a matrix f(a) + f(b), which changes only the intercept's variance.
// The Wiener rate W has stationary increments itself: block means k >= 1
// apart differ by the average of lag-k tau increments that overlap by
// k tau - |s - u|, so E[(ybar_a - ybar_{a+k})^2] = K^2 (k tau - tau/3).
std::vector<double> block_covariance(const NoiseModel& m, double tau, std::size_t lags,
                                     TermGroup group) {
  const bool stationary = group == TermGroup::stationary;
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

}  // namespace foglab::model::detail
