#include "foglab/stats/confidence.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
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

}  // namespace foglab::stats
