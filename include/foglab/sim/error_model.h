// foglab — the truth: the error model of a static gyro and its temperature.
//
// The module `sim` makes synthetic recordings whose parameters are known, so
// every estimator can be tested against the truth. It never depends on the
// estimation code (`model`).
//
// The rate a static gyro outputs (SPEC.md conventions, rate in deg/h):
//
//   y(t) = input_rate + bias + sum_k c_k (T(t) - T_ref)^k      systematic part
//        + white (N) + flicker (B) + random walk (K)
//        + Gauss-Markov (sigma, Tc) + ramp R t + quantisation (Q)
//
// Each sample is the AVERAGE of the continuous process over its sample
// interval tau0 = 1/fs (what an integrating gyro outputs), generated exactly
// in distribution, so that the Allan variance follows IEEE Std 952-1997
// Annex C at every tau = m tau0:
//   AVAR(tau) = R^2 tau^2/2 + K^2 tau/3 + (2 ln2/pi) B^2 + N^2/tau + 3 Q^2/tau^2
//             + sigma^2 (Tc/tau)^2 (2 tau/Tc - 3 + 4 e^(-tau/Tc) - e^(-2 tau/Tc)).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace foglab::sim {

/// IEEE Std 952 noise terms plus the systematic part, in SPEC.md units.
struct ErrorModel {
  double N = 0.0;         ///< white rate noise density [deg/h/sqrt(Hz)] (ARW = N/60 deg/sqrt(h))
  double B = 0.0;         ///< flicker (bias instability) coefficient [deg/h]; plateau 0.664 B
  double K = 0.0;         ///< rate random walk [deg/h/sqrt(s)]
  double R = 0.0;         ///< rate ramp [deg/h/s]
  double Q = 0.0;         ///< angle quantisation [deg/h*s] = quantisation step / sqrt(12)
  double gm_sigma = 0.0;  ///< first-order Gauss-Markov standard deviation [deg/h]
  double gm_tc = 0.0;     ///< its correlation time [s] (> 0 when gm_sigma > 0)
  double bias = 0.0;        ///< constant bias [deg/h]
  double input_rate = 0.0;  ///< constant input rate, e.g. the local Earth-rate component [deg/h]
  /// Temperature sensitivity c_1, c_2, ... [deg/h/degC^k] of the bias, as a
  /// polynomial in (T - T_ref), T_ref the profile's nominal mean temperature.
  std::vector<double> temp_coefs;
};

/// How the temperature evolves during a run.
enum class TemperatureKind {
  constant,  ///< thermostat: start_c plus white jitter of jitter_c
  ramp,      ///< linear from start_c to start_c + span_c over the run (plus jitter)
  file,      ///< a profile (time_s, temperature_c) read from a file, interpolated linearly
};

struct TemperatureProfile {
  TemperatureKind kind = TemperatureKind::constant;
  double start_c = 25.0;   ///< [degC]
  double span_c = 0.0;     ///< [degC] change over the run (ramp)
  double jitter_c = 0.0;   ///< [degC] 1-sigma white jitter of the sensor reading
  std::vector<double> profile_time_s;         ///< [s] for kind = file, increasing
  std::vector<double> profile_temperature_c;  ///< [degC] for kind = file

  /// The nominal mean temperature T_ref about which temp_coefs apply [degC].
  double reference_c(double duration_s) const;
};

/// Parses "const", "const:25", "ramp:10", "ramp:10@20" (span 10 degC from
/// 20 degC) or "file:PATH"; throws UsageError otherwise.
TemperatureProfile parse_temperature(const std::string& text);

}  // namespace foglab::sim
