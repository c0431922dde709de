// foglab — the lab manual's output model of a rate gyro (its eq. 10, section 2.1), one home
// for the truth that generates rate-table runs (sim/rate_table.h) and the calibration that
// fits them (model/calibration.h):
//
//   u(w, T) = S (1 + sum_k s_k dT^k) [1 + sum_k a_k w^k + (A/2) sign(w)] w + u0 + sum_k b_k dT^k
//
// u the output [LSB], w the rate [deg/s], dT = T - T_ref [degC]; S the scale factor
// [LSB/(deg/s)] at T_ref, s_k its temperature coefficients [1/degC^k], a_k the nonlinearity
// [1/(deg/s)^k], A the asymmetry (S+ - S-)/S, u0 the bias [LSB] at T_ref, b_k its temperature
// coefficients [LSB/degC^k].
#pragma once

#include <span>

namespace foglab {

/// sum_k c_k x^k for k = 1 .. coefs.size() (c_1 first, no constant term).
inline double power_series(std::span<const double> coefs, double x) {
  double sum = 0.0, power = 1.0;
  for (const double c : coefs) {
    power *= x;
    sum += c * power;
  }
  return sum;
}

/// The coefficients of eq. (10) (header comment), viewed, not owned.
struct OutputModelTerms {
  double scale_factor = 0.0;                  ///< S [LSB/(deg/s)]
  std::span<const double> scale_factor_temp;  ///< s_k [1/degC^k]
  std::span<const double> nonlinearity;       ///< a_k [1/(deg/s)^k]
  double asymmetry = 0.0;                     ///< A
  double bias = 0.0;                          ///< u0 [LSB]
  std::span<const double> bias_temp;          ///< b_k [LSB/degC^k]

  /// S(T) / S = 1 + sum s_k dT^k.
  double relative_scale_factor(double dT) const {
    return 1.0 + power_series(scale_factor_temp, dT);
  }
  /// f(w) = sum a_k w^k + (A/2) sign(w).
  double nonlinearity_at(double w) const {
    const double sign = w > 0.0 ? 1.0 : (w < 0.0 ? -1.0 : 0.0);
    return power_series(nonlinearity, w) + 0.5 * asymmetry * sign;
  }
  /// u0(T) = u0 + sum b_k dT^k [LSB].
  double bias_at(double dT) const { return bias + power_series(bias_temp, dT); }
  /// The output u at rate w [deg/s] and dT [degC], eq. (10) without the noise [LSB].
  double output(double w, double dT) const {
    return scale_factor * relative_scale_factor(dT) * (1.0 + nonlinearity_at(w)) * w + bias_at(dT);
  }
};

}  // namespace foglab
