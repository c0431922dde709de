// foglab — the built-in demonstration record used when a command is given no
// FILE, so that a new user sees a full result at once.
#pragma once

#include "foglab/io/reader.h"

namespace foglab::io {

/// Parameters of the built-in sample, in foglab's units (docs/conventions.md).
struct BuiltinSample {
  static constexpr double kSampleRateHz = 10.0;     ///< [Hz]
  static constexpr double kDurationS = 4.0 * 3600;  ///< [s] four hours
  static constexpr double kBiasDegH = 1.5;          ///< [deg/h] constant bias
  static constexpr double kWhiteN = 0.05;           ///< N [deg/h/sqrt(Hz)]
  static constexpr double kRandomWalkK = 0.002;     ///< K [deg/h/sqrt(s)]
  static constexpr unsigned kSeed = 20211;
};

/// A static closed-loop-FOG-like rate record: constant bias, white rate noise
/// N and a rate random walk K (IEEE Std 952 model), made deterministically
/// from a fixed seed. Path "(built-in sample)", channel "Y1".
Series builtin_sample();

}  // namespace foglab::io
