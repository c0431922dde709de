// foglab — the power series of the output model's temperature and rate terms.
#pragma once

#include <span>

namespace foglab {

/// sum_k c_k x^k for k = 1 .. coefs.size() (c_1 first, no constant term): the
/// temperature and rate polynomials of the output model (sim/rate_table.h,
/// model/calibration.h).
inline double power_series(std::span<const double> coefs, double x) {
  double sum = 0.0, power = 1.0;
  for (const double c : coefs) {
    power *= x;
    sum += c * power;
  }
  return sum;
}

}  // namespace foglab
