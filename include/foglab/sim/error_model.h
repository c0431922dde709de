// foglab — the truth: the error model of a static gyro and its temperature.
//
// The module `sim` makes synthetic recordings whose parameters are known, so
// every estimator can be tested against the truth. It never depends on the
// estimation code (`model`).
//
// The rate a static gyro outputs (conventions in docs/conventions.md, rate
// in deg/h):
//
//   y(t) = input_rate + bias + sum_k c_k (T(t) - T_ref)^k      systematic part
//        + white (N) + flicker (B) + random walk (K)
//        + Gauss-Markov (sigma, Tc) + ramp R t + quantisation (Q)
//
// The random part is foglab::NoiseModel (core/noise_model.h, which also
// states its Allan variance and PSD). Each sample is the AVERAGE of the
// continuous process over its sample interval tau0 = 1/fs (what an
// integrating gyro outputs), generated exactly in distribution, so that the
// Allan variance of the record follows the model's at every tau = m tau0.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/noise_model.h"
#include "foglab/sim/sensor_output.h"

namespace foglab::sim {

/// The error model of a static gyro: the random part (IEEE Std 952 terms
/// and a Gauss-Markov random bias) and the systematic part.
struct ErrorModel {
  NoiseModel noise;         ///< the random part
  double bias = 0.0;        ///< constant bias [deg/h]
  double input_rate = 0.0;  ///< constant input rate, e.g. the local Earth-rate component [deg/h]
  /// Temperature sensitivity c_1, c_2, ... [deg/h/degC^k] of the bias, as a
  /// polynomial in (T - T_ref), T_ref the profile's nominal mean temperature.
  std::vector<double> temp_coefs;
  /// What the sensor's output chain does after the model: bandwidth,
  /// disturbances, spikes, steps, the output word (sim/sensor_output.h).
  SensorOutput output;
};

/// How the temperature evolves during a run.
enum class TemperatureKind {
  constant,  ///< thermostat: start_c plus white jitter of jitter_c
  ramp,      ///< linear from start_c to start_c + span_c over the run (plus jitter)
  file,      ///< a profile (time_s, temperature_c) read from a file, interpolated linearly
};

/// "constant", "ramp", "file".
std::string_view to_string(TemperatureKind kind);

struct TemperatureProfile {
  TemperatureKind kind = TemperatureKind::constant;
  double start_c = 25.0;   ///< [degC]
  double span_c = 0.0;     ///< [degC] change over the run (ramp)
  double jitter_c = 0.0;   ///< [degC] 1-sigma white jitter of the sensor reading
  /// [degC] the temperature sensor's step: the recorded temperature is
  /// rounded to it, the rate follows the temperature before rounding (0:
  /// not rounded).
  double lsb_c = 0.0;
  std::vector<double> profile_time_s;         ///< [s] for kind = file, increasing
  std::vector<double> profile_temperature_c;  ///< [degC] for kind = file

  /// The nominal mean temperature T_ref about which temp_coefs apply [degC].
  double reference_c(double duration_s) const;
};

/// Parses "const", "const:25", "ramp:10", "ramp:10@20" (span 10 degC from
/// 20 degC) or "file:PATH"; throws UsageError otherwise.
TemperatureProfile parse_temperature(const std::string& text);

}  // namespace foglab::sim
