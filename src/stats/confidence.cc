#include "foglab/stats/confidence.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

namespace foglab::stats {

Interval chi2_interval(double dev, double edf, double p) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(edf > 0.0) || !std::isfinite(edf) || !(p > 0.0 && p < 1.0) || !std::isfinite(dev)) {
    return {nan, nan};
  }
  const boost::math::chi_squared_distribution<double> chi2(edf);
  const double tail = (1.0 - p) / 2.0;
  const double chi2_low = boost::math::quantile(chi2, tail);
  const double chi2_high = boost::math::quantile(chi2, 1.0 - tail);
  return {dev * std::sqrt(edf / chi2_high), dev * std::sqrt(edf / chi2_low)};
}

double chi2_quantile(double dof, double p) {
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof), p);
}

double edf_from_interval(double dev, double low, double high, double p) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(low > 0.0 && low < dev && dev < high) || !std::isfinite(high)) return nan;
  // The width ln(high/low) falls monotonically with the edf.
  const double width = std::log(high / low);
  auto gap = [&](double log_edf) {
    const Interval i = chi2_interval(1.0, std::exp(log_edf), p);
    return std::log(i.high / i.low) - width;
  };
  double a = std::log(0.1), b = std::log(1e9);
  if (gap(a) < 0.0 || gap(b) > 0.0) return nan;
  boost::math::tools::eps_tolerance<double> tolerance(40);
  std::uintmax_t iterations = 100;
  const auto [lo, hi] = boost::math::tools::toms748_solve(gap, a, b, tolerance, iterations);
  return std::exp(0.5 * (lo + hi));
}

}  // namespace foglab::stats
