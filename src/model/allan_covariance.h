// foglab — covariance of overlapping Allan variance estimates across tau
// (internal to the model module: the noise fit's sandwich covariance).
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <span>

#include "foglab/model/noise_fit.h"

namespace foglab::model::detail {

/// Covariance [(deg/h)^4] of the overlapping Allan variance estimates at the
/// averaging factors `m` (tau = m tau0) of a record of `phase_points` angle
/// samples taken every `tau0_s` seconds, for a Gaussian process with the
/// terms of `model`. The rate ramp R, a deterministic trend, adds nothing.
Eigen::MatrixXd allan_variance_covariance(const NoiseModel& model, double tau0_s,
                                          std::span<const std::int64_t> m,
                                          std::int64_t phase_points);

}  // namespace foglab::model::detail
